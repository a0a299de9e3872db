// SPDX-License-Identifier: Apache-2.0
// A drive in and out of a street canyon with an RTK base 2 km away: the
// carrier solution's state sequence follows the blockage (fixed in the open,
// float or lost in the canyon, fixed again after it), and its statistics are
// the ones docs/rtk.md compares with the real F9K drive
// (tools/rtk_log_stats.py on ../shared/data/receiver-logs/f9k_span_drive).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/geo/geodesy.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/scene/footprints.hpp"
#include "core/scene/scene.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace gnssemu::receiver {
namespace {

const std::string kDriveData = GNSSEMU_TEST_DATA;
const Lla kDriveOrigin{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

scene::Mesh drive_canyon() {
  scene::FootprintBuilder b(kDriveData + "/scenes/street_canyon.toml", {});
  b.add_ground(400.0, 0.0, "concrete", 3);
  b.add_building(b.outline({{-60, -150}, {-10, -150}, {-10, 150}, {-60, 150}}, 8, "building[0]"), 0.0, 30.0,
                 "concrete", 8, 7, "building[0]");
  b.add_building(b.outline({{10, -150}, {60, -150}, {60, 150}, {10, 150}}, 13, "building[1]"), 0.0, 30.0, "glass",
                 13, 12, "building[1]");
  return std::move(b).finish();
}

/// Run lengths of one state in a sequence of GGA-like qualities.
std::vector<int> runs_of(const std::vector<int>& q, int state) {
  std::vector<int> r;
  for (std::size_t i = 0; i < q.size();) {
    std::size_t j = i;
    while (j < q.size() && q[j] == q[i]) ++j;
    if (q[i] == state) r.push_back(static_cast<int>(j - i));
    i = j;
  }
  return r;
}

double median_of(std::vector<int> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// Epochs from leaving fixed to being fixed again (every gap that ends fixed).
std::vector<int> refix_gaps(const std::vector<int>& q) {
  std::vector<int> g;
  for (std::size_t i = 1; i < q.size(); ++i) {
    if (q[i - 1] != 4 || q[i] == 4) continue;
    std::size_t j = i;
    while (j < q.size() && q[j] != 4) ++j;
    if (j < q.size()) g.push_back(static_cast<int>(j - i));
    i = j;
  }
  return g;
}

TEST(RtkDrive, StreetCanyonLoopsFollowTheBlockage) {
  const orbit::NavData nav = orbit::read_rinex_nav(kDriveData + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 12, 0, 0.0});
  const geo::LocalFrame frame(kDriveOrigin);
  const scene::Scene canyon(drive_canyon());
  pipeline::PipelineConfig cfg;
  cfg.world.sky_seed = 1;
  pipeline::PipelineConfig base_cfg = cfg, rover_cfg = cfg;
  base_cfg.world.seed = 3;
  rover_cfg.world.seed = 4;
  world::SharedSky sky(store, SystemSet::all(), world::sky_errors_config(cfg.world));
  pipeline::Pipeline base(store, base_cfg), rover(store, rover_cfg);
  rover.world().attach_scene({&canyon, kDriveOrigin, scene::SearchConfig{}});
  const Ecef base_m = frame.to_ecef(Enu(1200.0, -1600.0, 0.0));
  Corrections corr;
  corr.station.station_id = 7;
  corr.station.position_valid = true;
  corr.station.arp_ecef_m = base_m;
  rover.receiver().set_corrections(&corr);

  // Out and back along the street, 450 m either side of the middle (the
  // canyon spans +-150 m): y = 450 sin(2 pi t / 180 s), 15.7 m/s at most.
  const double half = 450.0, omega = 2.0 * kPi / 180.0;
  std::vector<int> q;
  int fixed_in_canyon = 0, epochs_in_canyon = 0;
  std::vector<double> h_err;
  const int warm_up = 120, epochs = 1800;
  for (int k = 0; k < warm_up + epochs; ++k) {
    const double tau = k < warm_up ? 0.0 : k - warm_up;
    const double y = -half * std::cos(omega * tau);
    const double vy = half * omega * std::sin(omega * tau);
    const Enu p(0.0, y, 1.5);
    const time::GpsTime t = t0 + static_cast<double>(k);
    const Ecef rover_m = frame.to_ecef(p);
    const Ecef ants[2] = {base_m, rover_m};
    sky.update(t, ants);
    world::Truth tb;
    tb.t = t;
    tb.pos_m = base_m;
    tb.valid = true;
    base.step(sky, tb);
    corr.obs = base.receiver().raw();
    corr.obs_valid = corr.obs.time_valid && corr.obs.num_meas > 0;
    ++corr.revision;
    world::Truth tr;
    tr.t = t;
    tr.pos_m = rover_m;
    tr.vel_m_s = Ecef(geo::enu_to_ecef_vector(Enu(0.0, k < warm_up ? 0.0 : vy, 0.0), kDriveOrigin.lat_rad,
                                              kDriveOrigin.lon_rad));
    tr.valid = true;
    const Fix& f = rover.step(sky, tr);
    if (k < warm_up) continue;
    const int quality = !is_gnss_fix(f.type)                           ? 0
                        : f.carr_soln == CarrierSolution::kFixed       ? 4
                        : f.carr_soln == CarrierSolution::kFloat       ? 5
                        : f.diff_soln                                  ? 2
                                                                       : 1;
    q.push_back(quality);
    const bool in_canyon = std::fabs(p.y) < 150.0;
    epochs_in_canyon += in_canyon;
    fixed_in_canyon += in_canyon && quality == 4;
    if (std::getenv("RTK_DRIVE_TRACE") != nullptr) {
      const Enu e = geo::ecef_to_enu_vector(f.pos_m - rover_m, kDriveOrigin.lat_rad, kDriveOrigin.lon_rad);
      const auto& st = rover.receiver().rtk().status();
      std::printf("%d y %.0f q %d err %.3f %.3f %.3f hacc %.3f code %d phase %d dd %d ratio %.1f rej %u slips %u\n", k, p.y,
                  quality, e.x, e.y, e.z, f.h_acc_m, st.num_code_sd, st.num_phase_sd, st.num_fixed_dd, st.ratio,
                  st.fix_rejections, st.slips);
    }
    if (quality == 4) {
      const Enu e = geo::ecef_to_enu_vector(f.pos_m - rover_m, kDriveOrigin.lat_rad, kDriveOrigin.lon_rad);
      h_err.push_back(std::hypot(e.x, e.y));
    }
  }
  int n4 = 0, n5 = 0, n2 = 0, n1 = 0, n0 = 0;
  for (int v : q) {
    n4 += v == 4;
    n5 += v == 5;
    n2 += v == 2;
    n1 += v == 1;
    n0 += v == 0;
  }
  std::sort(h_err.begin(), h_err.end());
  std::printf("canyon drive %d epochs: quality 4 x %d, 5 x %d, 2 x %d, 1 x %d, none x %d; fixed fraction %.3f; "
              "runs fixed %zu (median %.1f), float %zu (median %.1f); back to fixed median %.1f s over %zu gaps; "
              "fixed in the canyon %d/%d; fixed h error median %.3f m, 95%% %.3f m; rejected fixes %u\n",
              epochs, n4, n5, n2, n1, n0, static_cast<double>(n4) / epochs, runs_of(q, 4).size(),
              median_of(runs_of(q, 4)), runs_of(q, 5).size(), median_of(runs_of(q, 5)), median_of(refix_gaps(q)),
              refix_gaps(q).size(), fixed_in_canyon, epochs_in_canyon,
              h_err.empty() ? NAN : h_err[h_err.size() / 2], h_err.empty() ? NAN : h_err[h_err.size() * 95 / 100],
              rover.receiver().rtk().status().fix_rejections);
  // Fixed in the open, not throughout the canyon, and fixed again after it.
  EXPECT_GT(n4, epochs / 4);
  EXPECT_LT(fixed_in_canyon, epochs_in_canyon);
  EXPECT_GE(refix_gaps(q).size(), 3u);
}

}  // namespace
}  // namespace gnssemu::receiver
