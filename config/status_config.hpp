#pragma once
// [status]: the daemon's live status page on HTTP (docs/status.md).
#include <cstdint>
#include <string>

#include "core/common/range.hpp"

namespace gnssemu::config {

struct StatusRanges {
  static constexpr Range port{0.0, 65535.0, ""};  ///< integer; 0: off
};

struct StatusConfig {
  /// Address the page listens on. Loopback by default: the page shows where
  /// the vehicle is; anything else is logged as a warning at start-up.
  std::string bind = "127.0.0.1";
  /// TCP port (StatusRanges); 0: no status page.
  uint16_t port = 5580;
  /// true: listen on any free port instead of port (printed at start-up),
  /// e.g. for several daemons on one machine and for tests.
  bool free_port = false;
};

}  // namespace gnssemu::config
