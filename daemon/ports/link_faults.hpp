// SPDX-License-Identifier: Apache-2.0
#pragma once
// LinkFaults: a scenario's port events (type = "port", docs/faults.md "Link
// faults") acting on the bytes of one output, as a bad line, a stuck
// firmware or a slow bridge would: byte loss, corrupted checksums, dropped
// messages, latency, a frozen epoch, a stopped output, a lower rate, a wrong
// fix type. The daemon hands every epoch's fault status to each channel
// (after the receiver step); the channel asks this model what to send.
// Draws are counter-based (world::CounterRng keyed by the world's seed, the
// output index, the epoch and the byte or message), so a lockstep run
// repeats byte for byte. Never throws; no allocation after construction.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/faults/fault_event.hpp"
#include "core/faults/fault_stage.hpp"
#include "core/protocol/nmea/reported_fix.hpp"
#include "core/world/random.hpp"
#include "daemon/ports/link_fault_stats.hpp"

namespace gnssemu::daemon {

/// The port events active on one output at one epoch, combined: several
/// events of a kind act together (independent probabilities, latencies in
/// series, the lowest rate, the latest-starting wrong fix type).
struct LinkFaultSet {
  bool stop = false;
  bool freeze = false;
  double byte_loss = 0.0;  ///< probability per byte, [0, 1]
  double corrupt = 0.0;    ///< probability per message, [0, 1]
  double drop = 0.0;       ///< probability per message, [0, 1]
  double latency_s = 0.0;  ///< added delay, s (>= 0)
  double rate_hz = 0.0;    ///< output rate, Hz (0: the navigation rate)
  protocol::FixOverride fix_type;  ///< reported instead of the receiver's
  bool rtcm_outage = false;  ///< RTCM 3 from the host is lost before the chip
  bool rtcm_stale = false;   ///< RTCM 3 arrives but the corrections stay as they were
  bool any() const noexcept {
    return stop || freeze || byte_loss > 0.0 || corrupt > 0.0 || drop > 0.0 || latency_s > 0.0 || rate_hz > 0.0 ||
           fix_type.has_value() || rtcm_outage || rtcm_stale;
  }
};

/// The port events among status active on output now (an event without
/// `output` acts on every output), combined. Ramps are at their current value.
LinkFaultSet active_link_faults(std::span<const faults::FaultStatus> status, std::size_t output) noexcept;

/// Scenario checks the fault stage cannot make (it does not know the
/// daemon's outputs): each port event names an existing output (index <
/// output_count) and gives the parameter its fault needs (probability,
/// latency_ms, rate_hz, fix_type). Returns "file:line: reason" for the first
/// problem, or nothing. For the scenario loader and `ctl inject`.
std::optional<std::string> check_port_events(std::span<const faults::FaultEvent> events, std::size_t output_count,
                                             std::string_view file = "scenario");

/// The same events against a reloaded configuration (docs/daemon.md
/// §Reload): running and reloaded are the [[output]] names in order. A port
/// event acts on the running output at its index until a restart; returns
/// "file:line: reason" for each event whose index the reloaded file gives
/// no output or another one (removed, renamed or moved: a restart would
/// refuse the event or put it on another port). reloaded_file names the file.
std::vector<std::string> check_port_events_on_reload(std::span<const faults::FaultEvent> events,
                                                     std::span<const std::string> running,
                                                     std::span<const std::string> reloaded, std::string_view file,
                                                     std::string_view reloaded_file);

/// Make the checksum of one framed message wrong so a parser rejects exactly
/// it: a UBX frame's CK_B is inverted, an NMEA sentence's *hh becomes
/// another valid hex value. Anything else is left as it is (returns false).
bool break_checksum(std::span<char> message) noexcept;

class LinkFaults {
public:
  /// What leaves the port's firmware this epoch.
  enum class Release : std::uint8_t {
    kCurrent,  ///< the epoch just composed
    kHeld,     ///< the epoch held when a freeze began (held())
    kNothing,  ///< stopped, or not due at a lowered rate
  };

  /// output: the port's [[output]] index (selects its events, keys its draws).
  explicit LinkFaults(std::size_t output);

  /// The world's seed (`[receiver.errors] seed`): draws repeat for a seed.
  void set_seed(std::uint64_t seed) noexcept;
  /// Take this epoch's fault status (FaultStage::status()); an empty span
  /// (no fault stage) clears every link fault.
  void update(std::span<const faults::FaultStatus> status) noexcept;
  const LinkFaultSet& active() const noexcept { return set_; }

  /// Stop, rate and freeze for this epoch (navigation period period_s, s).
  /// last: the bytes the port sent at its last release (kept when a freeze
  /// begins), with its message ends.
  Release release(double period_s, std::string_view last, std::span<const std::size_t> last_ends) noexcept;
  /// The epoch held by a freeze and its message ends.
  std::string_view held() const noexcept { return held_; }
  std::span<const std::size_t> held_ends() const noexcept { return held_ends_; }

  /// drop / corrupt draws for message index of epoch (counted when true).
  bool drops(std::uint64_t epoch, std::size_t index) noexcept;
  bool corrupts(std::uint64_t epoch, std::size_t index) noexcept;

  /// Copy in to out without the bytes the line loses this epoch (byte_loss;
  /// each byte drawn by its index), with ends moved to match (messages lost
  /// whole leave no end). reply: a reply's bytes (its own draws, counted by
  /// the reply number). Returns the bytes lost. out, out_ends are replaced.
  std::size_t lose_bytes(std::uint64_t epoch, bool reply, std::string_view in, std::span<const std::size_t> ends,
                         std::string& out, std::vector<std::size_t>& out_ends) noexcept;

  void count_wrong_fix() noexcept { ++stats_.epochs_wrong_fix; }
  void count_delayed() noexcept { ++stats_.epochs_delayed; }
  void count_stopped_reply() noexcept { ++stats_.replies_stopped; }
  const LinkFaultStats& stats() const noexcept { return stats_; }

private:
  std::size_t output_;
  world::CounterRng rng_{1};
  LinkFaultSet set_;
  std::string held_;                    ///< reserved MessageList::kMaxBytes
  std::vector<std::size_t> held_ends_;  ///< reserved MessageList::kMaxMessages
  bool holding_ = false;                ///< a freeze holds held_
  double rate_phase_ = 1.0;             ///< epochs due at the lowered rate (>= 1: one is due)
  std::uint64_t replies_ = 0;           ///< replies seen (their draws' key)
  LinkFaultStats stats_;
};

}  // namespace gnssemu::daemon
