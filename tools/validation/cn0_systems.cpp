// SPDX-License-Identifier: Apache-2.0
// C/N0 per system against elevation of a real station (RINEX / Compact
// RINEX S observations) next to the link budget of the signal stage
// (docs/models.md, "C/N0 per system"). Per system and 10-degree bin: the
// median measured C/N0 and the median of measured minus modelled (the model
// with the compiled-in per-system table) and that minus GPS's in the same
// bin (GPS's residual is the station's own level: antenna, cable, receiver).
// Per system the weighted line of those differences, d = a + b (1 - sin el),
// added to the table's row: the power and slope offsets this station asks
// for (on the fit station they equal the table; on a held-out one the
// difference is what the table misses).
//
// Usage: cn0_systems --obs FILE.crx.gz --nav NAV.rnx.gz [--nav ...] [--mask DEG]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/common/gnss_systems.hpp"
#include "core/common/sat_id.hpp"
#include "core/geo/geodesy.hpp"
#include "core/observation/rinex_obs.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/signal/link_budget.hpp"
#include "core/signal/system_signal.hpp"
#include "core/world/world_config.hpp"

namespace {

using namespace gnssemu;

constexpr int kBins = 9;  // 0-10 ... 80-90 deg

// The L1-band civil signal's S code per system, in order of preference
// (BeiDou B1I is "2I" from RINEX 3.02 on, "1I" in 3.01).
const std::vector<std::string>& s_codes(GnssSystem s) {
  static const std::array<std::vector<std::string>, kNumSystems> codes{{
      {"S1C"}, {"S1C"}, {"S1C", "S1X"}, {"S2I", "S1I"}, {"S1C"}, {"S1C"}}};
  return codes[static_cast<std::size_t>(s)];
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  return v[m];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"C/N0 per system against elevation: a station's S observations against the link budget"};
  std::string obs_path;
  std::vector<std::string> nav_paths;
  double mask_deg = 5.0;
  app.add_option("--obs", obs_path, "RINEX 3 observation file (.rnx, .crx, .gz)")->required();
  app.add_option("--nav", nav_paths, "broadcast navigation file(s) of the same day")->required();
  app.add_option("--mask", mask_deg, "elevation mask, deg");
  CLI11_PARSE(app, argc, argv);

  const observation::ObsData obs = observation::read_rinex_obs(obs_path);
  const orbit::NavData nav = orbit::read_rinex_nav_files(nav_paths);
  const orbit::EphemerisStore store(nav.ephemerides);
  if (!obs.header.approx_pos_m) {
    std::fprintf(stderr, "%s: no APPROX POSITION XYZ\n", obs_path.c_str());
    return 1;
  }
  const Ecef rx = *obs.header.approx_pos_m;
  const Lla rx_lla = geo::lla_from_ecef(rx);
  const signal::LinkBudgetModel link(world::SignalConfig{}.link);

