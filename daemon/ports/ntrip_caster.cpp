// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/ntrip_caster.hpp"

#include <array>
#include <cctype>

#include <boost/asio/write.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"

namespace gnssemu::daemon {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

constexpr std::size_t kMaxClients = 16;
constexpr std::size_t kMaxHeadBytes = 4096;       ///< a request head longer than this is refused
constexpr std::size_t kMaxQueuedBytes = 64 * 1024; ///< per client: about 6 s of MSM7 at 10 Hz

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// The value of header name (case-insensitive) in head; "" when absent.
std::string header(std::string_view head, std::string_view name) {
  const std::string h = lower(head);
  const std::string key = "\r\n" + lower(name) + ":";
  const std::size_t at = h.find(key);
  if (at == std::string::npos) return {};
  std::size_t b = at + key.size();
  const std::size_t e = head.find("\r\n", b);
  while (b < head.size() && head[b] == ' ') ++b;
  return std::string(head.substr(b, (e == std::string_view::npos ? head.size() : e) - b));
}

}  // namespace

std::string sourcetable_str(const config::BaseStation& base) {
  const config::BaseConfig& b = base.config();
  std::string systems;
  bool l2 = false;
  for (const config::BaseMessage& m : b.messages) {
    const char* name = nullptr;
    switch (m.number / 10) {
      case 107: name = "GPS"; break;
      case 108: name = "GLO"; break;
      case 109: name = "GAL"; break;
      case 111: name = "QZS"; break;
      case 112: name = "BDS"; break;
      default: break;
    }
    if (name == nullptr) continue;
    if (!systems.empty()) systems.push_back('+');
    systems.append(name);
  }
  for (int i = 0; i < base.raw().num_meas; ++i) l2 = l2 || signal_info(base.raw().meas[static_cast<std::size_t>(i)].signal).band == 1;
  // 1 mountpoint 2 identifier 3 format 4 details 5 carrier 6 nav-system 7 network 8 country 9 lat 10 lon 11 nmea
  // 12 solution 13 generator 14 compression 15 auth 16 fee 17 bitrate 18 misc (BKG STR, 19 fields with "STR").
  return fmt::format("STR;{};gnssemu base {};RTCM 3.3;{};{};{};gnssemu;XXX;{:.2f};{:.2f};0;0;gnssemu;none;{};N;0;",
                     b.ntrip.mountpoint, b.station_id, base.format_details(), l2 ? 2 : 1, systems,
                     b.position.lat_rad * kRadToDeg, b.position.lon_rad * kRadToDeg,
                     b.ntrip.user.empty() ? "N" : "B");
}

std::string base64(std::string_view text) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < text.size(); i += 3) {
    const unsigned v = static_cast<unsigned char>(text[i]) << 16 | static_cast<unsigned char>(text[i + 1]) << 8 |
                       static_cast<unsigned char>(text[i + 2]);
    for (int k = 18; k >= 0; k -= 6) out += kAlphabet[(v >> k) & 63u];
  }
  if (i < text.size()) {
    unsigned v = static_cast<unsigned char>(text[i]) << 16;
    if (i + 1 < text.size()) v |= static_cast<unsigned char>(text[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63u];
    out += kAlphabet[(v >> 12) & 63u];
    out += i + 1 < text.size() ? kAlphabet[(v >> 6) & 63u] : '=';
    out += '=';
  }
  return out;
}

NtripCaster::Answer NtripCaster::answer(std::string_view head, const config::NtripCasterConfig& cfg,
                                        std::string_view str) {
  const bool v2 = lower(header(head, "Ntrip-Version")).find("ntrip/2.0") != std::string::npos;
  const std::string_view proto = v2 ? "HTTP/1.1" : "HTTP/1.0";
  const std::string server = "Server: NTRIP gnssemu\r\n";
  const auto refuse = [&](std::string_view status) {
    return Answer{fmt::format("{} {}\r\n{}{}Connection: close\r\n\r\n", proto, status, server,
                              v2 ? "Ntrip-Version: Ntrip/2.0\r\n" : ""),
                  false, false};
  };
  const std::size_t eol = head.find("\r\n");
  const std::string_view line = head.substr(0, eol);
  if (line.substr(0, 4) != "GET " || line.find(" HTTP/1.") == std::string_view::npos) return refuse("400 Bad Request");
  std::string_view path = line.substr(4, line.find(' ', 4) - 4);
  if (!path.empty() && path.front() == '/') path.remove_prefix(1);
  const std::string table = std::string(str) + "\r\nENDSOURCETABLE\r\n";
  const auto sourcetable = [&] {
    if (v2) {
      return Answer{fmt::format("HTTP/1.1 200 OK\r\nNtrip-Version: Ntrip/2.0\r\n{}Content-Type: gnss/sourcetable\r\n"
                                "Content-Length: {}\r\nConnection: close\r\n\r\n{}",
                                server, table.size(), table),
                    false, false};
    }
    return Answer{fmt::format("SOURCETABLE 200 OK\r\n{}Content-Type: text/plain\r\nContent-Length: {}\r\n"
                              "Connection: close\r\n\r\n{}",
                              server, table.size(), table),
                  false, false};
  };
  if (path.empty()) return sourcetable();
  if (path != cfg.mountpoint) return v2 ? refuse("404 Not Found") : sourcetable();
  if (!cfg.user.empty()) {
    const std::string want = "basic " + lower(base64(cfg.user + ":" + cfg.password));
    if (lower(header(head, "Authorization")) != want) {
      Answer a = refuse("401 Unauthorized");
      a.text.insert(a.text.size() - 2, fmt::format("WWW-Authenticate: Basic realm=\"/{}\"\r\n", cfg.mountpoint));
      return a;
    }
  }
  if (v2) {
    return Answer{fmt::format("HTTP/1.1 200 OK\r\nNtrip-Version: Ntrip/2.0\r\n{}Content-Type: gnss/data\r\n"
                              "Cache-Control: no-store, no-cache, max-age=0\r\nConnection: close\r\n"
                              "Transfer-Encoding: chunked\r\n\r\n",
                              server),
                  true, true};
  }
  return Answer{"ICY 200 OK\r\n", true, false};
}

