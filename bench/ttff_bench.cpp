// SPDX-License-Identifier: Apache-2.0
// ttff_bench: time to first fix of the emulated receiver for cold, warm and
// hot starts, and the return of the fix after a total blockage of 10 s and
// 60 s (antenna signal gone, receiver running), next to the u-blox M8 data
// sheet figures (MAX-M8 UBX-15031506, GPS only: cold 29 s, hot 1 s; u-blox
// reacquisition 1 s). Many starts spread over the day and over the 30-s
// navigation-message frame, one seed each, at 1 Hz (the M8's default rate,
// so times are whole epochs, as the TTFF a u-blox reports). Also the coast
// through the blockage: how long the receiver dead-reckons and how its hAcc
// grows.
// Prints tables; not a test.
//   ttff_bench [--nav FILE] [--trials N] [--rate HZ] [--profile ublox_m8|geodetic]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/pipeline/receiver_profile.hpp"
#include "core/statistics/statistics.hpp"

namespace {

using namespace gnssemu;
using pipeline::PipelineConfig;
using receiver::StartMode;

struct Options {
  std::string nav = std::string(GNSSEMU_SOURCE_DIR) + "/tests/data/nav/brdc0010.22n";
  int trials = 40;
  double rate_hz = 1.0;
  std::string profile;  // empty: the built-in default world
};

const Lla kSites[] = {{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0},     // Paris
                      {39.6 * kDegToRad, 22.4 * kDegToRad, 100.0},          // Larissa
                      {-33.9 * kDegToRad, 151.2 * kDegToRad, 50.0},         // Sydney
                      {40.8 * kDegToRad, -115.8 * kDegToRad, 1600.0}};      // Elko

/// Time (s) from start_s to the first epoch with a fix; NaN when none within limit_s.
struct Run {
  double first_fix_s = std::nan("");
};

struct Trial {
  time::GpsTime t0;
  Ecef pos;
  uint64_t seed;
};

/// The default receiver, or the profile's, with the trial's seed.
PipelineConfig configured(const Options& o, const Trial& tr) {
  PipelineConfig c;
  if (!o.profile.empty()) c = pipeline::apply_profile(c, pipeline::receiver_profile(o.profile), geo::lla_from_ecef(tr.pos).lat_rad);
  c.world.seed = tr.seed;
  return c;
}

Trial trial(const orbit::EphemerisStore& store, int k) {
  // Starts 997 s apart (not a multiple of the 30-s frame) across the day.
  const time::GpsTime t0 = store.first_valid() + 3600.0 + 997.0 * k;
  return {t0, geo::ecef_from_lla(kSites[k % 4]), static_cast<uint64_t>(k + 1)};
}

double ttff(const orbit::EphemerisStore& store, const Options& o, const Trial& tr, StartMode mode) {
  PipelineConfig c = configured(o, tr);
  c.receiver.acquisition.start = mode;
  pipeline::Pipeline rx(store, c);
  world::Truth truth;
  truth.pos_m = tr.pos;
  truth.valid = true;
  for (int k = 0; k <= static_cast<int>(300.0 * o.rate_hz); ++k) {
    truth.t = tr.t0 + k / o.rate_hz;
    if (rx.step(truth.t, truth).type != receiver::FixType::kNone) return k / o.rate_hz;
  }
  return std::nan("");
}

struct Blockage {
  double refix_s = std::nan("");  ///< from the signals' return to the first fix, s
  double coast_s = 0.0;           ///< dead reckoning (coasting) into the blockage, s
  double hacc_start_m = 0.0, hacc_end_m = 0.0;  ///< hAcc before the blockage and at the last coasting epoch
  double sat_reacq_s = std::nan("");            ///< mean time until a satellite tracked before is tracked again, s
};

Blockage blockage(const orbit::EphemerisStore& store, const Options& o, const Trial& tr, double outage_s) {
  PipelineConfig c = configured(o, tr);
  pipeline::Pipeline rx(store, c);
  world::Truth truth;
  truth.pos_m = tr.pos;
  const double settle_s = 300.0;
  Blockage b;
  std::array<bool, kNumSats> before{};  // by SatId::index()
  std::array<double, kNumSats> back{};
  back.fill(std::nan(""));
  const int n = static_cast<int>((settle_s + outage_s + 120.0) * o.rate_hz);
  for (int k = 0; k <= n; ++k) {
    const double s = k / o.rate_hz;
    truth.t = tr.t0 + s;
    truth.valid = s < settle_s || s >= settle_s + outage_s;
    const receiver::Fix& f = rx.step(truth.t, truth);
    const bool fix = f.type == receiver::FixType::k2D || f.type == receiver::FixType::k3D;
    if (s < settle_s) {
      b.hacc_start_m = f.h_acc_m;
      for (int i = 0; i < f.num_sats; ++i) before[static_cast<std::size_t>(f.sats[i].sat.index())] = f.sats[i].tracked;
    } else if (!truth.valid) {
      if (f.type == receiver::FixType::kDeadReckoning) {
        b.coast_s = s - settle_s + 1.0 / o.rate_hz;
        b.hacc_end_m = f.h_acc_m;
      }
    } else {
      const double since = s - (settle_s + outage_s);
      if (fix && std::isnan(b.refix_s)) b.refix_s = since;
      for (int i = 0; i < f.num_sats; ++i) {
        const receiver::SatInfo& si = f.sats[i];
        const auto j = static_cast<std::size_t>(si.sat.index());
        if (before[j] && si.tracked && std::isnan(back[j])) back[j] = since;
      }
    }
  }
  double sum = 0.0;
  int count = 0;
  for (std::size_t p = 0; p < before.size(); ++p)
    if (before[p] && !std::isnan(back[p])) {
      sum += back[p];
      ++count;
    }
  if (count > 0) b.sat_reacq_s = sum / count;
  return b;
}

void row(const char* what, std::vector<double> v, const char* datasheet) {
  std::vector<double> ok;
  for (double x : v)
    if (std::isfinite(x)) ok.push_back(x);
  const auto q = [&](double p) { return statistics::quantile_linear(ok, p); };
  std::printf("| %s | %zu/%zu | %.1f | %.1f | %.1f | %.1f | %.1f | %s |\n", what, ok.size(), v.size(),
              statistics::mean(ok), q(0.5), q(0.05), q(0.95), ok.empty() ? NAN : *std::max_element(ok.begin(), ok.end()),
              datasheet);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--nav") o.nav = argv[i + 1];
    else if (k == "--trials") o.trials = std::max(1, std::atoi(argv[i + 1]));
    else if (k == "--rate") o.rate_hz = std::clamp(std::atof(argv[i + 1]), 1.0, 10.0);
    else if (k == "--profile") o.profile = argv[i + 1];
    else {
      std::fprintf(stderr, "ttff_bench: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  try {
    const orbit::NavData nav = orbit::read_rinex_nav(o.nav);
    const orbit::EphemerisStore store(nav.ephemerides);
    std::printf("# ttff_bench: %s, %d trials (4 sites, starts 997 s apart, one seed each), %g Hz epochs, %s\n\n",
                o.nav.c_str(), o.trials, o.rate_hz,
                o.profile.empty() ? "default PipelineConfig" : ("receiver profile " + o.profile).c_str());
    std::printf("| start | with a fix | mean (s) | median (s) | p5 (s) | p95 (s) | max (s) | M8 data sheet |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    std::vector<double> cold, warm, hot;
    for (int k = 0; k < o.trials; ++k) {
      const Trial tr = trial(store, k);
      cold.push_back(ttff(store, o, tr, StartMode::kCold));
      warm.push_back(ttff(store, o, tr, StartMode::kWarm));
      hot.push_back(ttff(store, o, tr, StartMode::kHot));
    }
    row("cold", cold, "29 s (GPS; 26 s GPS+GLONASS)");
    row("warm", warm, "not given (ephemeris download as cold)");
    row("hot", hot, "1 s");
    std::printf("\n| blockage | fix back after (s): mean / median / p95 / max | satellite reacquired after, mean (s) | "
                "dead reckoning into the blockage, median (s) | hAcc before -> at its last epoch, median (m) |\n");
    std::printf("|---|---|---|---|---|\n");
    for (const double outage : {10.0, 60.0}) {
      std::vector<double> refix, reacq, coast, h0, h1;
      for (int k = 0; k < o.trials; ++k) {
        const Blockage b = blockage(store, o, trial(store, k), outage);
        refix.push_back(b.refix_s);
        reacq.push_back(b.sat_reacq_s);
        coast.push_back(b.coast_s);
        h0.push_back(b.hacc_start_m);
        h1.push_back(b.hacc_end_m);
      }
      const auto q = [](std::vector<double> v, double p) { return statistics::quantile_linear(std::move(v), p); };
      std::printf("| %.0f s | %.1f / %.1f / %.1f / %.1f | %.2f | %.1f | %.1f -> %.1f |\n", outage, statistics::mean(refix),
                  q(refix, 0.5), q(refix, 0.95), *std::max_element(refix.begin(), refix.end()), statistics::mean(reacq),
                  q(coast, 0.5), q(h0, 0.5), q(h1, 0.5));
    }
    std::printf("\nu-blox: reacquisition 1 s (issue 10; u-blox 7/M8 data sheets).\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ttff_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
