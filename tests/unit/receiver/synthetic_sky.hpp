// SPDX-License-Identifier: Apache-2.0
#pragma once
// Test helpers: synthetic GPS ephemerides (a nominal Walker-like 6-plane
// constellation, and single satellites placed at a chosen azimuth/elevation)
// and Fix checks shared by the receiver tests.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/receiver/fix.hpp"
#include "core/world/truth.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/receiver/solution/solver.hpp"

namespace gnssemu::receiver::test {

using pipeline::PipelineConfig;

inline constexpr double kGpsSqrtA_sqrtm = 5153.7;  // A = 26 561.7 km (GPS nominal)

/// The epoch and site the acquisition, navigation and carrier tests share:
/// a nominal constellation's toe, a mid-latitude antenna.
inline const time::GpsTime kToe(2190, 300000.0);
inline const Lla kSite{45.0 * kDegToRad, 7.0 * kDegToRad, 300.0};

inline orbit::Ephemeris base_eph(int prn, const time::GpsTime& toe) {
  orbit::Ephemeris e;
  e.sat = SatId::gps(prn);
  e.toe = toe;
  e.toc = toe;
  // Realistic magnitudes of broadcast clock terms and TGD, varied per PRN.
  e.af0_s = 1.0e-5 * ((prn % 7) - 3);
  e.af1_s_s = 1.0e-12 * ((prn % 5) - 2);
  e.tgd_s = -1.0e-9 * (prn % 6);
  e.iode = e.iodc = 1;
  e.fit_interval_h = 48.0;  // validity +-24 h so long tests keep the same set
  e.sv_accuracy_m = 2.4;
  return e;
}

/// Nominal constellation: 6 planes (RAAN 60 deg apart), i = 55 deg, e = 0.005,
/// sats_per_plane slots per plane with phase offsets between planes.
inline std::vector<orbit::Ephemeris> nominal_constellation(const time::GpsTime& toe, int sats_per_plane = 4) {
  std::vector<orbit::Ephemeris> v;
  int prn = 1;
  for (int plane = 0; plane < 6; ++plane) {
    for (int slot = 0; slot < sats_per_plane && prn <= system_size(GnssSystem::kGps); ++slot, ++prn) {
      orbit::Ephemeris e = base_eph(prn, toe);
      e.sqrt_a_sqrtm = kGpsSqrtA_sqrtm;
      e.e = 0.005;
      e.i0_rad = 55.0 * kDegToRad;
      e.omega0_rad = (60.0 * plane + 17.0) * kDegToRad;
      e.omega_rad = 30.0 * kDegToRad;
      e.m0_rad = (360.0 / sats_per_plane * slot + 15.0 * plane) * kDegToRad;
      e.omega_dot_rad_s = -8.0e-9;
      e.delta_n_rad_s = 4.5e-9;
      e.crs_m = 20.0;
      e.cuc_rad = 1.0e-6;
      e.cis_rad = 5.0e-8;
      v.push_back(e);
    }
  }
  return v;
}

/// Circular polar orbit (radius |pos_m|) that puts the satellite at pos_m
/// (ECEF) at GPS time t_place.
inline orbit::Ephemeris placed_eph(int prn, const time::GpsTime& toe, const time::GpsTime& t_place,
                                   const Ecef& pos_m) {
  orbit::Ephemeris e = base_eph(prn, toe);
  const double r = pos_m.norm();
  e.sqrt_a_sqrtm = std::sqrt(r);
  e.i0_rad = kPi / 2.0;
  const double u = std::asin(pos_m.z / r);
  const double node = std::atan2(pos_m.y, pos_m.x);
  const double tk = t_place - toe;
  const double n = std::sqrt(kMuGps_m3_s2 / (r * r * r));
  e.m0_rad = u - n * tk;
  e.omega0_rad = node + kOmegaEarth_rad_s * (tk + toe.tow_s());
  return e;
}

/// ECEF point at GPS radius seen at (az, el) from rx.
inline Ecef sat_position_at(const Ecef& rx, const Lla& rx_lla, double az_rad, double el_rad) {
  const Vec3 los = geo::los_unit_ecef(az_rad, el_rad, rx_lla.lat_rad, rx_lla.lon_rad);
  const double r = kGpsSqrtA_sqrtm * kGpsSqrtA_sqrtm;
  const double b = rx.dot(los);
  const double rho = -b + std::sqrt(b * b - rx.dot(rx) + r * r);
  return Ecef(rx + los * rho);
}

/// The snapshot receiver: the solver alone every epoch on raw code,
/// satellites used as soon as their C/N0 allows (no search, no ephemeris
/// download), white Doppler noise of a fixed sigma. The tests of the world's
/// models and of the solver use it; acquisition, smoothing and the
/// navigation filter have tests of their own.
inline PipelineConfig snapshot(PipelineConfig c = {}) {
  c.receiver.filter.type = NavFilterType::kNone;
  c.receiver.acquisition.modelled = false;
  c.world.carrier.doppler_model = world::DopplerModel::kFixed;
  return c;
}

/// The pre-atmosphere world: no atmosphere, no receiver corrections, white
/// code noise of a fixed sigma (errors.thermal_sigma_m) and elevation-only
/// solver weights, seen by the snapshot receiver. The error is then exactly
/// GM orbit/clock + white noise.
inline PipelineConfig gm_white_world(PipelineConfig c = snapshot()) {
  c.world.atmosphere.ionosphere.enabled = false;
  c.world.atmosphere.troposphere.enabled = false;
  c.world.atmosphere.gases = false;
  c.receiver.solver.iono = atmosphere::IonoCorrection::kNone;
  c.receiver.solver.tropo = atmosphere::TropoCorrection::kNone;
  c.receiver.solver.sigma_c_m_sqrt_hz = 0.0;
  c.world.errors.thermal_model = world::ThermalModel::kFixed;
  return c;
}

/// The solver without atmospheric corrections or a C/N0 weight term (the
/// residual test at its default P_fa): for skies built without atmosphere.
inline SolverConfig plain_solver() {
  SolverConfig c;
  c.iono = atmosphere::IonoCorrection::kNone;
  c.tropo = atmosphere::TropoCorrection::kNone;
  c.sigma_c_m_sqrt_hz = 0.0;
  return c;
}

/// Valid truth at t: antenna at pos (ECEF m) moving at vel (ECEF m/s).
inline world::Truth truth_at(const Ecef& pos, const time::GpsTime& t, const Ecef& vel = {}) {
  world::Truth tr;
  tr.t = t;
  tr.pos_m = pos;
  tr.vel_m_s = vel;
  tr.valid = true;
  return tr;
}

/// Deterministic world (no random processes, no clock noise) with the
/// atmosphere of c, computed every epoch (no slow-term cache), seen by the
/// snapshot receiver.
inline PipelineConfig noiseless(PipelineConfig c = snapshot()) {
  c.world.errors.orbit_clock.sigma_m = 0.0;
  c.world.errors.thermal_model = world::ThermalModel::kFixed;
  c.world.errors.thermal_sigma_m = 0.0;
  c.world.errors.doppler_sigma_m_s = 0.0;
  c.world.clock.drift_noise_s_s_sqrt_s = 0.0;
  c.world.atmosphere.ionosphere.perturbation.sigma = 0.0;
  c.world.atmosphere.zwd_perturbation.sigma_m = 0.0;
  c.world.atmosphere.cache_refresh_s = 0.0;
  return c;
}

/// Error model off, clock without noise: the fix must equal the truth.
inline PipelineConfig errors_off_config() {
  PipelineConfig c = gm_white_world();
  c.world.errors.thermal_sigma_m = 0.0;
  c.world.errors.orbit_clock.sigma_m = 0.0;
  c.world.errors.doppler_sigma_m_s = 0.0;
  c.world.clock.drift_noise_s_s_sqrt_s = 0.0;
  return c;
}

inline bool all_finite(const Fix& f) {
  const double v[] = {f.pos_m.x, f.pos_m.y, f.pos_m.z, f.lla.lat_rad, f.lla.lon_rad, f.lla.height_m,
                      f.geoid_sep_m, f.vel_m_s.x, f.vel_m_s.y, f.vel_m_s.z, f.vel_enu_m_s.x, f.vel_enu_m_s.y,
                      f.vel_enu_m_s.z, f.speed_m_s, f.course_rad, f.climb_m_s, f.clock_bias_s,
                      f.clock_drift_s_s, f.dop.gdop, f.dop.pdop, f.dop.hdop, f.dop.vdop, f.dop.tdop,
                      f.sigma_uere_m, f.range_rms_m, f.sigma_e_m, f.sigma_n_m, f.sigma_u_m, f.h_acc_m,
                      f.v_acc_m, f.speed_acc_m_s, f.time_acc_s, f.t.tow_s()};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  for (const SatInfo& s : f.sats) {
    const double w[] = {s.az_rad, s.el_rad, s.cn0_dbhz, s.pseudorange_m, s.doppler_hz, s.residual_m};
    for (double x : w)
      if (!std::isfinite(x)) return false;
  }
  return true;
}

/// Structural invariants every Fix must satisfy.
inline void expect_consistent(const Fix& f) {
  EXPECT_TRUE(all_finite(f));
  int used = 0, tracked = 0, visible = 0;
  for (int i = 0; i < f.num_sats; ++i) {
    const SatInfo& s = f.sats[i];
    if (i > 0) {
      EXPECT_TRUE(f.sats[i - 1].sat < s.sat);  // SatId order
    }
    EXPECT_GT(s.el_rad, 0.0);
    used += s.used;
    tracked += s.tracked;
    visible += s.above_mask;
    if (s.used) {
      EXPECT_TRUE(s.tracked);
    }
    if (s.tracked) {
      EXPECT_TRUE(s.above_mask);
    }
    EXPECT_EQ(s.tracked, s.cn0_dbhz > 0.0);
  }
  EXPECT_EQ(used, f.num_used);
  EXPECT_EQ(tracked, f.num_tracked);
  EXPECT_EQ(visible, f.num_visible);
  if (f.type == FixType::kNone) {
    EXPECT_EQ(f.num_used, 0);
    EXPECT_EQ(f.dop.pdop, Dop::kNoDop);
  } else {
    EXPECT_GE(f.num_used, f.type == FixType::k3D ? 4 : 3);
    EXPECT_GT(f.h_acc_m, 0.0);
  }
}

}  // namespace gnssemu::receiver::test
