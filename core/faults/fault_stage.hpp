// SPDX-License-Identifier: Apache-2.0
#pragma once
// FaultStage: the faults of a scenario applied to the world's observables
// before the receiver sees them (DESIGN.md §1 step 6). Faults act on the
// signals and measurements only — C/N0, pseudorange, Doppler, the broadcast
// ephemeris the receiver decodes, the antenna — so the receiver's own
// tracking, solver, fault exclusion, accuracy estimates and flags react by
// themselves. Pure and deterministic for a seed; apply() never throws and
// never allocates (events are held in storage reserved at construction).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/common/gnss_signals.hpp"
#include "core/common/vec3.hpp"
#include "core/faults/fault_event.hpp"
#include "core/faults/interference.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/signal/dll_jitter.hpp"
#include "core/signal/link_budget.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/measurement/carrier.hpp"
#include "core/world/measurement/measurement_noise.hpp"
#include "core/world/observables.hpp"
#include "core/world/random.hpp"
#include "core/world/truth.hpp"

namespace gnssemu::faults {

/// What the stage needs of the world it edits.
struct FaultContext {
  std::uint64_t seed = 1;           ///< the world's seed (the stage draws its own streams from it)
  signal::LinkBudgetConfig link;    ///< noise floor (N0) and antenna pattern
  world::MeasurementNoise noise;    ///< code and Doppler noise versus C/N0, carrier loops (slips)
};

/// One event's state at the last epoch, for status displays.
struct FaultStatus {
  const FaultEvent* event = nullptr;
  bool active = false;
  double elapsed_s = 0.0;           ///< since the event's start (negative: pending)
};

/// Per-epoch summary of what the faults did (analysis, tools, status).
struct FaultEffects {
  double jammer_dbw = -1000.0;      ///< total jammer power at the antenna, dBW (-1000: none)
  double agc_rise_db = 0.0;         ///< in-band power rise from interference, dB
  int captured = 0;                 ///< satellites captured by a spoofer
  Enu spoof_offset_m;               ///< false position minus truth, ENU, m
  double spoof_clock_m = 0.0;       ///< false clock offset, m
};

class FaultStage {
public:
  /// Largest number of events held (scenario + injected).
  static constexpr std::size_t kMaxEvents = 64;

  /// Throws gnssemu::Error for more than kMaxEvents or an event failing
  /// check_event (naming its line when it has one).
  FaultStage(const FaultContext& context, std::span<const FaultEvent> events);

  /// The world's models changed (a receiver restart with a new
  /// configuration): use these from the next epoch on; events, time line
  /// and spoofer state stay. Setup only; throws gnssemu::Error on an
  /// invalid context (and keeps the old one).
  void set_context(const FaultContext& context);

  /// Edit obs for the epoch at t (GPS) with the vehicle truth (position for
  /// a placed jammer). The first call fixes time zero of the scenario.
  void apply(const time::GpsTime& t, const world::Truth& truth, world::Observables& obs) noexcept;

  /// Add events whose start_s counts from now (the last epoch applied, or
  /// time zero before the first). Throws gnssemu::Error (and adds nothing)
  /// on a bad event or when storage is full.
  void inject(std::span<const FaultEvent> events);
  /// Remove every event; the next epoch is fault free (the loops a spoofer
  /// moved lose lock there, as at the spoofer's own end).
  void clear() noexcept;

  /// Every event with its state at the last epoch (a plain list).
  std::span<const FaultStatus> status() noexcept;
  /// Number of events active at the last epoch.
  int active_count() const noexcept;
  const FaultEffects& effects() const noexcept { return effects_; }
  bool empty() const noexcept { return events_.empty(); }
  /// Events held (active, pending or ended).
  std::size_t event_count() const noexcept { return events_.size(); }

private:
  /// Slips the fault stage made a carrier loop take: they stay in its phase
  /// until the loop loses lock (not received, carrier invalid, or a missed
  /// epoch), as a real loop's do. Per satellite and band.
  struct CarrierSlips {
    double cycles = 0.0;         ///< sum of the slips, cycles
    std::uint32_t count = 0;     ///< slips (each a carrier discontinuity)
    bool half = false;           ///< odd number of half-cycle slips: the data sign flipped
    std::uint64_t last_epoch = 0;///< the stage's epoch it was last carried
  };
  struct SpoofState {
    bool started = false;
    Enu offset_m;                   ///< false minus true position, ENU
    Enu rate_m_s;                   ///< its rate
    double clock_m = 0.0, clock_rate_m_s = 0.0;
    double drag_s = 0.0;            ///< time dragged so far, s
    std::array<bool, kNumSats> captured{};
    bool aligned = true;            ///< the spoofed signals start where the authentic ones are
  };

