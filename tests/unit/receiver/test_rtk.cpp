// SPDX-License-Identifier: Apache-2.0
// The differential stage from the observables: a base receiver and a rover
// under one shared sky, the base's raw epoch handed to the rover as its
// corrections (as the RTCM decoder would fill them).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <deque>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/receiver/rtk/lambda.hpp"
#include "core/world/sky/shared_sky.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver {
namespace {

using test::kSite;
using test::kToe;

pipeline::PipelineConfig rig_config(std::uint64_t seed, bool smooth_sky) {
  pipeline::PipelineConfig c;
  c.world.seed = seed;
  c.world.sky_seed = 1;
  if (smooth_sky) {
    // The broadcast orbit/clock residual and the TEC perturbation are
    // first-order Gauss-Markov paths: 4 cm per second per satellite at the
    // defaults, where real ones change by millimetres.
    c.world.errors.orbit_clock.sigma_m = 0.0;
    c.world.atmosphere.ionosphere.perturbation.sigma = 0.0;
  }
  return c;
}

Ecef offset_enu(const Ecef& from, double e_m, double n_m, double u_m) {
  const Lla l = geo::lla_from_ecef(from);
  return Ecef(from + geo::enu_to_ecef_vector(Enu(e_m, n_m, u_m), l.lat_rad, l.lon_rad));
}

Enu error_enu(const Ecef& pos, const Ecef& truth) {
  const Lla l = geo::lla_from_ecef(truth);
  return geo::ecef_to_enu_vector(pos - truth, l.lat_rad, l.lon_rad);
}

/// Base and rover on one sky; corrections delayed by latency epochs.
// Squared heading error of a relative position against truth_rad, deg^2.
double heading_error_deg2(const RelativePosition& r, double truth_rad) {
  const double d = std::remainder(r.heading_rad - truth_rad, 2.0 * kPi) / kDegToRad;
  return d * d;
}

class RtkRig {
public:
  /// latency: epochs between the base's measurement and its use (0: time-matched).
  /// sky: the satellites; systems and bands: what base and rover track.
  RtkRig(const Ecef& base_m, const Ecef& rover_m, int latency = 0, bool smooth_sky = false,
         const std::vector<orbit::Ephemeris>& sky = test::nominal_constellation(kToe, 5),
         SystemSet systems = SystemSet::only(GnssSystem::kGps), int bands = 1)
      : store_(sky),
        base_cfg_(tracking(rig_config(7, smooth_sky), systems, bands)),
        rover_cfg_(tracking(rig_config(11, smooth_sky), systems, bands)),
        sky_(store_, SystemSet::all(), world::sky_errors_config(base_cfg_.world)),
        base_(store_, base_cfg_),
        rover_(store_, rover_cfg_),
        base_m_(base_m),
        rover_m_(rover_m),
        latency_(latency) {
    corr_.station.station_id = 42;
    corr_.station.position_valid = true;
    corr_.station.arp_ecef_m = base_m;
    rover_.receiver().set_corrections(&corr_);
  }

