// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/status_line.hpp"

#include <fmt/format.h>

namespace gnssemu::daemon {

std::string StatusLine::line(const StatusSnapshot& now) {
  const double span_s = now.now_s - last_.now_s;
  const double rate_hz = span_s > 0.0 ? static_cast<double>(now.packets_ok - last_.packets_ok) / span_s : 0.0;
  std::string out = now.fix_type >= 2   ? fmt::format("fix {}D, {} sats", now.fix_type, now.sats_used)
                    : now.fix_type == 1 ? fmt::format("dead reckoning, {} sats tracked", now.sats_tracked)
                                        : fmt::format("no fix, {} sats tracked", now.sats_tracked);
  if (!now.driver.empty()) {
    out += fmt::format("; truth {:.1f} Hz from '{}'{}", rate_hz, now.driver, now.driver_fresh ? "" : " (stale)");
  } else if (now.demo) {
    out += "; demo circle (no truth yet)";
  } else {
    out += "; no truth yet";
  }
  if (now.vehicles > 1) out += fmt::format(" ({} vehicles)", now.vehicles);
  out += fmt::format("; {} drops", now.drops - last_.drops);
  if (span_s > 0.0 && last_.now_s > 0.0) out += fmt::format(" in {:.0f} s", span_s);
  out += fmt::format("; {} epochs", now.epochs);
  if (!now.ports.empty()) {
    out += "; readers:";
    bool first = true;
    for (const StatusSnapshot::Port& p : now.ports) {
      out += fmt::format("{} {} {}", first ? "" : ",", p.name, p.readers < 0 ? std::string("?") : std::to_string(p.readers));
      first = false;
    }
  }
  last_ = now;
  return out;
}

}  // namespace gnssemu::daemon
