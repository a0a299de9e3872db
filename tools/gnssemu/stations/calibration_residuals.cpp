// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/stations/calibration_residuals.hpp"

#include <algorithm>
#include <cmath>

#include "core/atmosphere/receiver_corrections.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/receiver/solution/transmit_state.hpp"
#include "core/world/sky/sky.hpp"
#include "tools/gnssemu/stations/spp.hpp"

namespace gnssemu::cli {

namespace {

constexpr int kMinSatsPerEpoch = 5;  // clock estimate from 4 would leave 3 dof
constexpr double kOutlier_m = 30.0;  // |residual| beyond this: not a model error (blunder)

}  // namespace

double grid_step_s(const observation::ObsData& obs) {
  if (obs.header.interval_s > 0.0) return obs.header.interval_s;
  std::vector<double> d;
  for (std::size_t i = 1; i < obs.epochs.size(); ++i) d.push_back(obs.epochs[i].t - obs.epochs[i - 1].t);
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return std::max(d[d.size() / 2], 1e-3);
}

std::vector<Residual> station_residuals(const CalibrationInput& in, const orbit::EphemerisStore& store, double step_s,
                                        int day, int& epochs_used) {
  const observation::ObsData& obs = *in.obs;
  const int c1c = obs.header.type_index(GnssSystem::kGps, "C1C");
  const int s1c = obs.header.type_index(GnssSystem::kGps, "S1C");
  if (c1c < 0) throw Error(obs.source, 0, "no GPS C1C (RINEX 2: C1) pseudoranges");
  const Lla lla = geo::lla_from_ecef(in.station_m);
  const time::GpsTime t0 = obs.epochs.front().t;
  std::vector<Residual> out, epoch;
  epochs_used = 0;
  for (const observation::ObsEpoch& e : obs.epochs) {
    epoch.clear();
    for (const observation::SatObs& s : e.sats) {
      if (s.sat.system != GnssSystem::kGps) continue;  // the GPS error model
      const observation::ObsValue* pr = s.get(c1c);
      if (pr == nullptr) continue;
      const SatId sat = s.sat;
      const orbit::Ephemeris* eph = store.select(sat, e.t);
      if (eph == nullptr) continue;
      const orbit::SatState st = receiver::transmit_state(*eph, e.t, pr->value).state;
      // Sagnac at the known station: rotate by the geometric flight time (the
      // solver's flight time holds its clock estimate, which is not known here).
      double rho = (st.pos_m - in.station_m).norm();
      Ecef p = st.pos_m;
      for (int it = 0; it < 2; ++it) {
        p = world::rotate_earth(st.pos_m, kOmegaEarth_rad_s * rho / kSpeedOfLight_m_s);
        rho = (p - in.station_m).norm();
      }
      const geo::LookAngles look = geo::look_angles(in.station_m, lla, p);
      if (!(look.el_rad >= in.mask_rad)) continue;
      Residual r;
      r.day = day;
      r.tow_s = e.t.tow_s();
      r.sat = sat;
      r.el_rad = look.el_rad;
      r.az_rad = look.az_rad;
      r.range_m = rho;
      const double corr_m = receiver_correction_m(in.nav->klobuchar, lla, look.az_rad, look.el_rad, e.t);
      r.klobuchar_m = corr_m - atmosphere::standard_troposphere_correction_m(lla.lat_rad, lla.height_m, look.el_rad,
                                                                             e.t.fractional_day_of_year());
      r.nmf_wet = atmosphere::niell_mapping(look.el_rad, lla.lat_rad, lla.height_m, e.t.fractional_day_of_year()).wet;
      r.value_m = pr->value - (rho - kSpeedOfLight_m_s * (st.clk_bias_s - eph->tgd_s) + corr_m);
      if (const observation::ObsValue* sn = s.get(s1c)) r.cn0_dbhz = sn->value;
      epoch.push_back(r);
    }
    if (static_cast<int>(epoch.size()) < kMinSatsPerEpoch) continue;
    // Receiver clock: median (robust to one blunder), then the mean of the rest.
    std::vector<double> v;
    for (const Residual& r : epoch) v.push_back(r.value_m);
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    const double med = v[v.size() / 2];
    double sum = 0.0;
    int n = 0;
    for (const Residual& r : epoch) {
      if (std::fabs(r.value_m - med) < kOutlier_m) {
        sum += r.value_m;
        ++n;
      }
    }
    if (n < kMinSatsPerEpoch) continue;
    const double clock = sum / n;
    // Removing the epoch mean shrinks independent errors by (n-1)/n in variance.
    const double inflate = std::sqrt(static_cast<double>(n) / (n - 1));
    const int grid = day * kDayGridStride + static_cast<int>(std::lround((e.t - t0) / step_s));
    ++epochs_used;
    for (Residual r : epoch) {
      if (std::fabs(r.value_m - med) >= kOutlier_m) continue;
      r.value_m = (r.value_m - clock) * inflate;
      r.grid = grid;
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace gnssemu::cli