  /// One epoch at t; the rover's antenna moves with vel (ECEF m/s) from its start.
  const Fix& step(const time::GpsTime& t) {
    const Ecef ants[2] = {base_m_, rover_m_};
    sky_.update(t, ants);
    base_.step(sky_, test::truth_at(base_m_, t, base_vel_));
    queue_.push_back({base_.receiver().raw(), base_.last_fix().pos_m});
    if (!between_) deliver_due();
    const world::Observables& o = rover_.world().step(sky_, test::truth_at(rover_m_, t, rover_vel_),
                                                      rover_.receiver().config().elevation_mask_rad);
    obs_ = o;
    for (int i = 0; i < obs_.num_sats; ++i) {
      world::SatObservable& s = obs_.sats[i];
      s.carrier_phase_cycles += slip_cycles_;
      s.carrier_discontinuities += slips_;
    }
    const Fix& f = rover_.receiver().step(t, obs_);
    at_epoch_ = f.rel_pos;
    arrived_ = false;
    if (between_ && deliver_due()) arrived_ = rover_.receiver().on_corrections(obs_);
    return f;
  }
  /// Base epochs arrive between rover epochs: base epoch k after rover
  /// epoch k + lag, then Receiver::on_corrections (step's Fix is updated).
  void arrive_between(int lag) {
    between_ = true;
    latency_ = lag;
  }
  /// In arrive_between mode: the last step's rel_pos as its epoch's output
  /// had it, and whether the arrival after it gave a new one.
  const RelativePosition& at_epoch() const { return at_epoch_; }
  bool arrived() const { return arrived_; }
  /// Every satellite's carrier jumps by cycles from now on, flagged as a discontinuity.
  void slip_all(double cycles) {
    slip_cycles_ += cycles;
    ++slips_;
  }
  void move(const Ecef& base_m, const Ecef& rover_m) {
    base_m_ = base_m;
    rover_m_ = rover_m;
  }
  void set_velocity(const Ecef& v) { base_vel_ = rover_vel_ = v; }
  void set_rover_velocity(const Ecef& v) { rover_vel_ = v; }
  void stop_link() { link_ = false; }
  /// The base antenna sees only its first n signals (a blocked antenna).
  void limit_base(int n) { base_meas_limit_ = n; }
  void set_moving_base() {
    moving_base_ = true;
    corr_.station.moving = true;
  }
  Corrections& corrections() { return corr_; }
  /// The base's GLONASS phase ranges as an unaligned receiver's: its code-phase
  /// biases (L1, L2; m) short of the aligned ones (RTCM 10403.3 DF421 = 0).
  void unalign_base_glonass(double l1_m, double l2_m) { unaligned_m_ = {l1_m, l2_m}; }
  /// The base epoch latency_ epochs old becomes the link's newest; false: none.
  bool deliver_due() {
    bool delivered = false;
    if (link_ && static_cast<int>(queue_.size()) > latency_) {
      corr_.obs = queue_.front().raw;
      // A moving base's 4072.0 carries its position of the same epoch.
      if (moving_base_) corr_.station.arp_ecef_m = queue_.front().pos_m;
      corr_.obs.num_meas = std::min(corr_.obs.num_meas, base_meas_limit_);
      for (int i = 0; i < corr_.obs.num_meas; ++i) {
        RawMeasurement& m = corr_.obs.meas[static_cast<std::size_t>(i)];
        if (m.sat.system != GnssSystem::kGlonass) continue;
        const double lam = kSpeedOfLight_m_s / signal_carrier_hz(m.signal, m.glonass_channel);
        m.carrier_phase_cycles -= unaligned_m_[static_cast<std::size_t>(signal_info(m.signal).band)] / lam;
      }
      corr_.obs_valid = corr_.obs.time_valid && corr_.obs.num_meas > 0;
      ++corr_.revision;
      delivered = true;
    }
    while (static_cast<int>(queue_.size()) > latency_) queue_.pop_front();
    return delivered;
  }
  const Ecef& rover_truth() const { return rover_m_; }
  const Ecef& base_truth() const { return base_m_; }
  const rtk::RtkStatus& status() { return rover_.receiver().rtk().status(); }

private:
  orbit::EphemerisStore store_;
  pipeline::PipelineConfig base_cfg_, rover_cfg_;
  world::SharedSky sky_;
  pipeline::Pipeline base_, rover_;
  Ecef base_m_, rover_m_;
  Ecef base_vel_, rover_vel_;
  int latency_;
  Corrections corr_;
  struct BaseEpoch {
    RawEpoch raw;
    Ecef pos_m;
  };
  std::deque<BaseEpoch> queue_;
  world::Observables obs_;
  double slip_cycles_ = 0.0;
  std::uint32_t slips_ = 0;
  bool link_ = true;
  bool moving_base_ = false;
  bool between_ = false;
  bool arrived_ = false;
  RelativePosition at_epoch_;
  int base_meas_limit_ = kMaxRawMeasurements;
  std::array<double, 2> unaligned_m_{};

