// SPDX-License-Identifier: Apache-2.0
#pragma once
// StatusServer: the status page on loopback HTTP (docs/status.md). Boost.Beast
// on the daemon's io_context, so it shares the one thread with the epoch
// loop and never blocks it: every socket operation is asynchronous, each
// request must arrive within kRequestTimeoutS with headers under
// kMaxHeaderBytes, the event streams (server-sent events, one per epoch)
// have a bounded backlog per client and a client that falls behind is
// dropped, and at most kMaxSessions connections are served at once.
//   GET /, /status.js, ... the page (embedded assets, daemon/status/web_assets.hpp)
//   GET /api/status[?history=N]  StatusProducer::write_json
//   GET /api/status?vehicle=ID[&receiver=NAME]  a fleet's receiver (set_selector)
//   GET /api/receivers           the fleet's receivers, [{"vehicle":..,"receiver":..}] (set_selector)
//   GET /api/overview[?limit=N&offset=M]  one row per receiver (set_roster, overview.hpp)
//   GET /api/events              text/event-stream: one status (history=1) per epoch
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "daemon/status/status_producer.hpp"

namespace gnssemu::daemon {

inline constexpr double kRequestTimeoutS = 10.0;        ///< whole request (slow senders are cut off)
inline constexpr std::size_t kMaxHeaderBytes = 8192;    ///< request line + headers
inline constexpr std::size_t kMaxSessions = 64;         ///< connections served at once
inline constexpr std::size_t kMaxEventBacklogBytes = 256 * 1024;  ///< per event stream, then dropped
inline constexpr double kEventWriteTimeoutS = 10.0;     ///< one event write, then dropped

struct StatusServerStats {
  uint64_t requests = 0;        ///< answered requests (any status)
  uint64_t bad_requests = 0;    ///< unparsable, too large, timed out, wrong method
  uint64_t sessions_refused = 0;  ///< over kMaxSessions
  uint64_t streams_dropped = 0;   ///< event streams dropped for falling behind
  std::size_t sessions = 0;     ///< open now
  std::size_t streams = 0;      ///< event streams open now
};

class StatusServer {
public:
  /// producer outlives the server's use of it (stop() ends that).
  StatusServer(boost::asio::io_context& io, const StatusProducer& producer);
  ~StatusServer();
  StatusServer(const StatusServer&) = delete;
  StatusServer& operator=(const StatusServer&) = delete;

  /// Listen on bind:port (port 0: any free one) and start accepting.
  /// Throws gnssemu::Error when the address is bad or cannot be bound.
  void start(const std::string& bind, uint16_t port);
  boost::asio::ip::tcp::endpoint local_endpoint() const;
  /// The producer of a fleet's receiver (receiver "": the vehicle's first),
  /// null when there is none; outlives the server's use as the producer does.
  using Selector = std::function<const StatusProducer*(std::string_view vehicle, std::string_view receiver)>;
  /// The receivers as a JSON array of {"vehicle","receiver"} objects.
  using Lister = std::function<std::string()>;
  /// /api/status?vehicle= picks with selector, /api/receivers lists with
  /// lister (without them: 404).
  void set_selector(Selector selector, Lister lister);
  /// Fills out with every receiver, in the daemon's order (the producers'
  /// lifetime rule as above).
  using Roster = std::function<void(std::vector<OverviewEntry>& out)>;
  /// /api/overview lists the roster's receivers (without one: 404).
  void set_roster(Roster roster);
  /// The producer /api/status without a vehicle reads (the first receiver
  /// went with its vehicle in a reload); the same lifetime rule.
  void set_producer(const StatusProducer& producer) noexcept;
  /// A new epoch is in the producer: queue it on every event stream. Never
  /// blocks; a stream whose backlog would pass kMaxEventBacklogBytes is closed.
  void publish() noexcept;
  /// Close the listener and every connection.
  void stop() noexcept;
  StatusServerStats stats() const noexcept;

  struct Shared;  ///< state the connections share with the server (outlives both)

private:
  void accept();

  std::shared_ptr<Shared> shared_;
};

}  // namespace gnssemu::daemon
