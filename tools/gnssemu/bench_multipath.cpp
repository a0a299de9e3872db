// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/bench_multipath.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <span>

#include <time.h>

#include "config/setup/footprint_file.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/world/sky/sky.hpp"
#include "core/scene/procedural_city.hpp"
#include "core/scene/propagator.hpp"
#include "core/scene/scene.hpp"
#include "core/statistics/statistics.hpp"
#include "tools/gnssemu/sky.hpp"

namespace gnssemu::cli {

namespace {

struct Setting {
  int azimuth_rays;  ///< 0: hemisphere search with `rays`
  int rays;
  int bounces;
  double reuse_m;
  double reuse_deg;
};

// The sweep: elevation-cone rays (scenes of vertical/horizontal faces), the
// hemisphere search, depth, reuse thresholds.
constexpr Setting kSweep[] = {
    {32, 0, 16, 0.0, 0.0},    {64, 0, 16, 0.0, 0.0},    {128, 0, 16, 0.0, 0.0},   {256, 0, 16, 0.0, 0.0},
    {512, 0, 16, 0.0, 0.0},   {128, 0, 2, 0.0, 0.0},    {128, 0, 4, 0.0, 0.0},    {128, 0, 8, 0.0, 0.0},
    {128, 0, 16, 0.5, 0.5},   {128, 0, 16, 2.0, 1.0},   {0, 256, 16, 0.0, 0.0},   {0, 512, 16, 0.0, 0.0},
    {0, 1024, 16, 0.0, 0.0},  {0, 2048, 16, 0.0, 0.0},  {0, 4096, 16, 0.0, 0.0},  {0, 16384, 16, 0.0, 0.0},
    {0, 1024, 2, 0.0, 0.0},   {0, 1024, 4, 0.0, 0.0},   {0, 1024, 16, 0.5, 0.5},  {0, 1024, 16, 2.0, 1.0},
};

struct Epoch {
  time::GpsTime t;
  Enu rx_enu;
  Ecef rx_ecef;
  std::vector<scene::SatQuery> sats;  ///< above the mask, receiver's directions
};

void write_obj(const scene::Mesh& m, const std::string& path) {
  std::ofstream f(path, std::ios::trunc);
  if (!f) throw Error(path, 0, "cannot open for writing");
  f << "# gnssemu procedural city (ENU metres, z up)\n";
  for (const Vec3& v : m.vertices_m) f << fmt::format("v {:.3f} {:.3f} {:.3f}\n", v.x, v.y, v.z);
  uint16_t mat = 0xFFFF;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    if (m.material[i] != mat) {
      mat = m.material[i];
      f << "usemtl " << m.material_names[mat] << "\n";
    }
    const auto& t = m.triangles[i];
    f << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << "\n";
  }
  if (!f) throw Error(path, 0, "write failed");
}

// CPU time of this thread, us: the cost per core, unaffected by other load.
double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

struct FixTrace {
  std::vector<Ecef> pos;
  std::vector<bool> ok;
  std::vector<std::array<scene::PathKind, kNumSats>> kind;  ///< per epoch, by SatId::index()
  std::vector<std::array<double, kNumSats>> delay;
};

FixTrace run_receiver(const orbit::EphemerisStore& store, const std::vector<Epoch>& epochs, const scene::Scene& s,
                      const Lla& origin, const scene::SearchConfig& search, double mask_rad) {
  // Every fix kept (no residual test) so positions can be compared.
  pipeline::Pipeline rx(store, geometry_config(mask_rad), {}, world::SceneSetup{&s, origin, search});
  FixTrace tr;
  for (const Epoch& e : epochs) {
    world::Truth truth;
    truth.t = e.t;
    truth.pos_m = e.rx_ecef;
    truth.valid = true;
    const receiver::Fix& f = rx.step(e.t, truth);
    tr.ok.push_back(f.type == receiver::FixType::k3D);
    tr.pos.push_back(f.pos_m);
    std::array<scene::PathKind, kNumSats> k{};
    std::array<double, kNumSats> d{};
    k.fill(scene::PathKind::kLos);
    for (int i = 0; i < f.num_sats; ++i) {
      const receiver::SatInfo& si = f.sats[i];
      if (!si.above_mask) continue;
      const std::size_t j = static_cast<std::size_t>(si.sat.index());
      k[j] = si.blocked ? scene::PathKind::kNone : si.nlos ? scene::PathKind::kNlos : scene::PathKind::kLos;
      d[j] = si.nlos_delay_m;
    }
    tr.kind.push_back(k);
    tr.delay.push_back(d);
  }
  return tr;
}

}  // namespace