  static pipeline::PipelineConfig tracking(pipeline::PipelineConfig c, SystemSet systems, int bands) {
    c.world.systems = systems;
    c.receiver.bands = bands;
    return c;
  }
};

double rtk_median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

TEST(RtkLambda, FindsTheIntegersOfACorrelatedFloatVector) {
  // Float ambiguities near (3, -2, 7) with strongly correlated errors.
  rtk::AmbMat q{};
  const int n = 3;
  const double c[3][3] = {{0.09, 0.085, 0.08}, {0.085, 0.09, 0.084}, {0.08, 0.084, 0.09}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) q[i][j] = c[i][j];
  rtk::AmbVec a{};
  a[0] = 3.21;
  a[1] = -1.78;
  a[2] = 7.19;
  rtk::Lambda lambda;
  const rtk::LambdaResult& r = lambda.solve(a, q, n);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.best[0], 3.0);
  EXPECT_EQ(r.best[1], -2.0);
  EXPECT_EQ(r.best[2], 7.0);
  EXPECT_GT(r.ratio(), 1.0);
}

TEST(Rtk, StaticOneKmFloatThenFixedCentimetres) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 800.0, 600.0, 5.0));
  double t_float = -1.0, t_fixed = -1.0;
  std::vector<double> h_err, h_acc;
  int fixed_epochs = 0;
  for (int i = 0; i < 600; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    ASSERT_TRUE(test::all_finite(f));
    if (f.carr_soln != CarrierSolution::kNone && t_float < 0.0) t_float = i;
    if (f.carr_soln == CarrierSolution::kFixed) {
      if (t_fixed < 0.0) t_fixed = i;
      ++fixed_epochs;
      const Enu e = error_enu(f.pos_m, rig.rover_truth());
      h_err.push_back(std::hypot(e.x, e.y));
      h_acc.push_back(f.h_acc_m);
      EXPECT_TRUE(f.diff_soln);
      EXPECT_EQ(f.ref_station_id, 42);
      EXPECT_NEAR(f.corr_age_s, 0.0, 0.01);
      EXPECT_TRUE(f.rel_pos.valid);
      EXPECT_NEAR(f.rel_pos.length_m, 1000.0, 0.5);
    }
  }
  std::printf("static 1 km: float at %.0f s, fixed at %.0f s, fixed %d/600 epochs, h error median %.4f m, "
              "h_acc median %.4f m, ratio %.1f, searches %u\n",
              t_float, t_fixed, fixed_epochs, rtk_median(h_err), rtk_median(h_acc), rig.status().ratio,
              rig.status().ar_attempts);
  EXPECT_GE(t_float, 0.0);
  EXPECT_GE(t_fixed, t_float);
  EXPECT_LT(t_fixed, 300.0);
  EXPECT_LE(rtk_median(h_err), 0.02);
  EXPECT_LT(rtk_median(h_acc), 0.03);
}

TEST(Rtk, OneSecondOldBaseEpochStillFixes) {
  // The base's epoch one second older than the rover's: each side's
  // geometry at its own time. Smooth sky errors (see rig_config).
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 800.0, 600.0, 5.0), 1, true);
  std::vector<double> h_err;
  double t_fixed = -1.0;
  for (int i = 0; i < 300; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    if (f.carr_soln != CarrierSolution::kFixed) continue;
    if (t_fixed < 0.0) t_fixed = i;
    EXPECT_NEAR(f.corr_age_s, 1.0, 0.01);
    const Enu e = error_enu(f.pos_m, rig.rover_truth());
    h_err.push_back(std::hypot(e.x, e.y));
  }
  std::printf("1 s old base epoch: fixed at %.0f s, %zu/300 fixed, h error median %.4f m\n", t_fixed, h_err.size(),
              rtk_median(h_err));
  EXPECT_GT(h_err.size(), 200u);
  EXPECT_LE(rtk_median(h_err), 0.02);
}

TEST(Rtk, CycleSlipsFallBackToFloatAndRefix) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, -300.0, 900.0, 0.0));
  int t_fixed = -1;
  for (int i = 0; i < 400 && t_fixed < 0; ++i)
    if (rig.step(kToe + static_cast<double>(i)).carr_soln == CarrierSolution::kFixed) t_fixed = i;
  ASSERT_GE(t_fixed, 0);
  rig.slip_all(17.0);
  const time::GpsTime t_slip = kToe + static_cast<double>(t_fixed + 1);
  const Fix& f = rig.step(t_slip);
  EXPECT_EQ(f.carr_soln, CarrierSolution::kFloat);
  int refix = -1;
  for (int i = 1; i < 400 && refix < 0; ++i)
    if (rig.step(t_slip + static_cast<double>(i)).carr_soln == CarrierSolution::kFixed) refix = i;
  std::printf("slips: fixed at %d s, re-fixed %d s after every satellite slipped\n", t_fixed, refix);
  EXPECT_GT(refix, 0);
}

