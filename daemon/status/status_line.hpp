// SPDX-License-Identifier: Apache-2.0
#pragma once
// StatusLine: the one-line health summary gnssemud logs every minute, on
// SIGUSR1/SIGUSR2 and sends as the systemd STATUS= (docs/daemon.md §Logs):
//   fix 3D, 9 sats; truth 10.0 Hz from 'ego' (2 vehicles); 0 drops; readers: gps0 1, tcp 2
// Counters are cumulative; the line reports the rates since the last one.
#include <cstdint>
#include <string>
#include <vector>

namespace gnssemu::daemon {

struct StatusSnapshot {
  double now_s = 0.0;            ///< monotonic time, s
  int fix_type = 0;              ///< 0 none, 1 dead reckoning (coasting), 2 2D, 3 3D
  int sats_used = 0;
  int sats_tracked = 0;
  uint64_t packets_ok = 0;       ///< truth packets accepted (cumulative)
  uint64_t drops = 0;            ///< truth packets dropped (cumulative)
  uint64_t epochs = 0;           ///< epochs computed (cumulative)
  std::string driver;            ///< driving vehicle id; "" none yet
  bool driver_fresh = false;     ///< its truth is live
  bool demo = false;             ///< the demo circle drives the receiver
  std::size_t vehicles = 0;      ///< vehicles heard
  struct Port {
    std::string name;
    int readers = -1;            ///< OutputPort::readers()
  };
  std::vector<Port> ports;
};

class StatusLine {
public:
  /// The line for now against the previous snapshot (rates over the time
  /// between them; the first line: since start, now_s of 0).
  std::string line(const StatusSnapshot& now);

private:
  StatusSnapshot last_;
};

}  // namespace gnssemu::daemon