std::size_t median_repeat(const std::vector<double>& repeat_means) {
  if (repeat_means.empty()) return 0;
  std::vector<std::size_t> order(repeat_means.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return repeat_means[a] < repeat_means[b]; });
  return order[(order.size() - 1) / 2];
}

void run_bench_multipath(const BenchMultipathArgs& a, std::ostream& out, std::ostream& err) {
  if (a.origin.size() != 3) throw Error("--origin: expected LAT_DEG,LON_DEG,HEIGHT_M");
  const Lla origin{a.origin[0] * kDegToRad, a.origin[1] * kDegToRad, a.origin[2]};
  if (a.path_en_m.size() < 4 || a.path_en_m.size() % 2 != 0) {
    throw Error("--path: expected at least two points e0,n0,e1,n1,... (ENU m)");
  }
  if (!(a.speed_m_s > 0.0) || !(a.rate_hz > 0.0)) throw Error("--speed and --rate must be > 0");
  // Scene.
  scene::Mesh mesh;
  std::string scene_name;
  if (a.city_blocks > 0) {
    scene::CityConfig cc;
    cc.blocks = a.city_blocks;
    mesh = scene::make_city(cc);
    scene_name = fmt::format("procedural city {}x{} blocks", a.city_blocks, a.city_blocks);
    if (!a.write_city.empty()) write_obj(mesh, a.write_city);
  } else {
    mesh = config::load_mesh(a.scene_path);
    scene_name = a.scene_path;
    if (const std::string w = scene::skip_report(mesh.stats); !w.empty()) err << w << '\n';
  }
  const auto build0 = std::chrono::steady_clock::now();
  const scene::Scene buildings(mesh);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - build0).count();
  // Drive.
  const orbit::NavData nav = orbit::read_rinex_nav_files(a.nav_paths);
  const orbit::EphemerisStore store(nav.ephemerides);
  if (store.size() == 0) throw Error(nav.source, 0, "no GPS ephemerides");
  const time::GpsTime t0 = a.start ? *a.start : store.first_valid() + 7200.0;
  const geo::LocalFrame frame(origin);
  std::vector<Epoch> epochs;
  const double step_m = a.speed_m_s / a.rate_hz;
  double carry_m = 0.0;
  for (std::size_t i = 0; i + 3 < a.path_en_m.size(); i += 2) {
    const Vec3 p0(a.path_en_m[i], a.path_en_m[i + 1], a.antenna_height_m);
    const Vec3 p1(a.path_en_m[i + 2], a.path_en_m[i + 3], a.antenna_height_m);
    const double len = (p1 - p0).norm();
    for (double s = carry_m; s < len; s += step_m) {
      Epoch e;
      e.t = t0 + static_cast<double>(epochs.size()) / a.rate_hz;
      e.rx_enu = Enu(p0 + (p1 - p0) * (s / len));
      e.rx_ecef = frame.to_ecef(e.rx_enu);
      epochs.push_back(e);
      carry_m = s + step_m - len;
    }
  }
  const double mask_rad = a.mask_deg * kDegToRad;
  int sat_sum = 0;
  for (Epoch& e : epochs) {
    const Lla lla = geo::lla_from_ecef(e.rx_ecef);
    for (int i = 0; i < kNumSats; ++i) {
      const SatId sat = SatId::from_index(i);
      const orbit::Ephemeris* eph = store.select(sat, e.t);
      if (eph == nullptr) continue;
      const world::SkySat s = world::sky_sat(*eph, e.t, e.rx_ecef, lla, Ecef());
      if (!(s.el_rad >= mask_rad)) continue;
      e.sats.push_back({sat.index(), frame.vector_to_enu((s.pos_m - e.rx_ecef) / s.range_m)});
    }
    sat_sum += static_cast<int>(e.sats.size());
  }
  if (epochs.empty()) throw Error("--path: the drive has no epoch");
  const auto n_ep = static_cast<double>(epochs.size());
  err << fmt::format("scene: {} ({} triangles, BVH build {:.3f} s); {} epochs at {} Hz, {:.1f} satellites above {} deg\n",
                     scene_name, buildings.triangle_count(), build_s, epochs.size(), a.rate_hz,
                     static_cast<double>(sat_sum) / n_ep, a.mask_deg);

  // Dense reference.
  scene::SearchConfig ref;
  ref.rays = a.reference_rays;
  ref.azimuth_rays = buildings.vertical_horizontal() ? 4096 : 0;
  ref.max_bounces = 16;
  ref.match_factor = 1.5;
  ref.max_loss_db = a.max_loss_db;
  const FixTrace reference = run_receiver(store, epochs, buildings, origin, ref, mask_rad);
  {
    int nlos = 0, none = 0;
    double herr = 0.0;
    int fixes = 0;
    for (std::size_t k = 0; k < epochs.size(); ++k) {
      for (const scene::SatQuery& q : epochs[k].sats) {
        nlos += reference.kind[k][static_cast<std::size_t>(q.id)] == scene::PathKind::kNlos;
        none += reference.kind[k][static_cast<std::size_t>(q.id)] == scene::PathKind::kNone;
      }
      if (reference.ok[k]) {
        const Enu d = frame.vector_to_enu(reference.pos[k] - epochs[k].rx_ecef);
        herr += std::hypot(d.x, d.y);
        ++fixes;
      }
    }
    err << fmt::format("reference ({} rays, 16 bounces, loss cap {} dB): per epoch {:.2f} NLOS, {:.2f} not received; "
                       "{} of {} epochs with a 3D fix, mean horizontal error vs truth {:.2f} m (errors off)\n",
                       ref.azimuth_rays > 0 ? fmt::format("{} per satellite on its elevation cone", ref.azimuth_rays)
                                          : fmt::format("{} hemisphere", ref.rays),
                       a.max_loss_db, static_cast<double>(nlos) / n_ep, static_cast<double>(none) / n_ep,
                       fixes, epochs.size(), fixes > 0 ? herr / fixes : 0.0);
  }

  std::vector<Setting> sweep(std::begin(kSweep), std::end(kSweep));
  if (!a.settings.empty()) {
    if (a.settings.size() % 5 != 0) {
      throw Error("--settings: expected groups of 5: azimuth_rays,rays,max_bounces,reuse_m,reuse_deg");
    }
    sweep.clear();
    for (std::size_t i = 0; i < a.settings.size(); i += 5) {
      sweep.push_back({static_cast<int>(a.settings[i]), static_cast<int>(a.settings[i + 1]),
                       static_cast<int>(a.settings[i + 2]), a.settings[i + 3], a.settings[i + 4]});
    }
  }
  err << fmt::format("timing: thread CPU time per epoch; of {} repeat(s) per setting the median one by mean "
                     "gives mean, p95 and max\n",
                     std::max(1, a.repeats));
  out << "azimuth_rays,rays,max_bounces,reuse_m,reuse_deg,us_per_epoch_mean,us_per_epoch_p95,us_per_epoch_max,rays_per_epoch,"
         "misclassified,misclassified_pct,nlos_delay_err_rms_m,nlos_delay_err_max_m,pos_err_rms_m,pos_err_max_m\n";
  for (const Setting& st : sweep) {
    if (st.azimuth_rays > 0 && !buildings.vertical_horizontal()) {
      // Cone search needs vertical/horizontal faces; the receiver uses the hemisphere here too.
      if (!a.settings.empty()) {
        err << fmt::format("setting {},{},{},{},{} skipped: the scene has slanted faces, so the cone search does "
                           "not apply (use azimuth_rays 0)\n",
                           st.azimuth_rays, st.rays, st.bounces, st.reuse_m, st.reuse_deg);
      }
      continue;
    }
    scene::SearchConfig cfg;
    cfg.azimuth_rays = st.azimuth_rays;
    cfg.max_loss_db = a.max_loss_db;
    cfg.rays = st.rays > 0 ? st.rays : 1024;
    cfg.max_bounces = st.bounces;
    cfg.reuse_distance_m = st.reuse_m;
    cfg.reuse_angle_rad = st.reuse_deg * kDegToRad;
    // Timing: the scene stage alone on the receiver's queries. Every repeat
    // keeps its per-epoch times; the median repeat (by mean) is reported.
    cfg.rays = std::max(cfg.rays, 16);
    scene::validate(cfg);
    std::vector<double> repeat_means;
    std::vector<std::vector<double>> repeat_us;
    double rays_total = 0.0;
    for (int r = 0; r < std::max(1, a.repeats); ++r) {
      scene::Propagator prop(buildings, cfg);
      std::vector<scene::SatPath> paths(kMaxSatsInView);
      std::vector<double> per_epoch_us(epochs.size());
      double sum_us = 0.0;
      rays_total = 0.0;
      for (std::size_t k = 0; k < epochs.size(); ++k) {
        const Epoch& e = epochs[k];
        const double c0 = thread_cpu_us();
        prop.compute(e.rx_enu, e.sats, std::span<scene::SatPath>(paths.data(), e.sats.size()));
        const double us = thread_cpu_us() - c0;
        per_epoch_us[k] = us;
        sum_us += us;
        rays_total += static_cast<double>(prop.stats().rays);
      }
      repeat_means.push_back(sum_us / n_ep);
      repeat_us.push_back(std::move(per_epoch_us));
    }
    const std::size_t pick = median_repeat(repeat_means);
    const double mean_us = repeat_means[pick];
    const std::vector<double>& all_us = repeat_us[pick];
    // Error against the reference, through the full receiver.
    const FixTrace tr = run_receiver(store, epochs, buildings, origin, cfg, mask_rad);
    int mis = 0, total = 0, both_nlos = 0;
    double d2 = 0.0, dmax = 0.0, p2 = 0.0, pmax = 0.0;
    int pn = 0;
    for (std::size_t k = 0; k < epochs.size(); ++k) {
      for (const scene::SatQuery& q : epochs[k].sats) {
        const auto i = static_cast<std::size_t>(q.id);
        ++total;
        if (tr.kind[k][i] != reference.kind[k][i]) {
          ++mis;
        } else if (tr.kind[k][i] == scene::PathKind::kNlos) {
          const double dd = std::fabs(tr.delay[k][i] - reference.delay[k][i]);
          d2 += dd * dd;
          dmax = std::max(dmax, dd);
          ++both_nlos;
        }
      }
      if (tr.ok[k] && reference.ok[k]) {
        const double dp = (tr.pos[k] - reference.pos[k]).norm();
        p2 += dp * dp;
        pmax = std::max(pmax, dp);
        ++pn;
      } else if (tr.ok[k] != reference.ok[k]) {
        pmax = std::max(pmax, std::numeric_limits<double>::infinity());
      }
    }
    out << fmt::format("{},{},{},{},{},{:.1f},{:.1f},{:.1f},{:.0f},{},{:.2f},{:.3f},{:.3f},{:.3f},{:.3f}\n",
                       st.azimuth_rays, st.rays,
                       st.bounces, st.reuse_m, st.reuse_deg, mean_us, statistics::percentile_nearest_rank(all_us, 0.95),
                       statistics::max_abs(all_us), rays_total / n_ep, mis, 100.0 * mis / std::max(1, total),
                       both_nlos > 0 ? std::sqrt(d2 / both_nlos) : 0.0, dmax, pn > 0 ? std::sqrt(p2 / pn) : 0.0, pmax);
    out.flush();
  }
}

}  // namespace gnssemu::cli