TEST(Rtk, StoppedCorrectionsGiveDgnssThenStandaloneAfterTheTimeout) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 500.0, 0.0, 0.0));
  time::GpsTime t = kToe;
  for (int i = 0; i < 120; ++i, t = t + 1.0) rig.step(t);
  ASSERT_TRUE(rig.step(t).diff_soln);
  rig.stop_link();
  const time::GpsTime t_stop = t;
  bool dgnss_seen = false;
  std::vector<double> dgnss_err, dgnss_acc;
  for (int i = 1; i <= 70; ++i) {
    const Fix& f = rig.step(t_stop + static_cast<double>(i));
    const double age = static_cast<double>(i);
    if (age <= 30.0) {
      EXPECT_TRUE(f.diff_soln) << i;
    } else if (age <= 59.5) {
      EXPECT_TRUE(f.diff_soln) << i;
      EXPECT_EQ(f.carr_soln, CarrierSolution::kNone) << i;
      dgnss_seen = true;
      const Enu e = error_enu(f.pos_m, rig.rover_truth());
      dgnss_err.push_back(std::hypot(e.x, e.y));
      dgnss_acc.push_back(f.h_acc_m);
    } else if (age > 60.5) {
      EXPECT_FALSE(f.diff_soln) << i;
      EXPECT_EQ(f.carr_soln, CarrierSolution::kNone);
      EXPECT_LT(f.corr_age_s, 0.0);
      EXPECT_EQ(f.type, FixType::k3D);
    }
  }
  EXPECT_TRUE(dgnss_seen);
  std::printf("DGNSS (corrections 30-60 s old): horizontal error median %.3f m, hAcc median %.3f m\n",
              rtk_median(dgnss_err), rtk_median(dgnss_acc));
}

TEST(Rtk, WrongBaseCoordinatesOffsetTheRoverByTheSameVector) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 200.0, 300.0, 0.0));
  const Ecef wrong = offset_enu(base, 0.40, -0.25, 0.30);
  rig.corrections().station.arp_ecef_m = wrong;
  std::vector<double> de, dn, du;
  for (int i = 0; i < 500; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    if (f.carr_soln != CarrierSolution::kFixed) continue;
    const Enu e = error_enu(f.pos_m, rig.rover_truth());
    de.push_back(e.x);
    dn.push_back(e.y);
    du.push_back(e.z);
  }
  ASSERT_FALSE(de.empty());
  EXPECT_NEAR(rtk_median(de), 0.40, 0.03);
  EXPECT_NEAR(rtk_median(dn), -0.25, 0.03);
  EXPECT_NEAR(rtk_median(du), 0.30, 0.06);
}

TEST(Rtk, MovingBaselineOneMetreHeading) {
  const Ecef base = geo::ecef_from_lla(kSite);
  const double heading = 30.0 * kDegToRad;
  RtkRig rig(base, offset_enu(base, std::sin(heading), std::cos(heading), 0.0));
  rig.set_moving_base();
  std::vector<double> err_deg;
  double acc_deg = 0.0;
  int valid = 0, fixed = 0;
  for (int i = 0; i < 400; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    ASSERT_TRUE(test::all_finite(f));
    EXPECT_FALSE(f.diff_soln);  // the rover's own position stays standalone
    if (!f.rel_pos.heading_valid) continue;
    ++valid;
    if (f.rel_pos.carr_soln != CarrierSolution::kFixed) continue;
    ++fixed;
    double d = (f.rel_pos.heading_rad - heading) / kDegToRad;
    d = std::remainder(d, 360.0);
    err_deg.push_back(d);
    acc_deg = f.rel_pos.acc_heading_rad / kDegToRad;
    EXPECT_NEAR(f.rel_pos.length_m, 1.0, 0.03);
  }
  double ss = 0.0;
  for (double d : err_deg) ss += d * d;
  const double rms = err_deg.empty() ? NAN : std::sqrt(ss / static_cast<double>(err_deg.size()));
  std::printf("moving baseline 1 m: heading valid %d, fixed %d of 400 epochs, heading error rms %.3f deg, "
              "accHeading %.3f deg\n", valid, fixed, rms, acc_deg);
  ASSERT_GT(fixed, 100);
  EXPECT_LT(rms, 1.5);
}

