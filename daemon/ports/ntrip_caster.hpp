// SPDX-License-Identifier: Apache-2.0
#pragma once
// A one-mountpoint NTRIP caster on loopback: what an NTRIP client (RTKLIB
// str2str, gpsd, pygnssutils, a rover's firmware) connects to for the
// [base]'s RTCM 3 stream (docs/base-station.md "NTRIP"). NTRIP v1 (RTKLIB's
// caster and client, rtk-raw.md §3): `GET /MOUNT HTTP/1.0` -> `ICY 200 OK`
// then raw bytes; `GET /` or an unknown mountpoint -> `SOURCETABLE 200 OK`
// with one STR record; bad credentials -> `HTTP/1.0 401 Unauthorized`.
// NTRIP v2 (`Ntrip-Version: Ntrip/2.0`, GPSD's and pygnssutils' clients):
// `HTTP/1.1 200 OK` and chunked transfer, sourcetable as gnss/sourcetable,
// unknown mountpoint -> 404, bad credentials -> 401. Several clients at
// once; a client that does not read loses epochs (counted), never the loop.
#include <cstdint>
#include <list>
#include <memory>
#include <string>
#include <string_view>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "config/setup/base_station.hpp"

namespace gnssemu::daemon {

struct NtripStats {
  std::uint64_t clients_served = 0;   ///< data connections accepted
  std::uint64_t sourcetables = 0;     ///< sourcetable answers
  std::uint64_t refused = 0;          ///< 401, 404, 400 answers
  std::uint64_t dropped_epochs = 0;   ///< epochs a slow client lost (its queue full)
};

class NtripCaster {
public:
  /// str: the sourcetable's STR record (without CR LF). Listens on
  /// 127.0.0.1:cfg.port at once; throws gnssemu::Error when it cannot.
  NtripCaster(boost::asio::io_context& io, const config::NtripCasterConfig& cfg, std::string str);
  ~NtripCaster();
  NtripCaster(const NtripCaster&) = delete;
  NtripCaster& operator=(const NtripCaster&) = delete;

  /// Queues one epoch's bytes to every data client (never blocks).
  void publish(std::string_view bytes);
  int port() const noexcept { return port_; }
  int clients() const noexcept;
  const NtripStats& stats() const noexcept { return stats_; }

  /// The caster's answer to a request head (request line and headers up to
  /// the blank line) and whether data follows it (the connection then stays
  /// open) and as v2 chunks. Pure: the unit under test.
  struct Answer {
    std::string text;
    bool data = false;
    bool chunked = false;
  };
  static Answer answer(std::string_view head, const config::NtripCasterConfig& cfg, std::string_view str);

private:
  struct Client;
  void accept();
  void read_head(const std::shared_ptr<Client>& c);
  void flush(const std::shared_ptr<Client>& c);
  void drop(const std::shared_ptr<Client>& c);

  boost::asio::io_context& io_;
  config::NtripCasterConfig cfg_;
  std::string str_;
  boost::asio::ip::tcp::acceptor acceptor_;
  int port_ = 0;
  std::list<std::shared_ptr<Client>> clients_;
  NtripStats stats_;
};

/// The sourcetable's STR record of base (BKG's 19 fields, rtk-raw.md §3),
/// without CR LF.
std::string sourcetable_str(const config::BaseStation& base);

/// Base64 of text (RFC 4648 §4), for HTTP Basic credentials.
std::string base64(std::string_view text);

}  // namespace gnssemu::daemon
