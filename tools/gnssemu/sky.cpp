// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sky.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <optional>
#include <span>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/geo/local_frame.hpp"
#include "core/atmosphere/receiver_corrections.hpp"
#include "core/atmosphere/troposphere.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/signal/link_budget.hpp"
#include "core/world/measurement/propagation.hpp"
#include "core/world/sky/sky.hpp"

namespace gnssemu::cli {

pipeline::PipelineConfig geometry_config(double mask_rad, SystemSet systems) {
  pipeline::PipelineConfig c;
  c.world.systems = systems;
  c.receiver.elevation_mask_rad = mask_rad;
  c.world.errors.thermal_sigma_m = 0.0;
  c.world.errors.orbit_clock.sigma_m = 0.0;
  c.world.errors.doppler_sigma_m_s = 0.0;
  c.world.clock.drift_noise_s_s_sqrt_s = 0.0;
  c.receiver.max_channels = kMaxSatsInView;
  c.receiver.max_pdop = receiver::ReceiverRanges::max_pdop.max;  // report poor geometry rather than drop the fix
  c.receiver.solver.residual_test_pfa = 0.0;  // nothing to detect without errors
  // One epoch of geometry: the solver alone, every satellite at once.
  c.receiver.filter.type = receiver::NavFilterType::kNone;
  c.receiver.acquisition.modelled = false;
  return c;
}

int write_sky(const orbit::EphemerisStore& store, const SkyRequest& req, std::ostream& out) {
  out << "sat,prn,az_deg,el_deg,range_m,iono_klobuchar_m,tropo_zhd_m,nmf_hydro,nmf_wet,atten_db,cn0_dbhz"
      << (req.scene ? ",los,bounces,nlos_delay_m,path_loss_db\n" : "\n");
  const Ecef rx = geo::ecef_from_lla(req.rx_lla);
  const world::WorldConfig defaults;
  world::AtmospherePropagation world(defaults.atmosphere);
  const signal::LinkBudgetModel link(defaults.signal.link);
  const double doy = req.t.fractional_day_of_year();
  const double zhd_m = atmosphere::receiver_zhd_m(req.rx_lla.lat_rad, req.rx_lla.height_m);
  const geo::LocalFrame frame(req.scene_origin);
  std::optional<scene::Propagator> prop;
  if (req.scene) prop.emplace(*req.scene, req.search);
  int rows = 0;
  fmt::memory_buffer buf;
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    if (!req.systems.has(sat.system)) continue;
    const orbit::Ephemeris* eph = store.select(sat, req.t);
    if (eph == nullptr) continue;
    const world::SkySat s = world::sky_sat(*eph, req.t, rx, req.rx_lla, Ecef());
    if (!(s.el_rad >= req.mask_rad)) continue;
    const double iono_m = atmosphere::receiver_iono_delay_m(req.klobuchar, req.rx_lla.lat_rad, req.rx_lla.lon_rad,
                                                            s.az_rad, s.el_rad, req.t.tow_s());
    const atmosphere::NiellMapping nmf =
        atmosphere::niell_mapping(s.el_rad, req.rx_lla.lat_rad, req.rx_lla.height_m, doy);
    const double atten_db =
        world.slow_terms(req.rx_lla, s.az_rad, s.el_rad, req.t.tow_s(), doy)[world::kAttenDb];
    buf.clear();
    fmt::format_to(std::back_inserter(buf), "{},{},{:.6f},{:.6f},{:.4f},{:.4f},{:.4f},{:.5f},{:.5f},{:.4f},{:.2f}",
                   sat_name(sat).data(), sat.prn(),
                   s.az_rad * kRadToDeg, s.el_rad * kRadToDeg, s.range_m, iono_m, zhd_m, nmf.hydro, nmf.wet, atten_db,
                   link.cn0_dbhz(s.range_m, s.el_rad, atten_db, sat.system, orbit::carrier_hz(*eph)));
    if (prop) {
      const scene::SatQuery q{sat.index(), frame.vector_to_enu((s.pos_m - rx) / s.range_m)};
      scene::SatPath p;
      prop->compute(frame.to_enu(rx), std::span<const scene::SatQuery>(&q, 1), std::span<scene::SatPath>(&p, 1));
      if (p.kind == scene::PathKind::kNone) {
        fmt::format_to(std::back_inserter(buf), ",0,0,,");
      } else {
        fmt::format_to(std::back_inserter(buf), ",{},{},{:.4f},{:.2f}", p.kind == scene::PathKind::kLos ? 1 : 0,
                       p.bounces, p.extra_delay_m, p.loss_db);
      }
    }
    buf.push_back('\n');
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    ++rows;
  }
  return rows;
}

DopResult write_dop(const orbit::EphemerisStore& store, const SkyRequest& req, std::ostream& out) {
  out << "gdop,pdop,hdop,vdop,tdop,nsat\n";
  pipeline::Pipeline rx(store, geometry_config(req.mask_rad, req.systems));
  world::Truth truth;
  truth.t = req.t;
  truth.pos_m = geo::ecef_from_lla(req.rx_lla);
  truth.valid = true;
  const receiver::Fix& fix = rx.step(req.t, truth);
  if (fix.type == receiver::FixType::k3D) {
    const receiver::Dop& d = fix.dop;
    out << fmt::format("{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{}\n", d.gdop, d.pdop, d.hdop, d.vdop, d.tdop,
                       fix.num_used);
    return {fix.num_used, true};
  }
  out << fmt::format(",,,,,{}\n", fix.num_visible);
  return {fix.num_visible, false};
}

}  // namespace gnssemu::cli