TEST(Rtk, MovingBaseAtSpeedTimeMatchesALateBase) {
  // The base's epoch reaches the rover one epoch late (through the host)
  // while the vehicle drives at 5 m/s: the rover solves its own epoch of the
  // base's time, so the baseline is the antennas' and comes out one epoch late.
  const Ecef base = geo::ecef_from_lla(kSite);
  const double heading = 30.0 * kDegToRad;
  const Ecef rover = offset_enu(base, std::sin(heading), std::cos(heading), 0.0);
  RtkRig rig(base, rover, 1);
  rig.set_moving_base();
  const Lla at = geo::lla_from_ecef(base);
  const Vec3 vel = geo::enu_to_ecef_vector(Enu(5.0, 0.0, 0.0), at.lat_rad, at.lon_rad);
  rig.set_velocity(Ecef(vel));
  int late = 0, fixed = 0;
  double worst_length_m = 0.0, sum_heading2 = 0.0;
  for (int i = 0; i < 300; ++i) {
    const double t_s = static_cast<double>(i);
    rig.move(Ecef(base + vel * t_s), Ecef(rover + vel * t_s));
    const time::GpsTime t = kToe + t_s;
    const Fix& f = rig.step(t);
    ASSERT_TRUE(test::all_finite(f));
    if (!f.rel_pos.valid) continue;
    ASSERT_TRUE(f.rel_pos.late) << i;
    EXPECT_NEAR(t - f.rel_pos.t, 1.0, 1e-9) << i;
    ++late;
    if (f.rel_pos.carr_soln != CarrierSolution::kFixed) continue;
    ++fixed;
    worst_length_m = std::max(worst_length_m, std::fabs(f.rel_pos.length_m - 1.0));
    sum_heading2 += heading_error_deg2(f.rel_pos, heading);
  }
  const rtk::RtkStatus& st = rig.status();
  std::printf("moving base 1 m at 5 m/s, base 1 epoch late: %d baselines, %d fixed of 300 epochs, worst length error "
              "%.3f m, heading error RMS %.3f deg; matched %u, missed %u, delay %.1f s\n", late, fixed, worst_length_m,
              std::sqrt(sum_heading2 / fixed), st.moving_base_matched, st.moving_base_missed, st.moving_base_delay_s);
  ASSERT_GT(fixed, 100);
  EXPECT_LT(worst_length_m, 0.03);  // pairing with the previous base epoch would read 5 m off
  EXPECT_DOUBLE_EQ(st.moving_base_delay_s, 1.0);
}

TEST(Rtk, MovingBaselineHeadingFollowsFastTurns) {
  // The vehicle turns in place with the base antenna on the turning axis and
  // the rover's 1 m away: 30 deg/s (a car's hard turn) and 90 deg/s (a
  // multicopter's yaw), the base's epoch arriving one epoch late. Each
  // baseline is the antennas' at its own time (time-matched), so its heading
  // is the turn's heading at that time, every epoch of the sweep.
  for (const double rate_deg_s : {3.0, 30.0, 90.0}) {
    SCOPED_TRACE(rate_deg_s);
    const Ecef base = geo::ecef_from_lla(kSite);
    const Lla at = geo::lla_from_ecef(base);
    const double w_rad_s = rate_deg_s * kDegToRad;
    RtkRig rig(base, offset_enu(base, 0.0, 1.0, 0.0), 1);
    rig.set_moving_base();
    int baselines = 0, fixed = 0;
    double sum_heading2 = 0.0, worst_length_m = 0.0;
    for (int i = 0; i < 300; ++i) {
      const double t_s = static_cast<double>(i);
      const double h = w_rad_s * t_s;
      rig.move(base, offset_enu(base, std::sin(h), std::cos(h), 0.0));
      rig.set_rover_velocity(
          Ecef(geo::enu_to_ecef_vector(Enu(w_rad_s * std::cos(h), -w_rad_s * std::sin(h), 0.0), at.lat_rad, at.lon_rad)));
      const Fix& f = rig.step(kToe + t_s);
      ASSERT_TRUE(test::all_finite(f));
      if (!f.rel_pos.valid) continue;
      ++baselines;
      if (f.rel_pos.carr_soln != CarrierSolution::kFixed) continue;
      ++fixed;
      const double h_then = w_rad_s * (f.rel_pos.t - kToe);
      sum_heading2 += heading_error_deg2(f.rel_pos, h_then);
      worst_length_m = std::max(worst_length_m, std::fabs(f.rel_pos.length_m - 1.0));
    }
    const double rms = fixed > 0 ? std::sqrt(sum_heading2 / fixed) : NAN;
    std::printf("turning in place at %.0f deg/s, 1 m baseline, base 1 epoch late: %d baselines, %d fixed of 300, "
                "heading error RMS %.3f deg, worst length error %.3f m\n",
                rate_deg_s, baselines, fixed, rms, worst_length_m);
    ASSERT_GT(fixed, 100);
    EXPECT_LT(rms, 1.5);
    EXPECT_LT(worst_length_m, 0.03);
  }
}

