// SPDX-License-Identifier: Apache-2.0
// What each fault does to the carrier loops: a jammer's lower C/N0 brings
// phase jitter and Viterbi slips, and below the tracking threshold a loss of
// lock with a new ambiguity after it; a satellite's clock ramp moves code and
// carrier alike without a break, a step beyond a half chip breaks lock; a
// broadcast (ephemeris) error changes nothing measured; an aligned spoofer
// drags the carrier along, a non-aligned capture is a new lock; an outage
// is a loss of lock. Numbers in docs/raw-output.md "Faults and the carrier".
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <string>
#include <vector>

#include "core/faults/fault_stage.hpp"
#include "core/faults/interference.hpp"
#include "core/signal/system_signal.hpp"
#include "fault_rig.hpp"

namespace gnssemu::faults {
namespace {

using test::make_event;
using test::Rig;

constexpr double kClean_dbhz = 45.0;

double n0_dbw_hz(const signal::LinkBudgetConfig& l) {
  return signal::thermal_noise_density_dbw_hz(l.noise_temperature_k) + l.noise_figure_db + l.environment_noise_rise_db;
}

// J/S (dB over the nominal signal) of a wideband jammer on L1 that takes a
// kClean_dbhz signal of sys to cn0_dbhz: I0 = N0 (10^(dC/10) - 1), I0 per
// watt of jammer from the overlap with the system's main lobe.
double js_db_for(double cn0_dbhz, GnssSystem sys = GnssSystem::kGps) {
  const double n0_w_hz = std::pow(10.0, n0_dbw_hz(signal::LinkBudgetConfig{}) / 10.0);
  const double i0_per_w = interference_density_w_hz(
      1.0, JammerKind::kWideband, JammerBand{kL1Freq_hz, default_jammer_width_hz(JammerKind::kWideband)},
      SignalBand{kL1Freq_hz, signal::system_signal(sys).main_lobe_half_width_hz});
  const double j_w = n0_w_hz * (std::pow(10.0, (kClean_dbhz - cn0_dbhz) / 10.0) - 1.0) / i0_per_w;
  return 10.0 * std::log10(j_w) - kNominalSignal_dbw;
}

// Total loop jitter of the default carrier loops at cn0_dbhz, rad.
double loop_sigma_rad(double cn0_dbhz) {
  const world::CarrierConfig cc;
  return std::hypot(world::pll_jitter_rad(cn0_dbhz, cc.pll_bandwidth_hz, cc.integration_s), cc.oscillator_sigma_rad);
}

struct Slips {
  int count = 0, up = 0, down = 0;  ///< discontinuities, and slips by sign
  double size = 0.0;                ///< |size| of the last slip, cycles
  double noise_rms_cycles = 0.0;    ///< phase noise the stage added
  double cn0_dbhz = 0.0;
};

// One epoch of the fault stage alone on one satellite's clean L1 signal
// (received or not) at 1 Hz epoch k: the observable as the stage leaves it.
world::SatObservable one_sat_epoch(FaultStage& stage, SatId sat, int k, bool received) {
  world::Truth truth;
  truth.valid = true;
  truth.pos_m = Ecef(4.2e6, 0.17e6, 4.78e6);
  world::Observables obs;
  obs.antenna_connected = true;
  world::SatObservable& o = obs.sats[static_cast<std::size_t>(obs.num_sats++)];
  o.sat = sat;
  o.above_mask = o.received = o.carrier_valid = received;
  o.cn0_dbhz = received ? kClean_dbhz : 0.0;
  o.carrier_hz = kL1Freq_hz;
  o.wavelength_m = kL1Wavelength_m;
  stage.apply(time::GpsTime(2300, 1000.0 + k), truth, obs);
  return o;
}

// A jammer taking one satellite's C/N0 from kClean_dbhz to cn0_dbhz, one
// hour at 1 Hz on the fault stage alone: the slips and phase noise it adds.
Slips jam_one_hour(SatId sat, double cn0_dbhz) {
  FaultEvent e = make_event(FaultType::kJammer, 0.0);
  e.put(Param::kJsDb, js_db_for(cn0_dbhz, sat.system));
  FaultStage stage(FaultContext{}, std::vector<FaultEvent>{e});
  Slips s;
  double sum2 = 0.0, kept_cycles = 0.0;
  std::uint32_t kept_count = 0;
  for (int k = 0; k < 3600; ++k) {
    const world::SatObservable o = one_sat_epoch(stage, sat, k, true);
    // The loop keeps its slips: this epoch's is the step in the kept offset.
    const double kept = std::round(2.0 * o.carrier_phase_cycles) / 2.0;  // the noise is < 0.1 cycle
    const double slip = kept - kept_cycles;
    sum2 += (o.carrier_phase_cycles - kept) * (o.carrier_phase_cycles - kept);
    EXPECT_GE(o.carrier_discontinuities, kept_count);
    s.count += static_cast<int>(o.carrier_discontinuities - kept_count);
    kept_cycles = kept;
    kept_count = o.carrier_discontinuities;
    if (slip > 0.0) ++s.up;
    if (slip < 0.0) ++s.down;
    if (slip != 0.0) s.size = std::fabs(slip);
    s.cn0_dbhz = o.cn0_dbhz;
  }
  s.noise_rms_cycles = std::sqrt(sum2 / 3600.0);
  return s;
}

// Slips per hour the jammer should add at 1 Hz: the difference of the
// per-epoch slip probabilities (Viterbi) at the two C/N0.
double expected_per_hour(double cn0_dbhz) {
  const double b = world::CarrierConfig{}.pll_bandwidth_hz;
  return 3600.0 * (world::cycle_slip_probability(loop_sigma_rad(cn0_dbhz), b, 1.0) -
                   world::cycle_slip_probability(loop_sigma_rad(kClean_dbhz), b, 1.0));
}

TEST(FaultCarrier, JammerSlipsAndJitterFollowTheLoopsAtTheLowerCn0) {
  const SatId gps(GnssSystem::kGps, 5), gal(GnssSystem::kGalileo, 11);
  // 22 dB-Hz: Viterbi's mean time to slip is ~36 s, ~100 slips an hour.
  const double expected = expected_per_hour(22.0);
  ASSERT_GT(expected, 60.0);
  ASSERT_LT(expected, 150.0);
  for (const SatId sat : {gps, gal}) {
    const Slips s = jam_one_hour(sat, 22.0);
    EXPECT_NEAR(s.cn0_dbhz, 22.0, 1e-9);
    // Binomial over 3600 epochs: 5 sigma.
    EXPECT_NEAR(s.count, expected, 5.0 * std::sqrt(expected)) << system_letter(sat.system);
    EXPECT_EQ(s.up + s.down, s.count);
    // Either sign; a Costas loop (GPS C/A) by half a cycle, Galileo E1C's pilot PLL by a whole one.
    EXPECT_GT(s.up, s.count / 4);
    EXPECT_GT(s.down, s.count / 4);
    EXPECT_EQ(s.size, sat == gal ? 1.0 : 0.5);
    // The phase noise grows to the jitter at 22 dB-Hz (the world drew the 45 dB-Hz part).
    const double extra = std::sqrt(std::pow(loop_sigma_rad(22.0), 2) - std::pow(loop_sigma_rad(kClean_dbhz), 2)) / (2.0 * kPi);
    EXPECT_NEAR(s.noise_rms_cycles, extra, 0.05 * extra);
  }
  // 35 dB-Hz: the loop hardly notices (no slip expected in an hour).
  EXPECT_LT(expected_per_hour(35.0), 1e-3);
  const Slips mild = jam_one_hour(gps, 35.0);
  EXPECT_EQ(mild.count, 0);
  EXPECT_LT(mild.noise_rms_cycles, 0.02);
}

// A slip is a step in the loop's phase that stays: after a 10 min jammer at
// 22 dB-Hz ends, the carrier keeps the offset and the discontinuity count the
// slips left, epoch after epoch, until the loop loses lock.
TEST(FaultCarrier, JammerSlipsStayInThePhaseAfterTheJammer) {
  const SatId sat(GnssSystem::kGps, 5);
  FaultEvent e = make_event(FaultType::kJammer, 0.0);
  e.duration_s = 600.0;
  e.put(Param::kJsDb, js_db_for(22.0, sat.system));
  FaultStage stage(FaultContext{}, std::vector<FaultEvent>{e});
  const auto epoch = [&](int k, bool received) { return one_sat_epoch(stage, sat, k, received); };
  world::SatObservable last;
  for (int k = 0; k < 600; ++k) last = epoch(k, true);
  const double kept = std::round(2.0 * last.carrier_phase_cycles) / 2.0;
  ASSERT_GT(last.carrier_discontinuities, 5u);  // ~100 an hour: ~16 in 10 min
  for (int k = 600; k < 900; ++k) {
    const world::SatObservable o = epoch(k, true);
    ASSERT_EQ(o.carrier_discontinuities, last.carrier_discontinuities) << k;
    ASSERT_EQ(o.carrier_phase_cycles, kept) << k;  // the jammer's noise is gone, the slips stay
    ASSERT_EQ(o.carrier_half_cycle, last.carrier_half_cycle) << k;
  }
  // The loop loses the signal: a new lock starts without them.
  epoch(900, false);
  const world::SatObservable fresh = epoch(901, true);
  EXPECT_EQ(fresh.carrier_discontinuities, 0u);
  EXPECT_EQ(fresh.carrier_phase_cycles, 0.0);
  std::printf("jammer 600 s at 22 dB-Hz: %u slips, %.1f cycles kept for 300 s after it; gone after a loss of lock\n",
              last.carrier_discontinuities, kept);
}

const world::SatObservable* world_sat(const Rig& r, SatId sat) {
  const world::Observables& o = r.rx.world().observables();
  for (int i = 0; i < o.num_sats; ++i)
    if (o.sats[i].sat == sat) return &o.sats[i];
  return nullptr;
}

const receiver::RawMeasurement* raw_of(const Rig& r, SatId sat) {
  const receiver::RawEpoch& raw = r.rx.receiver().raw();
  for (int j = 0; j < raw.num_meas; ++j) {
    const receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(j)];
    if (m.sat == sat && m.carrier_valid) return &m;
  }
  return nullptr;
}

bool in_raw(const Rig& r, SatId sat) {
  const receiver::RawEpoch& raw = r.rx.receiver().raw();
  for (int j = 0; j < raw.num_meas; ++j)
    if (raw.meas[static_cast<std::size_t>(j)].sat == sat) return true;
  return false;
}

// The receiver's phase minus the world's (unfaulted) phase, cycles.
double phase_diff(const Rig& r, SatId sat) {
  const receiver::RawMeasurement* m = raw_of(r, sat);
  const world::SatObservable* w = world_sat(r, sat);
  if (m == nullptr || w == nullptr || !w->carrier_valid) return std::nan("");
  return m->carrier_phase_cycles - w->carrier_phase_cycles;
}

// Every satellite carrier-tracked at 9 s loses lock in [10, 10 + lost_s)
// and, after it, comes back as a new lock: lock time 0, half cycle
// unresolved and a new whole-cycle ambiguity. RAWX carries these as they are
// (locktime, trkStat cpValid / halfCyc; test_ubx RxmRawx pins the mapping):
// trkStat 0x07 before, no entry during, 0x03 and locktime 0 after.
// Returns the satellites that came back.
int expect_new_locks_after(const FaultEvent& e, double lost_s) {
  Rig r(std::vector<FaultEvent>{e});
  r.step(9.0);
  std::array<double, kNumSats> before{};
  std::array<int, kNumSats> state{};  // 1 tracked at 9 s, 2 lost, 3 back
  std::vector<SatId> sats;
  const world::Observables& wo = r.rx.world().observables();
  for (int i = 0; i < wo.num_sats; ++i) {
    const SatId s = wo.sats[i].sat;
    const double d = phase_diff(r, s);
    if (!std::isfinite(d) || s.system != GnssSystem::kGps) continue;
    before[static_cast<std::size_t>(s.index())] = d;
    state[static_cast<std::size_t>(s.index())] = 1;
    sats.push_back(s);
    const receiver::RawMeasurement* m = raw_of(r, s);
    EXPECT_GT(m->lock_time_s, 0.0);
    EXPECT_TRUE(m->pseudorange_valid && m->half_cycle_resolved);
  }
  EXPECT_GE(sats.size(), 5u);
  int back = 0, new_ambiguity = 0;
  for (int t = 10; t < 10 + static_cast<int>(lost_s) + 120; ++t) {
    r.step(t);
    for (const SatId s : sats) {
      int& st = state[static_cast<std::size_t>(s.index())];
      const receiver::RawMeasurement* m = raw_of(r, s);
      if (t < 10 + lost_s) {
        EXPECT_FALSE(in_raw(r, s)) << t << " G" << s.prn();  // not tracked while the fault lasts
        st = 2;
        continue;
      }
      if (m == nullptr) continue;
      if (st == 2) {
        EXPECT_EQ(m->lock_time_s, 0.0) << t << " G" << s.prn();
        EXPECT_FALSE(m->half_cycle_resolved);
        EXPECT_TRUE(m->pseudorange_valid);
        // A whole number of cycles, or half of one: the new lock's data sign
        // is unknown until the next preamble (test_fault_half_cycle.cpp).
        const double delta = phase_diff(r, s) - before[static_cast<std::size_t>(s.index())];
        EXPECT_NEAR(2.0 * delta, std::round(2.0 * delta), 1e-6) << t << " G" << s.prn();
        new_ambiguity += std::fabs(delta) >= 1.0;
        ++back;
        st = 3;
      }
    }
  }
  EXPECT_EQ(new_ambiguity, back);
  return back;
}

TEST(FaultCarrier, JammerBelowTheTrackingThresholdLosesLockAndReacquiresWithANewAmbiguity) {
  // ~20 dB-Hz: below the 25 dB-Hz at which the loops let go, still above 0.
  FaultEvent e = make_event(FaultType::kJammer, 10.0, 30.0);
  e.put(Param::kJsDb, js_db_for(20.0));
  EXPECT_GE(expect_new_locks_after(e, 30.0), 5);
}

TEST(FaultCarrier, OutageAndSkyBlockLoseLockAndReacquireWithANewAmbiguity) {
  EXPECT_GE(expect_new_locks_after(make_event(FaultType::kOutage, 10.0, 20.0, static_cast<int>(OutageKind::kBlockage)), 20.0), 5);
  FaultEvent b = make_event(FaultType::kSkyBlock, 10.0, 20.0);
  b.put(Param::kAzFromDeg, 0.0);
  b.put(Param::kAzToDeg, 360.0);
  b.put(Param::kElMinDeg, 0.0);
  b.put(Param::kElMaxDeg, 90.0);
  EXPECT_GE(expect_new_locks_after(b, 20.0), 5);
}

SatId first_carrier_sat(const Rig& r) {
  const world::Observables& wo = r.rx.world().observables();
  for (int i = 0; i < wo.num_sats; ++i)
    if (wo.sats[i].sat.system == GnssSystem::kGps && raw_of(r, wo.sats[i].sat) != nullptr) return wo.sats[i].sat;
  return SatId{};
}

// A satellite clock that runs off (0.5 m/s for 60 s): code and carrier move
// by the same metres, the Doppler by the rate, the lock holds.
TEST(FaultCarrier, SatelliteClockRampMovesCodeAndCarrierAlikeWithoutABreak) {
  Rig probe({}, false);
  probe.step(0.0);
  const SatId sat = first_carrier_sat(probe);
  ASSERT_NE(sat.prn(), 0);
  FaultEvent e = make_event(FaultType::kSatellite, 5.0, 60.0);
  e.put(Param::kPrn, sat.prn());
  e.put(Param::kRateMS, 0.5);
  Rig r(std::vector<FaultEvent>{e});
  r.step(0.0);
  const double d0 = phase_diff(r, sat);
  double lock_prev = raw_of(r, sat)->lock_time_s;
  for (int t = 1; t < 65; ++t) {
    r.step(t);
    const receiver::RawMeasurement* m = raw_of(r, sat);
    ASSERT_NE(m, nullptr) << t;
    const world::SatObservable* w = world_sat(r, sat);
    const double offset_m = t >= 5 ? 0.5 * (t - 5) : 0.0;
    EXPECT_NEAR(m->pseudorange_m - w->pseudorange_m, offset_m, 1e-6) << t;
    EXPECT_NEAR((phase_diff(r, sat) - d0) * w->wavelength_m, offset_m, 1e-6) << t;
    EXPECT_NEAR(m->doppler_hz - w->doppler_hz, t >= 5 ? -0.5 / w->wavelength_m : 0.0, 1e-6) << t;
    EXPECT_NEAR(m->lock_time_s, lock_prev + 1.0, 1e-9) << t;  // no break
    lock_prev = m->lock_time_s;
  }
}

// A step: 100 m (under the half chip the loops follow) moves code and
// carrier and keeps the lock; 300 m (a 1 us clock jump) breaks it, and the
// carrier comes back on the stepped signal with a new ambiguity; the end of
// the 300 m bias, 30 s on, is a step back that breaks it again.
TEST(FaultCarrier, SatelliteStepBeyondHalfAChipBreaksLock) {
  ASSERT_LT(100.0, world::CarrierConfig{}.lock_break_m);
  ASSERT_GT(300.0, world::CarrierConfig{}.lock_break_m);
  Rig probe({}, false);
  probe.step(0.0);
  const SatId sat = first_carrier_sat(probe);
  ASSERT_NE(sat.prn(), 0);
  for (const double bias_m : {100.0, 300.0}) {
    FaultEvent e = make_event(FaultType::kSatellite, 5.0, 30.0);
    e.put(Param::kPrn, sat.prn());
    e.put(Param::kBiasM, bias_m);
    Rig r(std::vector<FaultEvent>{e});
    r.step(4.0);
    const double d0 = phase_diff(r, sat);
    r.step(5.0);
    const receiver::RawMeasurement* m = raw_of(r, sat);
    if (bias_m < 150.0) {
      ASSERT_NE(m, nullptr);
      EXPECT_GT(m->lock_time_s, 60.0);
      EXPECT_NEAR((phase_diff(r, sat) - d0) * world_sat(r, sat)->wavelength_m, bias_m, 1e-6);
      continue;
    }
    EXPECT_EQ(m, nullptr);  // lost at the step
    int back_at = -1;
    for (int t = 6; t < 60 && back_at < 0; ++t) {
      r.step(t);
      m = raw_of(r, sat);
      if (m == nullptr) continue;
      back_at = t;
      EXPECT_EQ(m->lock_time_s, 0.0);
      const world::SatObservable* w = world_sat(r, sat);
      EXPECT_NEAR(m->pseudorange_m - w->pseudorange_m, bias_m, 1e-6);
      const double cycles = phase_diff(r, sat) - d0 - bias_m / w->wavelength_m;
      EXPECT_NEAR(2.0 * cycles, std::round(2.0 * cycles), 1e-6);  // half a cycle off until resolved
      EXPECT_GE(std::fabs(cycles), 1.0);  // a new ambiguity
    }
    EXPECT_GT(back_at, 5);
    for (int t = back_at + 1; t < 35; ++t) {
      r.step(t);
      EXPECT_NE(raw_of(r, sat), nullptr) << t;
    }
    r.step(35.0);
    EXPECT_EQ(raw_of(r, sat), nullptr);  // the bias ends: lost again
    back_at = -1;
    for (int t = 36; t < 90 && back_at < 0; ++t) {
      r.step(t);
      m = raw_of(r, sat);
      if (m == nullptr) continue;
      back_at = t;
      EXPECT_EQ(m->lock_time_s, 0.0);
      EXPECT_EQ(m->pseudorange_m, world_sat(r, sat)->pseudorange_m);
      const double cycles = phase_diff(r, sat) - d0;
      EXPECT_NEAR(2.0 * cycles, std::round(2.0 * cycles), 1e-6);  // half a cycle off until resolved
      EXPECT_GE(std::fabs(cycles), 1.0);
    }
    EXPECT_GT(back_at, 35);
  }
}

// A wrong broadcast orbit: the satellite is where it is, so every measurement
// and the lock are the world's; only the receiver's decoded ephemeris moves.
TEST(FaultCarrier, EphemerisErrorChangesNothingMeasured) {
  Rig probe({}, false);
  probe.step(0.0);
  const SatId sat = first_carrier_sat(probe);
  ASSERT_NE(sat.prn(), 0);
  FaultEvent e = make_event(FaultType::kSatellite, 5.0, 30.0);
  e.put(Param::kPrn, sat.prn());
  e.put(Param::kEphRadialM, 500.0);
  e.put(Param::kEphAlongM, 500.0);
  Rig r(std::vector<FaultEvent>{e});
  r.step(0.0);
  const double d0 = phase_diff(r, sat);
  double lock_prev = raw_of(r, sat)->lock_time_s;
  for (int t = 1; t < 40; ++t) {
    r.step(t);
    const receiver::RawMeasurement* m = raw_of(r, sat);
    ASSERT_NE(m, nullptr) << t;
    const world::SatObservable* w = world_sat(r, sat);
    EXPECT_EQ(m->pseudorange_m, w->pseudorange_m) << t;
    EXPECT_EQ(m->doppler_hz, w->doppler_hz) << t;
    EXPECT_EQ(phase_diff(r, sat), d0) << t;
    EXPECT_NEAR(m->lock_time_s, lock_prev + 1.0, 1e-9) << t;
    lock_prev = m->lock_time_s;
  }
}

// An aligned drag-off: the captured loops follow the spoofed signal without
// a break, code and carrier moved alike, the Doppler by the false range
// rate. A takeover that appears 10 us away: a new lock on the false signal.
TEST(FaultCarrier, SpooferCaptureDragsTheCarrierOrIsANewLock) {
  FaultEvent drag = make_event(FaultType::kSpoofer, 5.0, kForever_s, static_cast<int>(SpoofMode::kDrag));
  drag.put(Param::kDragSpeedMS, 2.0);
  drag.put(Param::kDragHeadingDeg, 90.0);
  Rig r(std::vector<FaultEvent>{drag});
  r.step(4.0);
  const SatId sat = first_carrier_sat(r);
  ASSERT_NE(sat.prn(), 0);
  const double d0 = phase_diff(r, sat);
  double lock_prev = raw_of(r, sat)->lock_time_s, shift_prev_m = 0.0;
  for (int t = 5; t < 60; ++t) {
    r.step(t);
    const receiver::RawMeasurement* m = raw_of(r, sat);
    ASSERT_NE(m, nullptr) << t;
    const world::SatObservable* w = world_sat(r, sat);
    const double shift_m = m->pseudorange_m - w->pseudorange_m;
    EXPECT_NEAR((phase_diff(r, sat) - d0) * w->wavelength_m, shift_m, 1e-6) << t;
    if (t > 6) {
      EXPECT_NEAR(-(m->doppler_hz - w->doppler_hz) * w->wavelength_m, shift_m - shift_prev_m, 0.05) << t;
    }
    EXPECT_NEAR(m->lock_time_s, lock_prev + 1.0, 1e-9) << t;
    lock_prev = m->lock_time_s;
    shift_prev_m = shift_m;
  }
  EXPECT_GT(std::fabs(shift_prev_m), 10.0);  // 110 m east by now: moved along the line of sight

  FaultEvent takeover = make_event(FaultType::kSpoofer, 5.0, kForever_s, static_cast<int>(SpoofMode::kTakeover));
  takeover.put(Param::kPowerAdvantageDb, 10.0);
  takeover.put(Param::kClockJumpUs, 10.0);
  Rig k(std::vector<FaultEvent>{takeover});
  k.step(4.0);
  const double k0 = phase_diff(k, sat);
  k.step(5.0);
  EXPECT_EQ(raw_of(k, sat), nullptr);  // the capture breaks lock
  int back_at = -1;
  for (int t = 6; t < 90 && back_at < 0; ++t) {
    k.step(t);
    const receiver::RawMeasurement* m = raw_of(k, sat);
    if (m == nullptr) continue;
    back_at = t;
    EXPECT_EQ(m->lock_time_s, 0.0);
    const world::SatObservable* w = world_sat(k, sat);
    const double cycles = phase_diff(k, sat) - k0 - (m->pseudorange_m - w->pseudorange_m) / w->wavelength_m;
    EXPECT_NEAR(2.0 * cycles, std::round(2.0 * cycles), 1e-6);  // half a cycle off until resolved
    EXPECT_GE(std::fabs(cycles), 1.0);
  }
  EXPECT_GT(back_at, 5);
}

}  // namespace
}  // namespace gnssemu::faults
