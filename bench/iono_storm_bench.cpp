// SPDX-License-Identifier: Apache-2.0
// iono_storm_bench: a broadcast-only receiver under an ionosphere the broadcast
// Klobuchar does not describe (fixed world VTEC, a storm), with and without
// the solver's model-error variance (iono_model_fraction, tropo_model_sigma_m):
// fixes kept by the chi-square test, how many lie beyond 5 sigma of their own
// accuracy estimate, and the 3D error against the reported accuracy.
// Prints a Markdown table; not a test.
//   iono_storm_bench [nav_file]    (default brdc0010.22n; 45 N 7 E, 1 h from 11:00 GPST, 15 s)
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"

int main(int argc, char** argv) {
  using namespace gnssemu;
  using pipeline::PipelineConfig;
  try {
    const std::string nav_path =
        argc > 1 ? argv[1] : std::string(GNSSEMU_SOURCE_DIR) + "/tests/data/nav/brdc0010.22n";
    const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
    const orbit::EphemerisStore store(nav.ephemerides);
    const Lla site{45.0 * kDegToRad, 7.0 * kDegToRad, 300.0};
    const Ecef pos = geo::ecef_from_lla(site);
    const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 11, 0, 0.0});
    constexpr int kEpochs = 240;
    std::printf("| world VTEC | model variance | fixes | beyond 5 sigma | worst err/sigma | 3D error rms m | "
                "reported sqrt(hAcc^2+vAcc^2) rms m |\n|---|---|---|---|---|---|---|\n");
    for (double fraction : {0.0, 0.5}) {
      for (double tec : {-1.0, 30.0, 50.0, 75.0, 100.0, 150.0, 200.0, 300.0}) {
        PipelineConfig c;
        c.receiver.solver.iono_model_fraction = fraction;
        c.receiver.solver.tropo_model_sigma_m = fraction > 0.0 ? 0.3 : 0.0;
        if (tec >= 0.0) {
          c.world.atmosphere.ionosphere.source = atmosphere::VtecSource::kFixed;
          c.world.atmosphere.ionosphere.vtec_tecu = tec;
        }
        pipeline::Pipeline rx(store, c, {.klobuchar = nav.klobuchar});
        int fixes = 0, beyond = 0;
        double worst = 0.0, e2 = 0.0, a2 = 0.0;
        for (int k = 0; k < kEpochs; ++k) {
          const time::GpsTime t = t0 + 15.0 * k;
          world::Truth tr;
          tr.t = t;
          tr.pos_m = pos;
          tr.valid = true;
          const receiver::Fix& f = rx.step(t, tr);
          if (f.type == receiver::FixType::kNone) continue;
          ++fixes;
          const double err = (f.pos_m - pos).norm(), acc = std::hypot(f.h_acc_m, f.v_acc_m);
          worst = std::max(worst, err / acc);
          beyond += err > 5.0 * acc;
          e2 += err * err;
          a2 += acc * acc;
        }
        const double n = fixes > 0 ? fixes : 1;
        std::printf("| %s | %s | %d/%d | %d | %.1f | %.2f | %.2f |\n",
                    tec < 0.0 ? "broadcast Klobuchar" : (std::to_string(static_cast<int>(tec)) + " TECU").c_str(),
                    fraction > 0.0 ? "0.5 I, 0.3 m" : "off", fixes, kEpochs, beyond, worst, std::sqrt(e2 / n),
                    std::sqrt(a2 / n));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "iono_storm_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