TEST(Rtk, MovingBaseEpochSolvedWhenItArrivesWithinTheEpoch) {
  // The base's epoch k arrives after the rover's epoch k and before k + 1:
  // the rover's output of epoch k leaves RELPOSNED out (held), and the
  // arrival solves epoch k at once (on_corrections), as the F9P sends it.
  // The data of MovingBaseAtSpeedTimeMatchesALateBase: the same baselines.
  const Ecef base = geo::ecef_from_lla(kSite);
  const double heading = 30.0 * kDegToRad;
  const Ecef rover = offset_enu(base, std::sin(heading), std::cos(heading), 0.0);
  RtkRig rig(base, rover);
  rig.set_moving_base();
  rig.arrive_between(0);
  const Lla at = geo::lla_from_ecef(base);
  const Vec3 vel = geo::enu_to_ecef_vector(Enu(5.0, 0.0, 0.0), at.lat_rad, at.lon_rad);
  rig.set_velocity(Ecef(vel));
  int early = 0, fixed = 0, held = 0;
  double worst_length_m = 0.0, sum_heading2 = 0.0;
  for (int i = 0; i < 300; ++i) {
    const double t_s = static_cast<double>(i);
    rig.move(Ecef(base + vel * t_s), Ecef(rover + vel * t_s));
    const time::GpsTime t = kToe + t_s;
    const Fix& f = rig.step(t);
    ASSERT_TRUE(test::all_finite(f));
    EXPECT_FALSE(rig.at_epoch().late) << i;
    if (i >= 3) {
      // From the second early solution on, every epoch's output waits for its base epoch.
      EXPECT_TRUE(rig.at_epoch().held) << i;
      EXPECT_FALSE(rig.at_epoch().valid) << i;
      ASSERT_TRUE(rig.arrived()) << i;
    }
    held += rig.at_epoch().held ? 1 : 0;
    if (!rig.arrived()) continue;
    ++early;
    EXPECT_FALSE(f.rel_pos.held) << i;
    EXPECT_FALSE(f.rel_pos.late) << i;
    EXPECT_NEAR(f.rel_pos.t - t, 0.0, 1e-9) << i;  // the epoch just output: RELPOSNED's iTOW = its NAV-PVT's
    if (f.rel_pos.carr_soln != CarrierSolution::kFixed) continue;
    ++fixed;
    worst_length_m = std::max(worst_length_m, std::fabs(f.rel_pos.length_m - 1.0));
    sum_heading2 += heading_error_deg2(f.rel_pos, heading);
  }
  const rtk::RtkStatus& st = rig.status();
  std::printf("moving base 1 m at 5 m/s, base epoch arriving within the epoch: %d solved on arrival (%d outputs "
              "held for it), %d fixed of 300 epochs, worst length error %.3f m, heading error RMS %.3f deg; matched "
              "%u (early %u), missed %u\n", early, held, fixed, worst_length_m, std::sqrt(sum_heading2 / fixed),
              st.moving_base_matched, st.moving_base_early, st.moving_base_missed);
  EXPECT_GE(early, 297);
  // The first arrival solves an epoch whose refObsMiss already went out: solved, not sent again.
  EXPECT_EQ(st.moving_base_early, static_cast<std::uint32_t>(early + 1));
  ASSERT_GT(fixed, 250);
  EXPECT_LT(worst_length_m, 0.03);  // pairing with another epoch's base would read 1 m off
  EXPECT_DOUBLE_EQ(st.moving_base_delay_s, 0.0);
}

