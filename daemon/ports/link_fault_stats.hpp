// SPDX-License-Identifier: Apache-2.0
#pragma once
// LinkFaultStats: what the link faults did to one port (docs/faults.md §5),
// counted by LinkFaults and shown per port by the status (docs/status.md).
#include <cstdint>

namespace gnssemu::daemon {

/// Totals since the port's channel opened (a reload that reopens the port starts them again).
struct LinkFaultStats {
  std::uint64_t bytes_lost = 0;          ///< byte_loss: bytes taken off the line (epochs and replies)
  std::uint64_t messages_corrupted = 0;  ///< corrupt: messages sent with a wrong checksum
  std::uint64_t messages_dropped = 0;    ///< drop: whole messages not sent
  std::uint64_t epochs_delayed = 0;      ///< latency: epochs held back
  std::uint64_t epochs_frozen = 0;       ///< freeze: epochs replaced by the one before the freeze
  std::uint64_t epochs_stopped = 0;      ///< stop: epochs not sent
  std::uint64_t replies_stopped = 0;     ///< stop: replies (ACK, poll answers) not sent
  std::uint64_t epochs_skipped = 0;      ///< rate: epochs not due at the lowered rate
  std::uint64_t epochs_wrong_fix = 0;    ///< wrong_fix: epochs composed with another fix type
};

}  // namespace gnssemu::daemon
