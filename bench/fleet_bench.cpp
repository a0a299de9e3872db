// SPDX-License-Identifier: Apache-2.0
// fleet_bench: N receivers on one world::SharedSky, as gnssemud runs a
// fleet — per epoch the sky is updated once at every antenna, then each
// receiver steps its own pipeline (Pipeline::step(sky, truth)). Prints the
// sky's cost, the first receiver's (sky + its step: what a receiver alone
// pays) against each further one's, a lone receiver on its own sky in the
// same run, the share of one core at the rate, and the process's RSS.
// Receivers: the default receiver, every system (G,R,E,C,J), 10 Hz, vehicles
// in a 2 km formation moving at 20 m/s. Thread CPU time (docs/benchmarks.md).
//   fleet_bench [vehicles] [seconds] [nav_file]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace {

using namespace gnssemu;

constexpr double kRateHz = 10.0;

double cpu_us() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

/// Resident set size of this process, MB (/proc/self/status VmRSS).
double rss_mb() {
  std::ifstream f("/proc/self/status");
  std::string key;
  while (f >> key) {
    if (key == "VmRSS:") {
      double kb = 0;
      f >> kb;
      return kb / 1024.0;
    }
    std::getline(f, key);
  }
  return 0.0;
}

pipeline::PipelineConfig config_for(SystemSet systems, uint64_t seed) {
  pipeline::PipelineConfig c;
  c.world.systems = systems;
  c.world.seed = seed;
  c.receiver.max_channels = 32;  // as many as an M8 has hardware tracking channels
  return c;
}

/// Vehicle i's truth at dt_s: a formation on a 2 km grid around the site, all heading north-east.
world::Truth truth_of(int i, double dt_s, const Lla& site, const time::GpsTime& t) {
  const Ecef p0 = geo::ecef_from_lla(site);
  const double e = 200.0 * (i % 10), n = 200.0 * (i / 10 % 10);
  const Vec3 off = geo::enu_to_ecef_vector(Enu(e, n, 0.0), site.lat_rad, site.lon_rad);
  const Vec3 v = geo::enu_to_ecef_vector(Enu(14.1, 14.1, 0.0), site.lat_rad, site.lon_rad);
  world::Truth tr;
  tr.t = t;
  tr.pos_m = Ecef(p0 + off + v * dt_s);
  tr.vel_m_s = Ecef(v);
  tr.valid = true;
  return tr;
}

double mean(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v;
  return x.empty() ? 0.0 : s / static_cast<double>(x.size());
}

double p99(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x.empty() ? 0.0 : x[static_cast<std::size_t>(0.99 * static_cast<double>(x.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::max(1, std::atoi(argv[1])) : 10;
  const double seconds = argc > 2 ? std::max(1.0, std::atof(argv[2])) : 30.0;
  const std::string nav_path = argc > 3 ? argv[3]
                                        : std::string(GNSSEMU_SOURCE_DIR) +
                                              "/tests/data/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz";
  try {
    const double rss0 = rss_mb();
    const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
    const orbit::EphemerisStore store(nav.ephemerides);
    const SystemSet all = SystemSet::only(GnssSystem::kGps)
                              .with(GnssSystem::kGlonass)
                              .with(GnssSystem::kGalileo)
                              .with(GnssSystem::kBeiDou)
                              .with(GnssSystem::kQzss);
    const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
    const time::GpsTime t0 = time::GpsTime(2296, 259200.0) + 3600.0;
    const double rss_nav = rss_mb();

    std::vector<std::unique_ptr<pipeline::Pipeline>> rx;
    for (int i = 0; i < n; ++i) rx.push_back(std::make_unique<pipeline::Pipeline>(store, config_for(all, 1 + i)));
    pipeline::Pipeline lone(store, config_for(all, 1000));
    world::SharedSky sky(store, all, world::sky_errors_config(config_for(all, 1).world));
    std::vector<Ecef> antennas(static_cast<std::size_t>(n));
    std::vector<world::Truth> truth(static_cast<std::size_t>(n));
    const double rss_setup = rss_mb();

    const int epochs = static_cast<int>(seconds * kRateHz);
    const int warm_up = 20;
    std::vector<double> sky_us, first_us, further_us, epoch_us, lone_us;
    int fixes = 0, steps = 0;
    for (int k = -warm_up; k < epochs; ++k) {
      const double dt = (k + warm_up) / kRateHz;
      const time::GpsTime t = t0 + dt;
      for (int i = 0; i < n; ++i) {
        truth[static_cast<std::size_t>(i)] = truth_of(i, dt, site, t);
        antennas[static_cast<std::size_t>(i)] = truth[static_cast<std::size_t>(i)].pos_m;
      }
      const double c0 = cpu_us();
      sky.update(t, antennas);
      const double c1 = cpu_us();
      double first = 0.0;
      for (int i = 0; i < n; ++i) {
        const double a = cpu_us();
        const receiver::Fix& f = rx[static_cast<std::size_t>(i)]->step(sky, truth[static_cast<std::size_t>(i)]);
        const double b = cpu_us();
        if (k < 0) continue;
        ++steps;
        if (f.type == receiver::FixType::k3D) ++fixes;
        if (i == 0) {
          first = b - a;
        } else {
          further_us.push_back(b - a);
        }
      }
      const double c2 = cpu_us();
      const world::Truth lt = truth_of(0, dt, site, t);
      const double l0 = cpu_us();
      (void)lone.step(t, lt);
      const double l1 = cpu_us();
      if (k < 0) continue;
      sky_us.push_back(c1 - c0);
      first_us.push_back(c1 - c0 + first);
      epoch_us.push_back(c2 - c0);
      lone_us.push_back(l1 - l0);
    }
    const double per_epoch = mean(epoch_us);
    std::printf("fleet_bench: %d receivers, every system (%s), %.0f Hz, %d epochs, %s\n", n, systems_text(all).data(),
                kRateHz, epochs, nav_path.c_str());
    std::printf("  sky update (once per epoch, %d antennas): mean %.1f us\n", n, mean(sky_us));
    std::printf("  first receiver (sky + its step):          mean %.1f us, p99 %.1f us\n", mean(first_us),
                p99(first_us));
    if (n > 1) {
      std::printf("  each further receiver (its step):         mean %.1f us, p99 %.1f us (%.0f %% of the first)\n",
                  mean(further_us), p99(further_us), 100.0 * mean(further_us) / mean(first_us));
    }
    std::printf("  a lone receiver on its own sky:           mean %.1f us\n", mean(lone_us));
    std::printf("  whole epoch: mean %.1f us, p99 %.1f us = %.1f %% of one core at %.0f Hz; 3D fixes %.1f %%\n",
                per_epoch, p99(epoch_us), per_epoch * kRateHz / 1e4, kRateHz, 100.0 * fixes / std::max(steps, 1));
    std::printf("  RSS: %.1f MB at start, %.1f MB with the nav data, %.1f MB with %d receivers (%.2f MB each), "
                "%.1f MB at the end\n",
                rss0, rss_nav, rss_setup, n, (rss_setup - rss_nav) / (n + 1), rss_mb());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fleet_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