TEST(Rtk, MovingBaseEpochArrivingAfterTheNextFallsBackToLate) {
  // A slow link: base epoch k arrives after the rover's epoch k + 1. It is
  // not solved on arrival (the rover has moved on) but with the rover's
  // next epoch, late, with its own epoch's time.
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 0.0, 1.0, 0.0));
  rig.set_moving_base();
  rig.arrive_between(1);
  int late = 0;
  for (int i = 0; i < 60; ++i) {
    const time::GpsTime t = kToe + static_cast<double>(i);
    const Fix& f = rig.step(t);
    EXPECT_FALSE(rig.arrived()) << i;
    EXPECT_FALSE(rig.at_epoch().held) << i;
    if (!f.rel_pos.valid) continue;
    ASSERT_TRUE(f.rel_pos.late) << i;
    EXPECT_NEAR(t - f.rel_pos.t, 2.0, 1e-9) << i;  // arrived after epoch k + 1, solved at k + 2
    ++late;
  }
  EXPECT_GE(late, 55);
  EXPECT_EQ(rig.status().moving_base_early, 0u);
}

TEST(Rtk, MovingBaseGivesUpOnEpochsTheBaseNeverSends) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 0.0, 1.0, 0.0), 1);
  rig.set_moving_base();
  for (int i = 0; i < 29; ++i) rig.step(kToe + static_cast<double>(i));
  ASSERT_TRUE(rig.step(kToe + 29.0).rel_pos.valid);  // rover epoch 28 with base epoch 28
  rig.stop_link();
  const std::uint32_t missed0 = rig.status().moving_base_missed;
  for (int i = 30; i < 35; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    EXPECT_FALSE(f.rel_pos.valid) << i;
    EXPECT_TRUE(f.rel_pos.ref_obs_miss) << i;
    EXPECT_TRUE(f.rel_pos.moving_base) << i;
  }
  // Held at most 1 s (moving_base_max_age_s) at 1 Hz: epochs 29..32 are given up at 31..34.
  EXPECT_EQ(rig.status().moving_base_missed - missed0, 4u);
}

TEST(Rtk, HeadingLostWhenTheBaseAntennaIsBlocked) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 0.0, 1.0, 0.0));
  rig.set_moving_base();
  bool fixed = false;
  for (int i = 0; i < 100; ++i) fixed = rig.step(kToe + static_cast<double>(i)).rel_pos.carr_soln == CarrierSolution::kFixed;
  ASSERT_TRUE(fixed);
  rig.limit_base(3);
  for (int i = 100; i < 110; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    EXPECT_FALSE(f.rel_pos.heading_valid) << i;
    EXPECT_EQ(f.type, FixType::k3D);  // the rover's own fix goes on
  }
  rig.limit_base(kMaxRawMeasurements);
  int back = -1;
  for (int i = 110; i < 300 && back < 0; ++i)
    if (rig.step(kToe + static_cast<double>(i)).rel_pos.carr_soln == CarrierSolution::kFixed) back = i - 110;
  std::printf("heading back (fixed) %d s after the base antenna sees the sky again\n", back);
  EXPECT_GE(back, 0);
}

TEST(Rtk, BaseFarAwayStaysFloatAndCounts) {
  const Ecef base = geo::ecef_from_lla(kSite);
  RtkRig rig(base, offset_enu(base, 150.0e3, 0.0, 0.0));
  int fixed = 0, floats = 0;
  for (int i = 0; i < 200; ++i) {
    const Fix& f = rig.step(kToe + static_cast<double>(i));
    ASSERT_TRUE(test::all_finite(f));
    fixed += f.carr_soln == CarrierSolution::kFixed;
    floats += f.carr_soln == CarrierSolution::kFloat;
  }
  EXPECT_EQ(fixed, 0);
  EXPECT_GT(floats, 0);
  EXPECT_GT(rig.status().long_baseline, 0u);
  EXPECT_GT(rig.status().baseline_big, 0u);
}

