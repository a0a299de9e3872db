// SPDX-License-Identifier: Apache-2.0
// receiver_bench: per-epoch cost of Pipeline::step() (world + receiver) on real broadcast
// ephemerides, static and moving (100 m/s) receivers, and heap allocations
// per epoch after warm-up, for the default receiver (navigation filter) and
// the snapshot receiver (filter none, acquisition not modelled: the receiver
// before the filter). Prints figures; not a test.
//   receiver_bench [nav_file] [epochs]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "tests/support/alloc_counter.hpp"


namespace {

using namespace gnssemu;

struct Result {
  double mean_us = 0, median_us = 0, p99_us = 0, max_us = 0;
  double allocs_per_epoch = 0, mean_used = 0, mean_h_err_m = 0, fix_ratio = 0;
};

pipeline::PipelineConfig snapshot() {
  pipeline::PipelineConfig c;
  c.receiver.filter.type = receiver::NavFilterType::kNone;
  c.receiver.acquisition.modelled = false;
  c.world.carrier.doppler_model = world::DopplerModel::kFixed;
  return c;
}

Result run(const orbit::EphemerisStore& store, const pipeline::PipelineConfig& cfg, const time::GpsTime& t0,
           double speed_m_s, int epochs) {
  pipeline::Pipeline rx(store, cfg);
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  const Ecef p0 = geo::ecef_from_lla(site);
  const Vec3 v = geo::enu_to_ecef_vector(Enu(speed_m_s * 0.6, speed_m_s * 0.8, 0.0), site.lat_rad, site.lon_rad);
  std::vector<double> us(static_cast<std::size_t>(epochs));
  const int warm_up = 10;
  long allocs = 0;
  double used = 0, herr = 0;
  int fixes = 0;
  for (int k = -warm_up; k < epochs; ++k) {
    const double dt = 0.1 * (k + warm_up);  // 10 Hz
    world::Truth tr;
    tr.t = t0 + dt;
    tr.pos_m = Ecef(p0 + v * dt);
    tr.vel_m_s = Ecef(v);
    tr.valid = true;
    const long a0 = gnssemu::support::allocation_count();
    const auto c0 = std::chrono::steady_clock::now();
    const receiver::Fix& f = rx.step(tr.t, tr);
    const auto c1 = std::chrono::steady_clock::now();
    const long a1 = gnssemu::support::allocation_count();
    if (k < 0) continue;
    allocs += a1 - a0;
    us[static_cast<std::size_t>(k)] = std::chrono::duration<double, std::micro>(c1 - c0).count();
    if (f.type == receiver::FixType::k3D) {
      ++fixes;
      used += f.num_used;
      const Enu e = geo::ecef_to_enu_vector(f.pos_m - tr.pos_m, site.lat_rad, site.lon_rad);
      herr += std::hypot(e.x, e.y);
    }
  }
  Result r;
  for (double x : us) r.mean_us += x;
  r.mean_us /= epochs;
  std::sort(us.begin(), us.end());
  r.median_us = us[us.size() / 2];
  r.p99_us = us[static_cast<std::size_t>(0.99 * static_cast<double>(us.size() - 1))];
  r.max_us = us.back();
  r.allocs_per_epoch = static_cast<double>(allocs) / epochs;
  r.fix_ratio = static_cast<double>(fixes) / epochs;
  r.mean_used = fixes ? used / fixes : 0.0;
  r.mean_h_err_m = fixes ? herr / fixes : 0.0;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string nav_path =
      argc > 1 ? argv[1] : std::string(GNSSEMU_SOURCE_DIR) + "/tests/data/nav/brdc0010.22n";
  const int epochs = argc > 2 ? std::max(100, std::atoi(argv[2])) : 5000;
  try {
    const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
    const orbit::EphemerisStore store(nav.ephemerides);
    std::printf("receiver_bench: %s, %d epochs at 10 Hz per case, 39.6N 22.4E\n", nav_path.c_str(), epochs);
    std::printf("%-9s %-8s %7s %9s %9s %9s %9s %12s %8s %9s %10s\n", "receiver", "case", "start_h", "mean_us",
                "median_us", "p99_us", "max_us", "allocs/ep", "fix", "sats_used", "h_err_m");
    // Several start times across the file's day: the satellite count (and so
    // the cost of the solver) varies with the sky.
    for (const bool filtered : {true, false}) {
      for (const double start_h : {2.0, 4.0, 8.0, 12.0, 16.0, 20.0}) {
        const time::GpsTime t0 = store.first_valid() + start_h * 3600.0;
        for (const double speed : {0.0, 100.0}) {
          const Result r = run(store, filtered ? pipeline::PipelineConfig{} : snapshot(), t0, speed, epochs);
          std::printf("%-9s %-8s %7.1f %9.2f %9.2f %9.2f %9.2f %12.3f %8.3f %9.2f %10.3f\n",
                      filtered ? "default" : "snapshot", speed > 0 ? "moving" : "static", start_h, r.mean_us,
                      r.median_us, r.p99_us, r.max_us, r.allocs_per_epoch, r.fix_ratio, r.mean_used, r.mean_h_err_m);
        }
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "receiver_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