  std::array<int, kNumSystems> s_index{};
  for (int s = 0; s < kNumSystems; ++s) {
    s_index[static_cast<std::size_t>(s)] = -1;
    for (const std::string& c : s_codes(static_cast<GnssSystem>(s))) {
      const int k = obs.header.type_index(static_cast<GnssSystem>(s), c);
      if (k >= 0) {
        s_index[static_cast<std::size_t>(s)] = k;
        break;
      }
    }
  }
  // Per system: every sample's (1 - sin el), measured S, residual; per bin the values.
  struct Samples {
    std::vector<double> x, r;
    std::array<std::vector<double>, kBins> s_bin, r_bin;
  };
  std::array<Samples, kNumSystems> by_sys;
  for (const observation::ObsEpoch& ep : obs.epochs) {
    for (const observation::SatObs& so : ep.sats) {
      const std::size_t sys = static_cast<std::size_t>(so.sat.system);
      const observation::ObsValue* v = so.get(s_index[sys]);
      if (v == nullptr || !(v->value > 0.0)) continue;
      const orbit::Ephemeris* eph = store.select(so.sat, ep.t);
      if (eph == nullptr || eph->health != 0) continue;
      const orbit::SatState st = orbit::sat_state(*eph, ep.t - 0.075);
      const geo::LookAngles la = geo::look_angles(rx, rx_lla, st.pos_m);
      const double el_deg = la.el_rad / kDegToRad;
      if (!(el_deg >= mask_deg)) continue;
      const double model =
          link.cn0_dbhz(la.range_m, la.el_rad, 0.0, so.sat.system, orbit::carrier_hz(*eph));
      Samples& smp = by_sys[sys];
      const double x = 1.0 - std::sin(la.el_rad);
      smp.x.push_back(x);
      smp.r.push_back(v->value - model);
      const int bin = std::min(static_cast<int>(el_deg / 10.0), kBins - 1);
      smp.s_bin[static_cast<std::size_t>(bin)].push_back(v->value);
      smp.r_bin[static_cast<std::size_t>(bin)].push_back(v->value - model);
    }
  }
  std::printf("# %s (%s), %zu epochs; model: default link budget with the per-system table\n",
              obs.header.marker_name.c_str(), obs.header.receiver_type.c_str(), obs.epochs.size());
  // The station's own level (antenna, cable, receiver) is GPS's residual:
  // a system's residual minus GPS's in the same bin is what the table must explain.
  std::printf("sys,el_bin_deg,n,median_cn0_dbhz,median_resid_db,resid_minus_gps_db\n");
  for (int s = 0; s < kNumSystems; ++s) {
    const Samples& smp = by_sys[static_cast<std::size_t>(s)];
    for (int b = 0; b < kBins; ++b) {
      const auto& sb = smp.s_bin[static_cast<std::size_t>(b)];
      if (sb.empty()) continue;
      const double r = median(smp.r_bin[static_cast<std::size_t>(b)]);
      const double r_gps = median(by_sys[0].r_bin[static_cast<std::size_t>(b)]);
      std::printf("%c,%d-%d,%zu,%.1f,%.1f,%.1f\n", system_letter(static_cast<GnssSystem>(s)), 10 * b, 10 * b + 10,
                  sb.size(), median(sb), r, r - r_gps);
    }
  }
  // The fit: per system the bin medians' difference from GPS's, d_b, against
  // x_b = 1 - sin(bin centre), weighted by the bin's samples: d = a + b x.
  // Added to the compiled-in row it is the row this station asks for.
  const double all_gps = median(by_sys[0].r);
  std::printf("sys,n,table_power_db,table_slope_db,fit_power_db,fit_slope_db,median_resid_minus_gps_db\n");
  for (int s = 0; s < kNumSystems; ++s) {
    const Samples& smp = by_sys[static_cast<std::size_t>(s)];
    if (smp.x.empty()) continue;
    double sw = 0, sx = 0, sd = 0, sxx = 0, sxd = 0;
    for (int b = 0; b < kBins; ++b) {
      const auto& rb = smp.r_bin[static_cast<std::size_t>(b)];
      const auto& gb = by_sys[0].r_bin[static_cast<std::size_t>(b)];
      if (rb.empty() || gb.empty()) continue;
      const double w = static_cast<double>(rb.size());
      const double x = 1.0 - std::sin((10.0 * b + 5.0) * kDegToRad);
      const double d = median(rb) - median(gb);
      sw += w, sx += w * x, sd += w * d, sxx += w * x * x, sxd += w * x * d;
    }
    const double det = sw * sxx - sx * sx;
    const double slope = std::fabs(det) > 1e-9 * sw * sw ? (sw * sxd - sx * sd) / det : 0.0;
    const double power = sw > 0.0 ? (sd - slope * sx) / sw : 0.0;
    const signal::SystemSignal& row = signal::system_signal(static_cast<GnssSystem>(s));
    std::printf("%c,%zu,%.2f,%.2f,%.2f,%.2f,%.2f\n", system_letter(static_cast<GnssSystem>(s)), smp.x.size(),
                row.power_offset_db, row.slope_offset_db, row.power_offset_db + power, row.slope_offset_db + slope,
                median(smp.r) - all_gps);
  }
  return 0;
}
