// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu ctl --socket PATH status | inject FILE | clear`: one request to a
// running gnssemud's control socket (docs/daemon.md §Control socket), its
// JSON reply line on out.
#include <ostream>
#include <string>

namespace gnssemu::cli {

struct CtlArgs {
  std::string socket;        ///< the daemon's [control] socket
  std::string command;       ///< status, inject, clear
  std::string file;          ///< inject: scenario file (start times from now)
  double timeout_s = 10.0;   ///< connect + reply, s (0, 600]
  std::string vehicle;       ///< --vehicle: its receivers only; "" every receiver
  std::string receiver;      ///< --receiver (with vehicle): that one only
};

/// Exit status: 0 the daemon said ok; 1 it refused (its error on err), the
/// file could not be read, or the socket did not answer.
int run_ctl(const CtlArgs& a, std::ostream& out, std::ostream& err);

}  // namespace gnssemu::cli
