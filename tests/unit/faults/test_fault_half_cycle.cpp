// SPDX-License-Identifier: Apache-2.0
// A Costas loop's half-cycle ambiguity end to end: a new lock (the world's,
// or the receiver's after a loss) and a half-cycle slip leave the phase 0 or
// half a cycle off a whole number while RXM-RAWX halfCyc is clear; once the
// frame preamble resolves it the receiver's phase is a whole number of cycles
// off the world's (subHalfCyc when it subtracted the half). A pilot (GPS
// L2C CL) never carries the half cycle. docs/raw-output.md "Half cycle".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/faults/interference.hpp"
#include "core/signal/system_signal.hpp"
#include "fault_rig.hpp"

namespace gnssemu::faults {
namespace {

using test::make_event;
using test::Rig;
using test::test_store;

struct HalfCycleCount {
  int resolved = 0, subtracted = 0;  ///< resolved measurements, and those with the half taken off
  int unresolved = 0, unresolved_half = 0;  ///< unresolved ones, and those half a cycle off
  int pilot = 0;                     ///< pilot measurements (always resolved, never half)
};

// Every carrier measurement of the receiver's epoch against the world's
// phase with the world's own half cycle taken out (the true whole-cycle
// phase): a whole number of cycles apart once resolved, 0 or 0.5 before.
void print(const char* what, const HalfCycleCount& n) {
  std::printf("%s: resolved %d (half subtracted %d), unresolved %d (half a cycle off %d), pilot %d\n", what,
              n.resolved, n.subtracted, n.unresolved, n.unresolved_half, n.pilot);
}

void check_epoch(const pipeline::Pipeline& rx, HalfCycleCount& n, double t) {
  const world::Observables& wo = rx.world().observables();
  const receiver::RawEpoch& raw = rx.receiver().raw();
  for (int j = 0; j < raw.num_meas; ++j) {
    const receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(j)];
    if (!m.carrier_valid) continue;
    const world::SatObservable* w = nullptr;
    for (int i = 0; i < wo.num_sats; ++i)
      if (wo.sats[i].sat == m.sat) w = &wo.sats[i];
    ASSERT_NE(w, nullptr);
    const int band = signal_info(m.signal).band;
    const double phase = band == 0 ? w->carrier_phase_cycles : w->band1.carrier_phase_cycles;
    const bool half = band == 0 ? w->carrier_half_cycle : w->band1.carrier_half_cycle;
    const double d = m.carrier_phase_cycles - (phase - (half ? 0.5 : 0.0));
    const double off = std::fabs(d - std::round(d));
    if (signal_info(m.signal).pilot) {
      ++n.pilot;
      EXPECT_FALSE(half) << t;
      EXPECT_TRUE(m.half_cycle_resolved) << t;
      EXPECT_FALSE(m.half_cycle_subtracted) << t;
      EXPECT_LT(off, 1e-6) << t << " " << m.sat.prn();
      continue;
    }
    if (m.half_cycle_resolved) {
      ++n.resolved;
      n.subtracted += m.half_cycle_subtracted;
      EXPECT_LT(off, 1e-6) << t << " G" << m.sat.prn() << " d " << d;
    } else {
      ++n.unresolved;
      EXPECT_FALSE(m.half_cycle_subtracted) << t;
      const bool half_off = std::fabs(off - 0.5) < 1e-6;
      EXPECT_TRUE(off < 1e-6 || half_off) << t << " G" << m.sat.prn() << " d " << d;
      n.unresolved_half += half_off;
    }
  }
}

TEST(FaultHalfCycle, WorldSlipsAndNewLocksAreResolvedToWholeCycles) {
  // A noisy oscillator (0.28 rad): Viterbi's mean time to a half-cycle slip
  // is about a minute, so every GPS L1 C/A loop slips a few times in 10 min;
  // GPS L2C CL (a pilot) slips by whole cycles.
  pipeline::PipelineConfig c;
  c.world.carrier.oscillator_sigma_rad = 0.28;
  c.world.bands = 2;
  c.receiver.bands = 2;
  pipeline::Pipeline rx(test_store(), c);
  world::Truth truth;
  truth.pos_m = geo::ecef_from_lla(Lla{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0});
  truth.valid = true;
  const time::GpsTime t0 = test_store().first_valid() + 8.0 * 3600.0;
  HalfCycleCount n;
  std::uint32_t slips = 0;
  for (int k = 0; k < 600; ++k) {
    truth.t = t0 + static_cast<double>(k);
    rx.step(truth.t, truth);
    check_epoch(rx, n, k);
    if (HasFailure()) return;
  }
  const world::Observables& wo = rx.world().observables();
  for (int i = 0; i < wo.num_sats; ++i) slips += wo.sats[i].carrier_discontinuities;
  print("world slips", n);
  std::printf("world carrier discontinuities %u\n", slips);
  EXPECT_GT(slips, 30u);
  EXPECT_GT(n.resolved, 2000);
  EXPECT_GT(n.pilot, 2000);
  // The half cycle is real while unresolved and taken off at resolution.
  EXPECT_GT(n.unresolved_half, 20);
  EXPECT_GT(n.unresolved, n.unresolved_half);
  EXPECT_GT(n.subtracted, 200);
  EXPECT_LT(n.subtracted, n.resolved);
}

// J/S of a wideband L1 jammer that takes a 45 dB-Hz GPS signal to cn0_dbhz.
double jammer_js_db(double cn0_dbhz) {
  const signal::LinkBudgetConfig l;
  const double n0_w_hz =
      std::pow(10.0, (signal::thermal_noise_density_dbw_hz(l.noise_temperature_k) + l.noise_figure_db +
                      l.environment_noise_rise_db) / 10.0);
  const double i0_per_w = interference_density_w_hz(
      1.0, JammerKind::kWideband, JammerBand{kL1Freq_hz, default_jammer_width_hz(JammerKind::kWideband)},
      SignalBand{kL1Freq_hz, signal::system_signal(GnssSystem::kGps).main_lobe_half_width_hz});
  const double j_w = n0_w_hz * (std::pow(10.0, (45.0 - cn0_dbhz) / 10.0) - 1.0) / i0_per_w;
  return 10.0 * std::log10(j_w) - kNominalSignal_dbw;
}

TEST(FaultHalfCycle, ReacquisitionAfterAJammerIsResolvedToWholeCycles) {
  // 30 s at 20 dB-Hz, below the loops' threshold: every GPS loop is lost and
  // re-acquired with the receiver's own ambiguity and data sign.
  FaultEvent lose = make_event(FaultType::kJammer, 10.0, 30.0);
  lose.put(Param::kJsDb, jammer_js_db(20.0));
  Rig r(std::vector<FaultEvent>{lose});
  HalfCycleCount n;
  for (int t = 0; t < 120; ++t) {
    r.step(t);
    check_epoch(r.rx, n, t);
    if (HasFailure()) return;
    // Before the jammer: the world's first locks, some on the inverted sign.
    if (t == 9) {
      EXPECT_GE(n.subtracted, 10);
    }
  }
  print("re-acquisition", n);
  EXPECT_GT(n.resolved, 300);
  EXPECT_GT(n.unresolved_half, 5);
  EXPECT_GT(n.subtracted, 50);
}

}  // namespace
}  // namespace gnssemu::faults