  void satellite_fault(const FaultEvent& e, double f, double since_s, world::Observables& obs) noexcept;
  /// Lock breaks where the satellite faults' total shift jumped since the last epoch.
  void satellite_steps(world::Observables& obs) noexcept;
  void sky_block(const FaultEvent& e, double f, world::Observables& obs) noexcept;
  void outage(const FaultEvent& e, world::Observables& obs) noexcept;
  void spoofer(const FaultEvent& e, SpoofState& s, double f, double dt_s, world::Observables& obs) noexcept;
  double jammer_power_w(const FaultEvent& e, double f, const world::Truth& truth, bool* cw) const noexcept;
  /// Lower a satellite's C/N0 to cn0_dbhz, adding the code and Doppler noise
  /// and the carrier slips the lower C/N0 brings (the loops' jitter
  /// difference), and drop it below 0 dB-Hz.
  void degrade(world::SatObservable& o, double cn0_dbhz) noexcept;
  /// The same for the second signal's C/N0 and carrier (dual-band worlds).
  void degrade_band1(world::SatObservable& o, double cn0_dbhz) noexcept;
  /// A carrier loop whose C/N0 falls from cn0_from to cn0_to (dB-Hz): the
  /// phase noise and the slips (pilot: whole cycles, else half, which
  /// flip the data sign) the larger jitter adds, kept in slips for the loop's
  /// lifetime (carry_slips applies them); stream: the signal's random stream.
  void degrade_carrier(double& phase_cycles, CarrierSlips& slips, double cn0_from_dbhz, double cn0_to_dbhz, bool pilot,
                       std::uint64_t stream) noexcept;
  /// Shift a satellite's signal by delta_m (code and carrier alike) and its
  /// range rate by rate_m_s.
  static void shift(world::SatObservable& o, double delta_m, double rate_m_s) noexcept;
  /// The receiver loses lock on o (a non-aligned signal replaced it).
  static void break_lock(world::SatObservable& o) noexcept;
  /// A spoofer that moved the loops it held stops (its end, or clear()):
  /// they find no signal where it was and lose lock on the received ones.
  static bool moved(const SpoofState& s) noexcept { return s.offset_m.norm() > 0.0 || s.clock_m != 0.0; }
  static void let_go(const std::array<bool, kNumSats>& held, world::Observables& obs) noexcept;

  /// A jammer active this epoch: its power at the antenna (W) and spectrum.
  struct ActiveJammer {
    double power_w = 0.0;
    JammerKind kind = JammerKind::kWideband;
    JammerBand band;
  };

  FaultContext ctx_;
  std::array<ActiveJammer, kMaxEvents> jam_{};
  double n0_dbw_hz_ = 0.0;
  world::CounterRng rng_{0};
  std::vector<FaultEvent> events_;          ///< reserved kMaxEvents
  std::vector<FaultStatus> status_;         ///< reserved kMaxEvents
  std::vector<SpoofState> spoof_;           ///< one per event, reserved kMaxEvents
  std::array<bool, kNumSats> released_{};  ///< loops cleared spoofers held: they let go next epoch
  bool releasing_ = false;
  /// Total shift of a satellite's signal by satellite faults (m) and its
  /// rate (m/s), this epoch and the last epoch it was in view (one line per
  /// satellite: the stage touches a few per epoch).
  struct Shift {
    double m = 0.0, rate_m_s = 0.0, prev_m = 0.0, prev_rate_m_s = 0.0;
  };
  std::array<Shift, kNumSats> shift_{};
  bool shifted_ = false;                    ///< a satellite fault acted at the last epoch
  std::array<std::array<CarrierSlips, kNumBands>, kNumSats> slips_{};
  bool any_slips_ = false;
  /// s as of this epoch: reset when the loop missed the last epoch.
  CarrierSlips& current(CarrierSlips& s) const noexcept;
  /// Adds the loops' kept slips to this epoch's carriers; drops those of lost loops.
  void carry_slips(world::Observables& obs) noexcept;
  std::array<orbit::Ephemeris, kNumSats> eph_copy_{};  ///< broadcast sets a fault falsified, per satellite
  FaultEffects effects_;
  bool started_ = false;
  time::GpsTime t0_, t_prev_;
  double elapsed_s_ = 0.0;
  double dt_s_ = 0.0;                       ///< this epoch's step, s
  std::uint64_t epoch_ = 0;
};

}  // namespace gnssemu::faults
