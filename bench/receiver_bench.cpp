// SPDX-License-Identifier: Apache-2.0
// receiver_bench: per-epoch cost of Pipeline::step() (world + receiver) on real
// broadcast ephemerides, GPS-only and four systems (G,R,E,C + J) side by side
// in one run, static and moving (100 m/s) receivers, and heap allocations per
// epoch after warm-up, for the default receiver (navigation filter) and the
// snapshot receiver (filter none, acquisition not modelled). Prints figures;
// not a test. Times are thread CPU time (docs/benchmarks.md).
//   receiver_bench [--rtk | --rtk-f9p] [nav_file] [epochs] [week tow_s]
// --rtk: the RTK table only; --rtk-f9p: only its four-system two-band rows
// (for callgrind: rtk_step, m8_step and wide_step carry each receiver's
// instructions, docs/rtk.md "Cost").
// The default nav file is the IGS multi-GNSS broadcast cut of 2024-01-10,
// starting at 00:00 GPST of that day (week 2296, tow 259200).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/world/sky/shared_sky.hpp"
#include "tests/support/alloc_counter.hpp"

namespace {

using namespace gnssemu;

/// Thread CPU time, µs: the cost per core on a shared machine, not the wall
/// clock.
double cpu_us() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 +
         static_cast<double>(ts.tv_nsec) * 1e-3;
}

struct Result {
  double mean_us = 0, median_us = 0, p99_us = 0, max_us = 0;
  double allocs_per_epoch = 0, evals_per_epoch = 0, mean_visible = 0,
         mean_used = 0, mean_h_err_m = 0, fix_ratio = 0;
};

pipeline::PipelineConfig config_for(bool filtered, SystemSet systems,
                                    int bands) {
  pipeline::PipelineConfig c;
  c.receiver.bands = bands;
  if (!filtered) {
    c.receiver.filter.type = receiver::NavFilterType::kNone;
    c.receiver.acquisition.modelled = false;
    c.world.carrier.doppler_model = world::DopplerModel::kFixed;
  }
  c.world.systems = systems;
  // Four systems: as many channels as an M8 has hardware tracking channels.
  if (systems.count() > 1)
    c.receiver.max_channels = 32;
  return c;
}

#ifdef GNSSEMU_BENCH_BASELINE
long orbit_evaluations(const pipeline::Pipeline &) { return 0; }
#else
long orbit_evaluations(const pipeline::Pipeline &rx) {
  return rx.world().own_sky().evaluations();
}
#endif

Result run(const orbit::EphemerisStore &store,
           const pipeline::PipelineConfig &cfg, const time::GpsTime &t0,
           double speed_m_s, int epochs) {
  pipeline::Pipeline rx(store, cfg);
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  const Ecef p0 = geo::ecef_from_lla(site);
  const Vec3 v = geo::enu_to_ecef_vector(
      Enu(speed_m_s * 0.6, speed_m_s * 0.8, 0.0), site.lat_rad, site.lon_rad);
  std::vector<double> us(static_cast<std::size_t>(epochs));
  const int warm_up = 10;
  long allocs = 0;
  double used = 0, herr = 0, visible = 0;
  int fixes = 0;
  long evals0 = 0;
  for (int k = -warm_up; k < epochs; ++k) {
    if (k == 0)
      evals0 = orbit_evaluations(rx);
    const double dt = 0.1 * (k + warm_up); // 10 Hz
    world::Truth tr;
    tr.t = t0 + dt;
    tr.pos_m = Ecef(p0 + v * dt);
    tr.vel_m_s = Ecef(v);
    tr.valid = true;
    const long a0 = gnssemu::support::allocation_count();
    const double c0 = cpu_us();
    const receiver::Fix &f = rx.step(tr.t, tr);
    const double c1 = cpu_us();
    const long a1 = gnssemu::support::allocation_count();
    if (k < 0)
      continue;
    allocs += a1 - a0;
    us[static_cast<std::size_t>(k)] = c1 - c0;
    visible += f.num_visible;
    if (f.type == receiver::FixType::k3D) {
      ++fixes;
      used += f.num_used;
      const Enu e = geo::ecef_to_enu_vector(f.pos_m - tr.pos_m, site.lat_rad,
                                            site.lon_rad);
      herr += std::hypot(e.x, e.y);
    }
  }
  Result r;
  r.evals_per_epoch =
      static_cast<double>(orbit_evaluations(rx) - evals0) / epochs;
  for (double x : us)
    r.mean_us += x;
  r.mean_us /= epochs;
  std::sort(us.begin(), us.end());
  r.median_us = us[us.size() / 2];
  r.p99_us =
      us[static_cast<std::size_t>(0.99 * static_cast<double>(us.size() - 1))];
  r.max_us = us.back();
  r.allocs_per_epoch = static_cast<double>(allocs) / epochs;
  r.fix_ratio = static_cast<double>(fixes) / epochs;
  r.mean_visible = visible / epochs;
  r.mean_used = fixes ? used / fixes : 0.0;
  r.mean_h_err_m = fixes ? herr / fixes : 0.0;
  return r;
}

