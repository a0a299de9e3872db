// SPDX-License-Identifier: Apache-2.0
#pragma once
// ControlServer: the daemon's control socket (docs/daemon.md §Control
// socket): a Unix stream socket created 0600, JSON lines in, one JSON line
// out per request. Asynchronous on the daemon's io_context, so a slow or
// silent client never holds up the epoch loop: a request line is capped at
// kMaxControlLineBytes, at most kMaxControlSessions clients are served, and
// a client that sends nothing for kControlIdleS is closed. What a request
// means is the handler's (control_commands.hpp).
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>

namespace gnssemu::daemon {

inline constexpr std::size_t kMaxControlLineBytes = 1 << 20;  ///< one request (a scenario's text fits)
inline constexpr std::size_t kMaxControlSessions = 16;       ///< clients served at once
inline constexpr double kControlIdleS = 60.0;                 ///< silence before a client is closed, s

class ControlServer {
public:
  /// Reply (one JSON object, no newline) to one request line. Never throws.
  using Handler = std::function<std::string(std::string_view request)>;

  ControlServer(boost::asio::io_context& io, Handler handler);
  /// Closes every connection and removes the socket file.
  ~ControlServer();
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  /// Create the socket at path (absolute), mode 0600, and accept. A stale
  /// socket file nobody listens on is replaced; a live one, a file that is
  /// not a socket or a missing folder is a gnssemu::Error naming path.
  void start(const std::string& path);
  const std::string& path() const noexcept { return path_; }
  /// Close the listener and every connection; remove the socket file.
  void stop() noexcept;

  struct Shared;  ///< state the connections share with the server

private:
  void accept();

  std::shared_ptr<Shared> shared_;
  std::string path_;
};

}  // namespace gnssemu::daemon
