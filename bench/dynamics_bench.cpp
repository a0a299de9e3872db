// SPDX-License-Identifier: Apache-2.0
// dynamics_bench: how the emulated receiver moves, per dynamic model.
// Static: epoch-to-epoch steps of the fix (horizontal, vertical), speed and
// climb noise at 1 Hz and 10 Hz, straight from the Fix (no NMEA rounding).
// Moving: a car at 20 m/s with two 0.3 g turns, a 0.3 g stop, 20 s standing
// and a restart: the along-track lag of the fix (-(fix - truth) . t / speed),
// the overshoot of the stop, and the speed error; lag and overshoot in a
// world without errors (the filter's own dynamics), speed error and lag also
// in the default world. Prints tables; not a test.
//   dynamics_bench [--nav FILE] [--seeds N] [--section static|moving|all]
//                  [--model NAME] [--profile ublox_m8|geodetic] [--position-noise M2_S] [--smoothing S]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/pipeline/receiver_profile.hpp"
#include "core/statistics/statistics.hpp"

namespace {

using namespace gnssemu;
using pipeline::PipelineConfig;
using receiver::DynamicModel;

const Lla kSite{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};  // config/default.toml origin
constexpr DynamicModel kModels[] = {DynamicModel::kPortable,   DynamicModel::kStationary,  DynamicModel::kPedestrian,
                                    DynamicModel::kAutomotive, DynamicModel::kSea,         DynamicModel::kAirborne1g,
                                    DynamicModel::kAirborne2g, DynamicModel::kAirborne4g, DynamicModel::kWrist};

struct Options {
  std::string nav = std::string(GNSSEMU_SOURCE_DIR) + "/tests/data/nav/brdc0010.22n";
  int seeds = 5;
  std::string section = "all";
  std::string model;             // empty: every model
  std::string profile;           // empty: the built-in default world
  double position_noise = -1.0;  // < 0: the default
  double smoothing = -1.0;
};

double q(std::vector<double> v, double p) { return statistics::quantile_linear(std::move(v), p); }

/// A world without random errors, atmosphere or receiver corrections: the
/// snapshot fix is the truth, so what remains is the filter's dynamics.
PipelineConfig errorless(PipelineConfig c) {
  c.world.errors.orbit_clock.sigma_m = 0.0;
  c.world.errors.thermal_model = world::ThermalModel::kFixed;
  c.world.errors.thermal_sigma_m = 0.0;
  c.world.errors.doppler_sigma_m_s = 0.0;
  c.world.errors.multipath.sigma_m = 0.0;
  c.world.errors.gradient = {};
  c.world.errors.iono_scale.sigma = 0.0;
  c.world.carrier.doppler_model = world::DopplerModel::kFixed;
  c.world.carrier.oscillator_sigma_rad = 0.0;
  c.world.clock.drift_noise_s_s_sqrt_s = 0.0;
  c.world.atmosphere.ionosphere.enabled = false;
  c.world.atmosphere.troposphere.enabled = false;
  c.world.atmosphere.gases = false;
  c.receiver.solver.iono = atmosphere::IonoCorrection::kNone;
  c.receiver.solver.tropo = atmosphere::TropoCorrection::kNone;
  return c;
}

PipelineConfig base(const Options& o, DynamicModel m, uint64_t seed) {
  PipelineConfig c;
  if (!o.profile.empty()) c = pipeline::apply_profile(c, pipeline::receiver_profile(o.profile), kSite.lat_rad);
  c.world.seed = seed;
  c.receiver.filter.dynamic_model = m;
  if (o.position_noise >= 0.0) c.receiver.filter.position_noise_m2_s = o.position_noise;
  if (o.smoothing >= 0.0) c.receiver.filter.smoothing_window_s = o.smoothing;
  return c;
}

// ---------------------------------------------------------------- static

struct StaticFigures {
  std::vector<double> h, v, speed, climb;
};

void run_static(const orbit::EphemerisStore& store, const PipelineConfig& cfg, const time::GpsTime& t0, double rate_hz,
                double span_s, StaticFigures& f) {
  pipeline::Pipeline rx(store, cfg);
  const geo::LocalFrame frame(kSite);
  world::Truth tr;
  tr.pos_m = frame.origin_ecef();
  tr.valid = true;
  bool have = false;
  Enu prev;
  const int n = static_cast<int>(span_s * rate_hz);
  for (int k = 0; k <= n; ++k) {
    tr.t = t0 + k / rate_hz;
    const receiver::Fix& fx = rx.step(tr.t, tr);
    if (fx.type != receiver::FixType::k3D || k < 60 * rate_hz) {
      have = false;  // the first minute: acquisition and the filter settling
      continue;
    }
    const Enu e = frame.to_enu(fx.pos_m);
    if (have) {
      f.h.push_back(std::hypot(e.x - prev.x, e.y - prev.y));
      f.v.push_back(std::fabs(e.z - prev.z));
    }
    f.speed.push_back(fx.speed_m_s);
    f.climb.push_back(std::fabs(fx.climb_m_s));
    prev = e;
    have = true;
  }
}

void static_section(const Options& o, const orbit::EphemerisStore& store) {
  std::printf("\n## Static receiver (default world, %d seeds, 1 h at 1 Hz / 10 min at 10 Hz each, first minute dropped)\n\n",
              o.seeds);
  std::printf("| model | rate | h step median / p95 (m) | v step median / p95 (m) | speed median / p95 (m/s) | climb p95 (m/s) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const DynamicModel m : kModels) {
    if (!o.model.empty() && receiver::dynamic_model_name(m) != o.model) continue;
    for (const double rate : {1.0, 10.0}) {
      StaticFigures f;
      for (int s = 1; s <= o.seeds; ++s) {
        const time::GpsTime t0 = store.first_valid() + 3600.0 * s;
        run_static(store, base(o, m, static_cast<uint64_t>(s)), t0, rate, rate > 1.0 ? 660.0 : 3660.0, f);
      }
      std::printf("| %s | %g Hz | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.3f |\n",
                  std::string(receiver::dynamic_model_name(m)).c_str(), rate, q(f.h, 0.5), q(f.h, 0.95),
                  q(f.v, 0.5), q(f.v, 0.95), q(f.speed, 0.5), q(f.speed, 0.95), q(f.climb, 0.95));
    }
  }
}

// ---------------------------------------------------------------- moving

struct Sample {
  Enu pos, vel;
};

/// The drive, in the local frame, every 1 ms: 50 s straight north at 20 m/s,
/// a right turn at 0.3 g through 90 deg, 15 s straight, a left turn, 10 s,
/// braking at 0.3 g to a stop, 20 s standing, 2 m/s^2 back to 20 m/s, 15 s.
std::vector<Sample> drive(double& stop_begin_s, double& stop_end_s) {
  struct Segment {
    double duration_s, accel_m_s2, turn_rad_s;
  };
  const double g03 = 0.3 * 9.80665;
  const double v0 = 20.0;
  const double turn = g03 / v0;
  const double turn_s = (kPi / 2.0) / turn;
  const double brake_s = v0 / g03;
  const Segment segs[] = {{50.0, 0.0, 0.0},      {turn_s, 0.0, turn}, {15.0, 0.0, 0.0}, {turn_s, 0.0, -turn},
                          {10.0, 0.0, 0.0},      {brake_s, -g03, 0.0}, {20.0, 0.0, 0.0}, {10.0, 2.0, 0.0},
                          {15.0, 0.0, 0.0}};
  std::vector<Sample> out;
  const double dt = 1e-3;
  double e = 0, n = 0, heading = 0, speed = v0, t = 0;
  for (const Segment& s : segs) {
    if (s.accel_m_s2 < 0.0) stop_begin_s = t + s.duration_s;
    if (s.accel_m_s2 > 0.0) stop_end_s = t;
    const int steps = static_cast<int>(std::lround(s.duration_s / dt));
    for (int k = 0; k < steps; ++k, t += dt) {
      out.push_back({Enu(e, n, 0.0), Enu(speed * std::sin(heading), speed * std::cos(heading), 0.0)});
      const double speed_next = std::max(speed + s.accel_m_s2 * dt, 0.0);
      const double heading_next = heading + s.turn_rad_s * dt;
      const double vm = 0.5 * (speed + speed_next), hm = 0.5 * (heading + heading_next);
      e += vm * std::sin(hm) * dt;
      n += vm * std::cos(hm) * dt;
      speed = speed_next;
      heading = heading_next;
    }
  }
  return out;
}

struct MovingFigures {
  std::vector<double> lag_s, speed_err;
  double overshoot_m = 0.0;
  int epochs = 0, fixes = 0;
};

void run_drive(const orbit::EphemerisStore& store, const PipelineConfig& cfg, const time::GpsTime& t0, double rate_hz,
               const std::vector<Sample>& path, double stop_begin_s, double stop_end_s, MovingFigures& f) {
  pipeline::Pipeline rx(store, cfg);
  const geo::LocalFrame frame(kSite);
  // 60 s standing before the drive: acquisition and the filter settle.
  const double lead_s = 60.0;
  const double span_s = 1e-3 * static_cast<double>(path.size() - 1);
  Enu dir_before_stop(0.0, 1.0, 0.0);
  for (int k = 0;; ++k) {
    const double t_s = k / rate_hz - lead_s;
    if (t_s > span_s) break;
    const std::size_t i = t_s <= 0.0 ? 0 : static_cast<std::size_t>(std::lround(t_s * 1e3));
    Sample s = path[std::min(i, path.size() - 1)];
    if (t_s < 0.0) s.vel = Enu(0.0, 0.0, 0.0);
    world::Truth tr;
    tr.t = t0 + k / rate_hz;
    tr.pos_m = frame.to_ecef(t_s < 0.0 ? path[0].pos : s.pos);
    tr.vel_m_s = Ecef(frame.vector_to_ecef(s.vel));
    tr.valid = true;
    const receiver::Fix& fx = rx.step(tr.t, tr);
    if (t_s < 0.0) continue;
    ++f.epochs;
    const double speed = std::hypot(s.vel.x, s.vel.y);
    if (speed > 1.0) dir_before_stop = Enu(s.vel.x / speed, s.vel.y / speed, 0.0);
    if (fx.type == receiver::FixType::kNone) continue;
    ++f.fixes;
    const Enu d = frame.to_enu(fx.pos_m);
    const Enu err(d.x - s.pos.x, d.y - s.pos.y, d.z - s.pos.z);
    f.speed_err.push_back(fx.speed_m_s - speed);
    if (speed > 1.0) f.lag_s.push_back(-(err.x * s.vel.x + err.y * s.vel.y) / (speed * speed));
    if (t_s >= stop_begin_s && t_s < stop_end_s)
      f.overshoot_m = std::max(f.overshoot_m, err.x * dir_before_stop.x + err.y * dir_before_stop.y);
  }
}

void moving_section(const Options& o, const orbit::EphemerisStore& store) {
  double stop_begin = 0, stop_end = 0;
  const std::vector<Sample> path = drive(stop_begin, stop_end);
  std::printf("\n## Moving: 20 m/s, two 0.3 g turns, a 0.3 g stop, 20 s standing, restart (%d seeds)\n\n", o.seeds);
  std::printf("Lag: -(fix - truth) . direction / speed while faster than 1 m/s (positive: the fix trails).\n");
  std::printf("Overshoot: largest (fix - stop point) along the last direction while standing.\n\n");
  std::printf("| model | rate | fixes | no errors: lag mean / p95 abs (s) | no errors: overshoot max (m) | default world: "
              "lag mean / p95 abs (s) | speed error median abs / p95 abs (m/s) |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const DynamicModel m : kModels) {
    if (!o.model.empty() && receiver::dynamic_model_name(m) != o.model) continue;
    for (const double rate : {1.0, 10.0}) {
      MovingFigures clean, real;
      for (int s = 1; s <= o.seeds; ++s) {
        const time::GpsTime t0 = store.first_valid() + 3600.0 * s;
        run_drive(store, errorless(base(o, m, static_cast<uint64_t>(s))), t0, rate, path, stop_begin, stop_end, clean);
        run_drive(store, base(o, m, static_cast<uint64_t>(s)), t0, rate, path, stop_begin, stop_end, real);
      }
      const auto abs_of = [](std::vector<double> v) {
        for (double& x : v) x = std::fabs(x);
        return v;
      };
      std::printf("| %s | %g Hz | %.1f %% | %+.3f / %.3f | %.2f | %+.3f / %.3f | %.3f / %.3f |\n",
                  std::string(receiver::dynamic_model_name(m)).c_str(), rate,
                  real.epochs ? 100.0 * real.fixes / real.epochs : 0.0, statistics::mean(clean.lag_s),
                  q(abs_of(clean.lag_s), 0.95), clean.overshoot_m, statistics::mean(real.lag_s),
                  q(abs_of(real.lag_s), 0.95), q(abs_of(real.speed_err), 0.5), q(abs_of(real.speed_err), 0.95));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--nav") o.nav = argv[i + 1];
    else if (k == "--seeds") o.seeds = std::max(1, std::atoi(argv[i + 1]));
    else if (k == "--section") o.section = argv[i + 1];
    else if (k == "--model") o.model = argv[i + 1];
    else if (k == "--profile") o.profile = argv[i + 1];
    else if (k == "--position-noise") o.position_noise = std::atof(argv[i + 1]);
    else if (k == "--smoothing") o.smoothing = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "dynamics_bench: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  try {
    const orbit::NavData nav = orbit::read_rinex_nav(o.nav);
    const orbit::EphemerisStore store(nav.ephemerides);
    std::printf("# dynamics_bench: %s, Paris (48.8738 N 2.2950 E), %s per dynamic model\n", o.nav.c_str(),
                o.profile.empty() ? "default PipelineConfig" : ("receiver profile " + o.profile).c_str());
    if (o.section == "static" || o.section == "all") static_section(o, store);
    if (o.section == "moving" || o.section == "all") moving_section(o, store);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dynamics_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
