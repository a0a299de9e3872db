// SPDX-License-Identifier: Apache-2.0
#pragma once
// [status]: the daemon's live status page on HTTP (docs/status.md).
#include <cstdint>
#include <optional>
#include <string>

#include "core/common/range.hpp"
#include "core/common/violation.hpp"

namespace gnssemu::config {

struct StatusConfig {
  /// Address the page listens on (IPv4 or IPv6). Loopback by default: the
  /// page shows where the vehicle is; any other address is logged as a
  /// warning at start-up.
  std::string bind = "127.0.0.1";
  /// TCP port, integer [0, 65535]; 0: no status page. A port taken at start-up
  /// moves the page to a free one (logged as a warning).
  uint16_t port = 5580;
  /// true: any free port instead of port (printed at start-up), e.g. for
  /// several daemons on one machine and for tests; needs port > 0.
  bool free_port = false;
};

/// free_port asks for a page that port = 0 turns off.
std::optional<Violation> check_status(const StatusConfig& s);

}  // namespace gnssemu::config