// Out of line so that a profiler's inclusive cost is one receiver's.
[[gnu::noipa]] const receiver::Fix &rtk_step(pipeline::Pipeline &p,
                                             const world::SharedSky &sky,
                                             const world::Truth &tr) {
  return p.step(sky, tr);
}
[[gnu::noipa]] void m8_step(pipeline::Pipeline &p, const world::SharedSky &sky,
                            const world::Truth &tr) {
  p.step(sky, tr);
}
[[gnu::noipa]] void wide_step(pipeline::Pipeline &p,
                              const world::SharedSky &sky,
                              const world::Truth &tr) {
  p.step(sky, tr);
}

struct RtkResult {
  double m8_us = 0, wide_us = 0, rtk_us = 0, rtk_p99_us = 0,
         allocs_per_epoch = 0, fixed = 0, flt = 0, dgnss = 0, h_err_fixed_m = 0;
};

/// The RTK rover (64 channels) against the same antenna without corrections
/// (M8: 32 channels; wide: the rover's 64 channels, no RTK stage), one
/// shared sky with a base 2 km away, 8 Hz, each step timed (world + receiver).
RtkResult run_rtk(const orbit::EphemerisStore &store, SystemSet systems,
                  int bands, const time::GpsTime &t0, int epochs) {
  pipeline::PipelineConfig cfg = config_for(true, systems, 1);
  cfg.world.sky_seed = 1;
  pipeline::PipelineConfig base_cfg = cfg, rtk_cfg = cfg;
  base_cfg.world.seed = 5;
  rtk_cfg.world.seed = 9;
  rtk_cfg.receiver.max_channels = 64;
  base_cfg.receiver.bands = rtk_cfg.receiver.bands =
      bands; // F9P: L1 + L2/E5b/B2I
  world::SharedSky sky(store, systems, world::sky_errors_config(cfg.world));
  pipeline::Pipeline base(store, base_cfg), rover(store, rtk_cfg),
      m8(store, cfg), wide(store, rtk_cfg);
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  const Ecef rover_m = geo::ecef_from_lla(site);
  const Ecef base_m(rover_m + geo::enu_to_ecef_vector(Enu(1200.0, -1600.0, 3.0),
                                                      site.lat_rad,
                                                      site.lon_rad));
  receiver::Corrections corr;
  corr.station.station_id = 1;
  corr.station.position_valid = true;
  corr.station.arp_ecef_m = base_m;
  corr.glonass_cpb_valid =
      true; // the base sends 1230 with its MSM, as F9P bases do
  rover.receiver().set_corrections(&corr);
  std::vector<double> us_rtk, us_m8, us_wide;
  long allocs = 0;
  RtkResult r;
  int counted = 0;
  const int warm_up = 480; // 60 s: acquisition and ephemerides
  for (int k = -warm_up; k < epochs; ++k) {
    const time::GpsTime t = t0 + 0.125 * (k + warm_up);
    const Ecef ants[2] = {base_m, rover_m};
    sky.update(t, ants);
    base.step(sky, [&] {
      world::Truth tr;
      tr.t = t;
      tr.pos_m = base_m;
      tr.valid = true;
      return tr;
    }());
    corr.obs = base.receiver().raw();
    corr.obs_valid = corr.obs.time_valid && corr.obs.num_meas > 0;
    ++corr.revision;
    world::Truth tr;
    tr.t = t;
    tr.pos_m = rover_m;
    tr.valid = true;
    const long a0 = gnssemu::support::allocation_count();
    const double c0 = cpu_us();
    const receiver::Fix &f = rtk_step(rover, sky, tr);
    const double c1 = cpu_us();
    const long a1 = gnssemu::support::allocation_count();
    m8_step(m8, sky, tr);
    const double c2 = cpu_us();
    wide_step(wide, sky, tr);
    const double c3 = cpu_us();
    if (k < 0)
      continue;
    us_rtk.push_back(c1 - c0);
    us_m8.push_back(c2 - c1);
    us_wide.push_back(c3 - c2);
    allocs += a1 - a0;
    ++counted;
    r.fixed += f.carr_soln == receiver::CarrierSolution::kFixed;
    r.flt += f.carr_soln == receiver::CarrierSolution::kFloat;
    r.dgnss += f.diff_soln && f.carr_soln == receiver::CarrierSolution::kNone;
    if (f.carr_soln == receiver::CarrierSolution::kFixed) {
      const Enu e = geo::ecef_to_enu_vector(f.pos_m - rover_m, site.lat_rad,
                                            site.lon_rad);
      r.h_err_fixed_m += std::hypot(e.x, e.y);
    }
  }
  for (double x : us_rtk)
    r.rtk_us += x;
  for (double x : us_m8)
    r.m8_us += x;
  for (double x : us_wide)
    r.wide_us += x;
  r.wide_us /= counted;
  r.rtk_us /= counted;
  r.m8_us /= counted;
  std::sort(us_rtk.begin(), us_rtk.end());
  r.rtk_p99_us = us_rtk[static_cast<std::size_t>(
      0.99 * static_cast<double>(us_rtk.size() - 1))];
  r.allocs_per_epoch = static_cast<double>(allocs) / counted;
  if (r.fixed > 0)
    r.h_err_fixed_m /= r.fixed;
  r.fixed /= counted;
  r.flt /= counted;
  r.dgnss /= counted;
  return r;
}

} // namespace

