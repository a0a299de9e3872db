// SPDX-License-Identifier: Apache-2.0
#pragma once
// [control]: the daemon's control socket (docs/daemon.md §Control socket):
// JSON lines over a Unix socket for status and live fault injection.
#include <cstddef>
#include <string>

namespace gnssemu::config {

/// Longest socket path: sockaddr_un.sun_path holds 108 bytes with the NUL (unix(7)).
inline constexpr std::size_t kMaxSocketPathBytes = 107;

struct ControlConfig {
  /// Absolute path of the Unix socket (created 0600, removed at exit);
  /// empty: no control socket.
  std::string socket;
};

}  // namespace gnssemu::config