struct NtripCaster::Client {
  explicit Client(asio::io_context& io) : socket(io) {}
  tcp::socket socket;
  std::string head;
  std::array<char, 512> rx{};
  std::string queue;    ///< waiting to be written
  std::string writing;  ///< being written
  bool data = false;
  bool chunked = false;
  bool closing = false;
};

NtripCaster::NtripCaster(asio::io_context& io, const config::NtripCasterConfig& cfg, std::string str)
    : io_(io), cfg_(cfg), str_(std::move(str)), acceptor_(io) {
  boost::system::error_code ec;
  const tcp::endpoint ep(asio::ip::address_v4::loopback(), static_cast<unsigned short>(cfg.port));
  acceptor_.open(ep.protocol(), ec);
  if (!ec) acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) acceptor_.bind(ep, ec);
  if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw Error(fmt::format("[base.ntrip]: cannot listen on 127.0.0.1:{}: {}", cfg.port, ec.message()));
  port_ = acceptor_.local_endpoint(ec).port();
  accept();
}

NtripCaster::~NtripCaster() {
  boost::system::error_code ec;
  acceptor_.close(ec);
  for (auto& c : clients_) c->socket.close(ec);
}

int NtripCaster::clients() const noexcept {
  int n = 0;
  for (const auto& c : clients_) n += c->data ? 1 : 0;
  return n;
}

void NtripCaster::accept() {
  auto c = std::make_shared<Client>(io_);
  acceptor_.async_accept(c->socket, [this, c](const boost::system::error_code& ec) {
    if (ec == asio::error::operation_aborted || !acceptor_.is_open()) return;
    if (!ec) {
      if (clients_.size() >= kMaxClients) {
        boost::system::error_code cec;
        c->socket.close(cec);
        ++stats_.refused;
      } else {
        clients_.push_back(c);
        read_head(c);
      }
    }
    accept();
  });
}

void NtripCaster::read_head(const std::shared_ptr<Client>& c) {
  c->socket.async_read_some(asio::buffer(c->rx), [this, c](const boost::system::error_code& ec, std::size_t n) {
    if (ec == asio::error::operation_aborted) return;
    if (ec) {
      drop(c);
      return;
    }
    if (c->data) {  // NMEA GGA from a rover: not needed by a fixed base; read and ignore
      read_head(c);
      return;
    }
    c->head.append(c->rx.data(), n);
    const std::size_t end = c->head.find("\r\n\r\n");
    if (end == std::string::npos && c->head.size() < kMaxHeadBytes) {
      read_head(c);
      return;
    }
    const Answer a = end == std::string::npos ? Answer{"HTTP/1.0 400 Bad Request\r\n\r\n", false, false}
                                              : answer(std::string_view(c->head).substr(0, end + 2), cfg_, str_);
    if (a.data) {
      ++stats_.clients_served;
      spdlog::info("ntrip: client on /{} ({})", cfg_.mountpoint, a.chunked ? "v2" : "v1");
    } else if (a.text.find("SOURCETABLE") == 0 || a.text.find("gnss/sourcetable") != std::string::npos) {
      ++stats_.sourcetables;
    } else {
      ++stats_.refused;
      spdlog::info("ntrip: refused: {}", a.text.substr(0, a.text.find("\r\n")));
    }
    c->data = a.data;
    c->chunked = a.chunked;
    c->closing = !a.data;
    c->queue = a.text;
    flush(c);
    if (a.data) read_head(c);
  });
}

void NtripCaster::publish(std::string_view bytes) {
  if (bytes.empty()) return;
  for (auto& c : clients_) {
    if (!c->data) continue;
    const std::string chunk_head = c->chunked ? fmt::format("{:X}\r\n", bytes.size()) : std::string();
    if (c->queue.size() + bytes.size() + chunk_head.size() + 2 > kMaxQueuedBytes) {
      ++stats_.dropped_epochs;  // a client that does not read loses epochs, not the others
      continue;
    }
    c->queue += chunk_head;
    c->queue.append(bytes);
    if (c->chunked) c->queue += "\r\n";
    flush(c);
  }
}

void NtripCaster::flush(const std::shared_ptr<Client>& c) {
  if (!c->writing.empty() || c->queue.empty()) return;
  c->writing.swap(c->queue);
  asio::async_write(c->socket, asio::buffer(c->writing), [this, c](const boost::system::error_code& ec, std::size_t) {
    if (ec == asio::error::operation_aborted) return;
    c->writing.clear();
    if (ec) {
      drop(c);
      return;
    }
    if (!c->queue.empty()) {
      flush(c);
    } else if (c->closing) {
      drop(c);
    }
  });
}

void NtripCaster::drop(const std::shared_ptr<Client>& c) {
  boost::system::error_code ec;
  c->socket.shutdown(tcp::socket::shutdown_both, ec);
  c->socket.close(ec);
  clients_.remove(c);
}

}  // namespace gnssemu::daemon