int main(int argc, char **argv) {
  // 0: every table; 1: the RTK table; 2: its four-system two-band rows.
  int rtk_only = 0;
  if (argc > 1 && std::string(argv[1]) == "--rtk")
    rtk_only = 1;
  else if (argc > 1 && std::string(argv[1]) == "--rtk-f9p")
    rtk_only = 2;
  if (rtk_only > 0) {
    --argc;
    ++argv;
  }
  const std::string nav_path =
      argc > 1
          ? argv[1]
          : std::string(GNSSEMU_SOURCE_DIR) +
                "/tests/data/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz";
  const int epochs = argc > 2 ? std::max(100, std::atoi(argv[2])) : 3000;
  try {
    const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
    const orbit::EphemerisStore store(nav.ephemerides);
    const time::GpsTime day =
        argc > 4 ? time::GpsTime(std::atoi(argv[3]), std::atof(argv[4]))
                 : time::GpsTime(2296, 259200.0);
    std::printf(
        "receiver_bench: %s, %d epochs at 10 Hz per case, 39.6N 22.4E\n",
        nav_path.c_str(), epochs);
    if (rtk_only == 0)
      std::printf(
          "%-9s %-8s %-10s %7s %9s %9s %9s %9s %10s %8s %8s %8s %9s %9s\n",
          "receiver", "case", "systems", "start_h", "mean_us", "median_us",
          "p99_us", "max_us", "allocs/ep", "evals/ep", "fix", "in_view",
          "sats_used", "h_err_m");
    const SystemSet gps = SystemSet::only(GnssSystem::kGps);
    const SystemSet four = gps.with(GnssSystem::kGlonass)
                               .with(GnssSystem::kGalileo)
                               .with(GnssSystem::kBeiDou)
                               .with(GnssSystem::kQzss);
    double sum_us[3] = {0.0, 0.0, 0.0};
    int n_cases = 0;
    for (const bool filtered : {true, false}) {
      if (rtk_only > 0)
        break;
      for (const double start_h : {1.0, 3.0, 5.0}) {
        const time::GpsTime t0 = day + start_h * 3600.0;
        for (const double speed : {0.0, 100.0}) {
          for (int s = 0; s < 3; ++s) { // GPS L1, five systems L1, five systems
                                        // L1 + second frequency
            const SystemSet set = s == 0 ? gps : four;
            const Result r =
                run(store, config_for(filtered, set, s == 2 ? 2 : 1), t0, speed,
                    epochs);
            sum_us[s] += r.mean_us;
            std::printf("%-9s %-8s %-10s %7.1f %9.2f %9.2f %9.2f %9.2f %10.3f "
                        "%8.2f %8.3f %8.2f %9.2f %9.3f\n",
                        filtered ? "default" : "snapshot",
                        speed > 0 ? "moving" : "static",
                        s == 2 ? "GRECJ-L1L2" : systems_text(set).data(),
                        start_h, r.mean_us, r.median_us, r.p99_us, r.max_us,
                        r.allocs_per_epoch, r.evals_per_epoch, r.fix_ratio,
                        r.mean_visible, r.mean_used, r.mean_h_err_m);
          }
          ++n_cases;
        }
      }
    }
    if (rtk_only == 0)
      std::printf("mean over the cases: GPS-only %.2f us/epoch, G,R,E,C,J %.2f "
                  "us/epoch (ratio %.2f), G,R,E,C,J on two bands %.2f us/epoch "
                  "(ratio to one band %.2f)\n",
                  sum_us[0] / n_cases, sum_us[1] / n_cases,
                  sum_us[1] / sum_us[0], sum_us[2] / n_cases,
                  sum_us[2] / sum_us[1]);
    std::printf("\nRTK rover (base 2 km, 8 Hz, shared sky) against the same "
                "antenna without corrections (M8 default)\n");
    std::printf("%-10s %5s %7s %9s %9s %9s %9s %7s %10s %7s %7s %7s %11s\n",
                "systems", "bands", "start_h", "m8_us", "wide_us", "rtk_us",
                "rtk_p99", "ratio", "allocs/ep", "fixed", "float", "dgnss",
                "h_err_fix_m");
    for (const double start_h : {1.0, 3.0}) {
      for (int s = 0; s < 2; ++s) {
        for (const int bands : {1, 2}) {
          if (rtk_only == 2 && (s == 0 || bands == 1))
            continue;
          const SystemSet set = s == 0 ? gps : four;
          const RtkResult r =
              run_rtk(store, set, bands, day + start_h * 3600.0, epochs);
          std::printf("%-10s %5d %7.1f %9.2f %9.2f %9.2f %9.2f %7.2f %10.3f "
                      "%7.3f %7.3f %7.3f %11.4f\n",
                      systems_text(set).data(), bands, start_h, r.m8_us,
                      r.wide_us, r.rtk_us, r.rtk_p99_us, r.rtk_us / r.m8_us,
                      r.allocs_per_epoch, r.fixed, r.flt, r.dgnss,
                      r.h_err_fixed_m);
        }
      }
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "receiver_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