// GPS and, on every GPS satellite, a GLONASS one (from its state at toe) on
// channel prn % 14 - 7: all channels, negative ones among them.
std::vector<orbit::Ephemeris> gps_glonass_sky() {
  std::vector<orbit::Ephemeris> v = test::nominal_constellation(kToe, 5);
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n && v[i].sat.number <= 24; ++i) {
    const orbit::SatState st = orbit::sat_state(v[i], kToe);
    orbit::Ephemeris r;
    r.sat = SatId(GnssSystem::kGlonass, v[i].sat.number);
    r.toe = r.toc = kToe;
    r.pos_m = st.pos_m;
    r.vel_m_s = st.vel_m_s;
    r.glo_channel = v[i].sat.number % 14 - 7;
    v.push_back(r);
  }
  return v;
}

// GLONASS ambiguities are fixed with the base's 1230: at once when it says
// the phase ranges are aligned (as a u-blox F9 base does), after adding its
// biases when they are not; never without it or with unaligned ranges and no
// biases (then GPS alone is fixed).
TEST(Rtk, GlonassFixedWithAlignedOrBiasCorrectedBasePhase) {
  struct Outcome {
    long fixed_dd = 0;
    int fixed_epochs = 0;
    double h_err_m = NAN;
  };
  const Ecef base = geo::ecef_from_lla(kSite);
  const std::vector<orbit::Ephemeris> sky = gps_glonass_sky();
  const SystemSet systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGlonass);
  constexpr double kL1Cpb_m = 20.0, kL2Cpb_m = -12.0;
  auto run = [&](bool sent, bool aligned, bool biases, bool unaligned_phase) {
    RtkRig rig(base, offset_enu(base, 300.0, 400.0, 2.0), 0, true, sky, systems, 2);
    Corrections& c = rig.corrections();
    c.glonass_cpb_aligned = aligned;
    c.glonass_cpb_m = biases ? std::array<double, 4>{kL1Cpb_m, 0.0, kL2Cpb_m, 0.0} : std::array<double, 4>{};
    c.glonass_cpb_valid = sent && (aligned || biases);  // as the decoder has it
    if (unaligned_phase) rig.unalign_base_glonass(kL1Cpb_m, kL2Cpb_m);
    Outcome o;
    std::vector<double> h;
    for (int i = 0; i < 240; ++i) {
      const Fix& f = rig.step(kToe + static_cast<double>(i));
      if (f.carr_soln != CarrierSolution::kFixed) continue;
      ++o.fixed_epochs;
      o.fixed_dd += rig.status().num_fixed_dd;
      const Enu e = error_enu(f.pos_m, rig.rover_truth());
      h.push_back(std::hypot(e.x, e.y));
    }
    o.h_err_m = rtk_median(h);
    return o;
  };
  const Outcome none = run(false, false, false, false);
  const Outcome f9 = run(true, true, false, false);
  const Outcome corrected = run(true, false, true, true);
  const Outcome no_biases = run(true, false, false, true);
  std::printf("GLONASS AR: fixed DDs (epochs) without 1230 %ld (%d), aligned base %ld (%d), unaligned + biases %ld (%d), "
              "unaligned without biases %ld (%d); h error median %.4f / %.4f / %.4f / %.4f m\n",
              none.fixed_dd, none.fixed_epochs, f9.fixed_dd, f9.fixed_epochs, corrected.fixed_dd,
              corrected.fixed_epochs, no_biases.fixed_dd, no_biases.fixed_epochs, none.h_err_m, f9.h_err_m,
              corrected.h_err_m, no_biases.h_err_m);
  EXPECT_GT(none.fixed_epochs, 100);
  // GLONASS double differences held on top of GPS's.
  EXPECT_GT(f9.fixed_dd, none.fixed_dd + 10 * f9.fixed_epochs);
  EXPECT_LE(f9.h_err_m, 0.02);
  // The biases restore the aligned ranges: the same solution.
  EXPECT_EQ(corrected.fixed_epochs, f9.fixed_epochs);
  EXPECT_EQ(corrected.fixed_dd, f9.fixed_dd);
  EXPECT_NEAR(corrected.h_err_m, f9.h_err_m, 1e-4);
  // Unaligned without biases: GPS alone, as without 1230.
  EXPECT_EQ(no_biases.fixed_dd, none.fixed_dd);
}

}  // namespace
}  // namespace gnssemu::receiver
