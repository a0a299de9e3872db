// SPDX-License-Identifier: Apache-2.0
// The fault stage through the whole pipeline: each fault acts on signals and
// measurements, and the receiver's own tracking, solution, exclusion and
// flags react.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/faults/fault_stage.hpp"
#include "core/faults/interference.hpp"
#include "fault_rig.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::faults {
namespace {

using test::make_event;
using test::Rig;

double n0_dbw_hz(const Rig& r) {
  const auto& l = r.rx.world().config().signal.link;
  return signal::thermal_noise_density_dbw_hz(l.noise_temperature_k) + l.noise_figure_db + l.environment_noise_rise_db;
}

int first_used_prn(const receiver::Fix& f) {
  for (int i = 0; i < f.num_sats; ++i)
    if (f.sats[i].used) return f.sats[i].sat.prn();
  return 0;
}

const receiver::SatInfo* sat(const receiver::Fix& f, int prn) {
  for (int i = 0; i < f.num_sats; ++i)
    if (f.sats[i].sat.prn() == prn) return &f.sats[i];
  return nullptr;
}

TEST(FaultStage, JammerFollowsTheInterferenceRelation) {
  FaultEvent e = make_event(FaultType::kJammer, 0.0);
  e.put(Param::kJsDb, 25.0);
  Rig clean({}, false), jammed(std::vector<FaultEvent>{e});
  const double i0 = interference_density_w_hz(kNominalSignal_dbw + 25.0, JammerKind::kWideband);
  for (int s = 0; s < 5; ++s) {
    const receiver::Fix c = clean.step(s);
    const receiver::Fix& j = jammed.step(s);
    int compared = 0;
    for (int i = 0; i < c.num_sats; ++i) {
      const receiver::SatInfo* js = sat(j, c.sats[i].sat.prn());
      if (!c.sats[i].tracked || js == nullptr || !js->tracked) continue;
      EXPECT_NEAR(js->cn0_dbhz, effective_cn0_dbhz(c.sats[i].cn0_dbhz, n0_dbw_hz(clean), i0), 1e-9);
      ++compared;
    }
    EXPECT_GE(compared, 4);
    EXPECT_GT(j.noise_rise_db, c.noise_rise_db + 1.0);  // the AGC sees the jammer
  }
}

TEST(FaultStage, PlacedJammerFollowsFreeSpaceLossAndTheAntennaPattern) {
  Rig probe({}, false);
  // 1 km north of the receiver, at its height (elevation ~0).
  const double north_deg = 1000.0 / 111200.0;
  FaultEvent e = make_event(FaultType::kJammer, 0.0);
  e.put(Param::kEirpDbw, -20.0);
  e.put(Param::kLatDeg, probe.site.lat_rad / kDegToRad + north_deg);
  e.put(Param::kLonDeg, probe.site.lon_rad / kDegToRad);
  e.put(Param::kHeightM, probe.site.height_m);
  Rig rig(std::vector<FaultEvent>{e});
  rig.step(0);
  const auto& link = rig.rx.world().config().signal.link;
  const double expected = jammer_power_dbw(-20.0, 1000.0, signal::antenna_gain_dbi(link.antenna, 0.0));
  EXPECT_NEAR(rig.rx.faults()->effects().jammer_dbw, expected, 0.1);  // 1 km to ~0.5 %, el ~0 deg
  FaultEvent d = make_event(FaultType::kJammer, 0.0);
  d.put(Param::kEirpDbw, -20.0);
  d.put(Param::kDistanceM, 1000.0);
  Rig by_distance(std::vector<FaultEvent>{d});
  by_distance.step(0);
  EXPECT_NEAR(by_distance.rx.faults()->effects().jammer_dbw, expected, 1e-9);
}

TEST(FaultStage, WidebandIsGentlerThanCwAtTheSamePower) {
  FaultEvent wide = make_event(FaultType::kJammer, 0.0, kForever_s, static_cast<int>(JammerKind::kWideband));
  wide.put(Param::kJsDb, 30.0);
  FaultEvent cw = wide;
  cw.mode = static_cast<std::uint8_t>(JammerKind::kCw);
  Rig a(std::vector<FaultEvent>{wide}), b(std::vector<FaultEvent>{cw});
  const receiver::Fix fa = a.step(0);
  const receiver::Fix& fb = b.step(0);
  EXPECT_EQ(fa.cw_jam_to_noise, 0.0);
  EXPECT_GT(fb.cw_jam_to_noise, 0.0);
  double sa = 0, sb = 0;
  for (int i = 0; i < fa.num_sats; ++i) sa += fa.sats[i].cn0_dbhz;
  for (int i = 0; i < fb.num_sats; ++i) sb += fb.sats[i].cn0_dbhz;
  EXPECT_GT(sa, sb);  // Q = 2 against Q = 1
}

TEST(FaultStage, RampedJammerLosesTheFixAndItComesBack) {
  FaultEvent e = make_event(FaultType::kJammer, 10.0, 60.0);
  e.put(Param::kJsDb, Ramp{0.0, 60.0});
  Rig rig(std::vector<FaultEvent>{e});
  int lost_at = -1;
  for (int s = 0; s < 90; ++s) {
    const receiver::Fix& f = rig.step(s);
    if (s < 10) {
      EXPECT_EQ(f.type, receiver::FixType::k3D);
    }
    if (lost_at < 0 && f.type == receiver::FixType::kNone) lost_at = s;
    if (s >= 85) {
      EXPECT_EQ(f.type, receiver::FixType::k3D) << s;  // reacquired after the jammer stops
    }
  }
  EXPECT_GT(lost_at, 10 + 20);  // not before J/S passes ~20 dB (the jammer reaches the noise floor)
  EXPECT_LT(lost_at, 70);
}

TEST(FaultStage, DragOffMovesTheFixWithQuietResiduals) {
  FaultEvent e = make_event(FaultType::kSpoofer, 10.0, kForever_s, static_cast<int>(SpoofMode::kDrag));
  e.put(Param::kDragSpeedMS, 2.0);
  e.put(Param::kDragHeadingDeg, 90.0);
  Rig rig(std::vector<FaultEvent>{e});
  for (int s = 0; s <= 110; ++s) {
    const receiver::Fix& f = rig.step(s);
    ASSERT_EQ(f.type, receiver::FixType::k3D) << s;
    EXPECT_EQ(f.num_used, f.num_tracked) << s;  // nothing excluded
    EXPECT_LT(f.h_acc_m, 10.0);
  }
  const Enu d = rig.error(rig.rx.last_fix());
  EXPECT_NEAR(d.x, 200.0, 8.0);  // 2 m/s for 100 s, east
  EXPECT_NEAR(d.y, 0.0, 8.0);
  EXPECT_NEAR(rig.rx.faults()->effects().spoof_offset_m.x, 200.0, 1e-6);
}

TEST(FaultStage, CaptureFollowsThePowerAdvantage) {
  int captured[3] = {};
  int tracked = 0;
  const double advantages[3] = {-15.0, 0.0, 6.0};
  for (int k = 0; k < 3; ++k) {
    FaultEvent e = make_event(FaultType::kSpoofer, 0.0, kForever_s, static_cast<int>(SpoofMode::kTimePush));
    e.put(Param::kPowerAdvantageDb, advantages[k]);
    Rig rig(std::vector<FaultEvent>{e});
    tracked = rig.step(0).num_tracked;
    captured[k] = rig.rx.faults()->effects().captured;
  }
  EXPECT_LT(captured[0], captured[1]);  // weak satellites first
  EXPECT_GT(captured[1], 0);
  EXPECT_LT(captured[1], tracked);      // 0 dB over the strongest: not the strongest ones (margin 3 dB)
  EXPECT_EQ(captured[2], tracked);      // 6 dB: all
}

TEST(FaultStage, TimePushMovesTheClockNotThePosition) {
  FaultEvent e = make_event(FaultType::kSpoofer, 0.0, kForever_s, static_cast<int>(SpoofMode::kTimePush));
  e.put(Param::kPushRateNsS, 100.0);
  Rig clean({}, false), pushed(std::vector<FaultEvent>{e});
  for (int s = 0; s <= 50; ++s) {
    const receiver::Fix c = clean.step(s);
    const receiver::Fix& p = pushed.step(s);
    // The navigation filter follows the ramp within a few ns.
    EXPECT_NEAR((p.clock_bias_s - c.clock_bias_s) * 1e9, 100.0 * s, 5.0) << s;
    EXPECT_LT((p.pos_m - c.pos_m).norm(), 2.0) << s;
  }
}

TEST(FaultStage, TakeoverJumpsTheClockAndIsDetected) {
  FaultEvent e = make_event(FaultType::kSpoofer, 20.0, kForever_s, static_cast<int>(SpoofMode::kTakeover));
  e.put(Param::kClockJumpUs, 10.0);
  e.put(Param::kOffsetNorthM, 300.0);
  e.put(Param::kPowerAdvantageDb, 10.0);
  Rig rig(std::vector<FaultEvent>{e});
  double clock_before = 0;
  int jumped_at = -1;
  for (int s = 0; s < 40; ++s) {
    const receiver::Fix& f = rig.step(s);
    if (s < 20) {
      EXPECT_EQ(f.spoof_det_state, 1) << s;
      clock_before = f.clock_bias_s + f.clock_drift_s_s;  // predicted one second on
      continue;
    }
    // A non-aligned takeover breaks lock: the receiver reacquires the
    // spoofed signals within a few epochs, and its clock jumps.
    if (jumped_at < 0 && f.type == receiver::FixType::k3D && f.num_used >= 4) {
      jumped_at = s;
      EXPECT_NEAR((f.clock_bias_s - clock_before) * 1e6, 10.0, 0.1);
    }
    if (jumped_at >= 0) {
      EXPECT_GE(f.spoof_det_state, 2) << s;
      clock_before = f.clock_bias_s + f.clock_drift_s_s;
    }
  }
  EXPECT_GT(jumped_at, 20);  // lock was lost first
  EXPECT_LE(jumped_at, 25);
  EXPECT_NEAR(rig.error(rig.rx.last_fix()).y, 300.0, 10.0);
}

TEST(FaultStage, SatelliteStepAboveTheThresholdIsExcludedBelowItIsNot) {
  Rig probe({}, false);
  const int prn = first_used_prn(probe.step(0));
  ASSERT_GT(prn, 0);
  for (const double bias : {50.0, 3.0}) {
    FaultEvent e = make_event(FaultType::kSatellite, 5.0, 10.0);
    e.put(Param::kPrn, prn);
    e.put(Param::kBiasM, bias);
    Rig rig(std::vector<FaultEvent>{e});
    for (int s = 0; s < 20; ++s) {
      const receiver::Fix& f = rig.step(s);
      const receiver::SatInfo* si = sat(f, prn);
      ASSERT_NE(si, nullptr);
      const bool faulted = s >= 5 && s < 15;
      EXPECT_EQ(si->used, !(faulted && bias > 10.0)) << "bias " << bias << " t " << s;
    }
  }
}

TEST(FaultStage, UnhealthyBroadcastIsTrackedNotUsed) {
  Rig probe({}, false);
  const int prn = first_used_prn(probe.step(0));
  FaultEvent e = make_event(FaultType::kSatellite, 0.0);
  e.put(Param::kPrn, prn);
  e.put(Param::kUnhealthy, 1.0);
  Rig rig(std::vector<FaultEvent>{e});
  const receiver::SatInfo* si = sat(rig.step(0), prn);
  ASSERT_NE(si, nullptr);
  EXPECT_TRUE(si->tracked);
  EXPECT_FALSE(si->healthy);
  EXPECT_FALSE(si->used);
}

bool gnss_fix(const receiver::Fix& f) { return f.type == receiver::FixType::k2D || f.type == receiver::FixType::k3D; }

TEST(FaultStage, AntennaOpenAndShortAndRecovery) {
  for (const OutageKind kind : {OutageKind::kOpen, OutageKind::kShort, OutageKind::kBlockage}) {
    Rig rig(std::vector<FaultEvent>{make_event(FaultType::kOutage, 5.0, 10.0, static_cast<int>(kind))});
    int back_at = -1;
    for (int s = 0; s < 30; ++s) {
      const receiver::Fix& f = rig.step(s);
      const bool out = s >= 5 && s < 15;
      if (s < 5) {
        EXPECT_TRUE(gnss_fix(f)) << s;
      }
      if (out) {
        // Nothing tracked: the filter dead-reckons for its coast limit, then no fix.
        EXPECT_FALSE(gnss_fix(f)) << s;
        EXPECT_EQ(f.num_tracked, 0);
        if (s >= 5 + 4) {
          EXPECT_EQ(f.type, receiver::FixType::kNone) << s;
        }
        EXPECT_EQ(f.antenna_status, kind == OutageKind::kOpen    ? receiver::AntennaStatus::kOpen
                                    : kind == OutageKind::kShort ? receiver::AntennaStatus::kShort
                                                                 : receiver::AntennaStatus::kOk);
      } else {
        EXPECT_EQ(f.antenna_status, receiver::AntennaStatus::kOk);
      }
      if (s >= 15 && back_at < 0 && f.type == receiver::FixType::k3D) back_at = s;
    }
    // Recovery through reacquisition: a few seconds, not at once.
    EXPECT_GT(back_at, 15);
    EXPECT_LE(back_at, 20);
  }
}

TEST(FaultStage, SkyBlockRemovesTheSectorOnly) {
  FaultEvent e = make_event(FaultType::kSkyBlock, 0.0);
  e.put(Param::kAzFromDeg, 270.0);
  e.put(Param::kAzToDeg, 90.0);  // the northern half, through north
  Rig rig(std::vector<FaultEvent>{e});
  const receiver::Fix& f = rig.step(0);
  int north = 0, south = 0;
  for (int i = 0; i < f.num_sats; ++i) {
    const receiver::SatInfo& s = f.sats[i];
    if (!s.above_mask) continue;
    const double az = s.az_rad / kDegToRad;
    if (az >= 270.0 || az <= 90.0) {
      EXPECT_FALSE(s.tracked) << s.sat.prn();
      ++north;
    } else {
      south += s.tracked;
    }
  }
  EXPECT_GT(north, 0);
  EXPECT_GT(south, 0);
}

TEST(FaultStage, SameEventsSameSeedSameFixes) {
  FaultEvent j = make_event(FaultType::kJammer, 0.0, 50.0);
  j.put(Param::kJsDb, Ramp{20.0, 40.0});
  FaultEvent s = make_event(FaultType::kSpoofer, 5.0, kForever_s, static_cast<int>(SpoofMode::kDrag));
  s.put(Param::kDragSpeedMS, 1.0);
  const std::vector<FaultEvent> ev{j, s};
  Rig a(ev), b(ev);
  for (int t = 0; t < 40; ++t) {
    const receiver::Fix fa = a.step(t);
    const receiver::Fix& fb = b.step(t);
    EXPECT_EQ(fa.pos_m, fb.pos_m);
    EXPECT_EQ(fa.num_used, fb.num_used);
  }
}

TEST(FaultStage, AnEmptyStageChangesNothing) {
  Rig with({}, true), without({}, false);
  for (int t = 0; t < 20; ++t) {
    const receiver::Fix fa = with.step(t);
    EXPECT_EQ(fa.pos_m, without.step(t).pos_m);
  }
}

TEST(FaultStage, InjectCountsFromNowAndClearEndsEverything) {
  Rig rig;
  for (int t = 0; t <= 30; ++t) rig.step(t);
  rig.rx.faults()->inject(std::vector<FaultEvent>{make_event(FaultType::kOutage, 5.0, 5.0)});
  for (int t = 31; t < 40; ++t) {
    const receiver::Fix& f = rig.step(t);
    EXPECT_EQ(f.num_tracked == 0, t >= 35) << t;  // starts 5 s after the injection
  }
  EXPECT_EQ(rig.rx.faults()->status().size(), 1u);
  EXPECT_TRUE(rig.rx.faults()->status()[0].active);
  rig.rx.faults()->inject(std::vector<FaultEvent>{make_event(FaultType::kOutage, 0.0)});
  for (int t = 40; t < 50; ++t) EXPECT_EQ(rig.step(t).num_tracked, 0) << t;  // the second outage holds
  EXPECT_EQ(rig.rx.faults()->active_count(), 1);
  rig.rx.faults()->clear();
  EXPECT_TRUE(rig.rx.faults()->status().empty());
  int back_at = -1;
  for (int t = 50; t < 60 && back_at < 0; ++t)
    if (rig.step(t).type == receiver::FixType::k3D) back_at = t;
  EXPECT_GT(back_at, 50);  // through reacquisition
  EXPECT_LE(back_at, 55);
}

// `ctl clear` switches a spoofer off: the loops it dragged away lose lock and
// reacquire the authentic signals, epoch for epoch as when it ends by itself.
TEST(FaultStage, ClearEndsASpooferAsItsOwnEndDoes) {
  FaultEvent e = make_event(FaultType::kSpoofer, 0.0, kForever_s, static_cast<int>(SpoofMode::kDrag));
  e.put(Param::kDragSpeedMS, 5.0);
  FaultEvent ends = e;
  ends.duration_s = 10.0;
  Rig cleared(std::vector<FaultEvent>{e}), ended(std::vector<FaultEvent>{ends});
  for (int t = 0; t < 10; ++t) {
    cleared.step(t);
    ended.step(t);
  }
  ASSERT_GT(cleared.error(cleared.rx.last_fix()).norm(), 30.0);  // dragged 45 m
  cleared.rx.faults()->clear();
  int coasting = 0;
  for (int t = 10; t < 20; ++t) {
    const receiver::Fix& a = cleared.step(t);
    const receiver::Fix& b = ended.step(t);
    EXPECT_EQ(a.type, b.type) << t;
    EXPECT_EQ(a.num_used, b.num_used) << t;
    EXPECT_EQ(a.pos_m, b.pos_m) << t;
    coasting += a.num_used == 0;
  }
  EXPECT_GE(coasting, 1);  // the loops let go
  EXPECT_LT(cleared.error(cleared.rx.last_fix()).norm(), 10.0);  // and found the authentic signals
}

// A receiver restart (CFG-RST, a reload) builds a new pipeline; the faults
// in the world around it go on where they were.
TEST(FaultStage, AStageHandedToANewPipelineKeepsItsTimeLine) {
  Rig rig(std::vector<FaultEvent>{make_event(FaultType::kOutage, 5.0, 10.0)});
  for (int t = 0; t < 8; ++t) rig.step(t);
  EXPECT_TRUE(rig.rx.faults()->status()[0].active);
  pipeline::Pipeline fresh(test::test_store(), pipeline::PipelineConfig{});
  fresh.adopt_faults(rig.rx.take_faults());
  EXPECT_EQ(rig.rx.faults(), nullptr);
  ASSERT_NE(fresh.faults(), nullptr);
  world::Truth truth = rig.truth;
  for (int t = 8; t < 15; ++t) {  // the outage still holds: nothing tracked
    truth.t = rig.t0 + Rig::kWarmUp_s + t;
    EXPECT_EQ(fresh.step(truth.t, truth).num_tracked, 0) << t;
  }
  EXPECT_NEAR(fresh.faults()->status()[0].elapsed_s, 9.0, 1e-9);  // 14 s - 5 s
  int tracked_at = -1;
  for (int t = 15; t < 25 && tracked_at < 0; ++t) {  // it ends at 15 s as scripted
    truth.t = rig.t0 + Rig::kWarmUp_s + t;
    if (fresh.step(truth.t, truth).num_tracked > 0) tracked_at = t;
  }
  EXPECT_GE(tracked_at, 15);
  EXPECT_LE(tracked_at, 17);  // through the new receiver's acquisition
  EXPECT_FALSE(fresh.faults()->status()[0].active);
}

TEST(FaultStage, BadInjectionChangesNothing) {
  Rig rig;
  FaultEvent bad = make_event(FaultType::kSatellite, 0.0);  // no prn
  EXPECT_THROW(rig.rx.faults()->inject(std::vector<FaultEvent>{make_event(FaultType::kOutage, 0.0), bad}), Error);
  EXPECT_TRUE(rig.rx.faults()->empty());
}

TEST(FaultStage, StepDoesNotAllocateWithEveryFaultActive) {
  std::vector<FaultEvent> ev;
  FaultEvent j = make_event(FaultType::kJammer, 0.0, 400.0, static_cast<int>(JammerKind::kCw));
  j.put(Param::kEirpDbw, Ramp{-40.0, -20.0});
  j.put(Param::kLatDeg, 48.875);
  j.put(Param::kLonDeg, 2.296);
  ev.push_back(j);
  FaultEvent s = make_event(FaultType::kSpoofer, 0.0, kForever_s, static_cast<int>(SpoofMode::kDrag));
  s.put(Param::kDragSpeedMS, 1.0);
  s.put(Param::kPushRateNsS, 10.0);
  ev.push_back(s);
  FaultEvent b = make_event(FaultType::kSkyBlock, 0.0);
  b.put(Param::kAzFromDeg, 100.0);
  b.put(Param::kAzToDeg, 140.0);
  b.put(Param::kLossDb, 6.0);
  ev.push_back(b);
  FaultEvent sat = make_event(FaultType::kSatellite, 0.0);
  sat.put(Param::kPrn, 4);
  sat.put(Param::kEphAlongM, 50.0);
  sat.put(Param::kRateMS, 0.5);
  ev.push_back(sat);
  ev.push_back(make_event(FaultType::kOutage, 300.0, 20.0, static_cast<int>(OutageKind::kOpen)));
  Rig rig(ev);
  for (int k = 0; k < 10; ++k) rig.step(k);  // warm-up
  const long before = support::allocation_count();
  for (int k = 10; k < 400; ++k) rig.step(k);
  EXPECT_EQ(support::allocation_count() - before, 0);
}

}  // namespace
}  // namespace gnssemu::faults
