// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/stations/simulated_station.hpp"

#include <optional>
#include <string>

#include "core/common/error.hpp"
#include "core/common/gnss_signals.hpp"
#include "core/geo/geodesy.hpp"
#include "core/world/world.hpp"

namespace gnssemu::cli {

observation::ObsData simulate_station(const observation::ObsData& real, const orbit::NavData& nav,
                                      const orbit::EphemerisStore& store, const world::WorldConfig& world,
                                      const Ecef& antenna_m, double mask_rad, SystemSet systems) {
  observation::ObsData out;
  out.source = real.source + " (simulated)";
  out.header.rinex_version = 3.05;
  out.header.file_system = systems == SystemSet::only(GnssSystem::kGps) ? 'G' : 'M';
  for (int k = 0; k < kNumSystems; ++k) {
    const auto sys = static_cast<GnssSystem>(k);
    const std::optional<SignalId> l1 = signal_of(sys, 0);
    if (!systems.has(sys) || !l1) continue;
    const std::string code = signal_info(*l1).rinex_code;  // "1C"; BeiDou B1I "2I"
    out.header.types_of(sys) = {"C" + code, "S" + code};
  }
  out.header.interval_s = real.header.interval_s;
  world::World w(store, world);
  w.set_klobuchar_shape(nav.klobuchar);
  world::Truth truth;
  truth.pos_m = antenna_m;
  truth.valid = true;
  for (const observation::ObsEpoch& e : real.epochs) {
    truth.t = e.t;
    const world::Observables& o = w.step(e.t, truth, mask_rad);
    observation::ObsEpoch sim;
    sim.t = o.t_rx_local;
    for (int i = 0; i < o.num_sats; ++i) {
      const world::SatObservable& s = o.sats[static_cast<std::size_t>(i)];
      if (!s.above_mask || !s.received || !systems.has(s.sat.system)) continue;
      observation::SatObs so;
      so.sat = s.sat;
      so.values = {observation::ObsValue{s.pseudorange_m, true, 0, 0}, observation::ObsValue{s.cn0_dbhz, true, 0, 0}};
      sim.sats.push_back(std::move(so));
    }
    out.epochs.push_back(std::move(sim));
  }
  return out;
}

Ecef antenna_reference_point(const observation::ObsHeader& h, const std::string& source) {
  if (!h.approx_pos_m) throw Error(source, 0, "no APPROX POSITION XYZ in the header");
  const Lla lla = geo::lla_from_ecef(*h.approx_pos_m);
  // antenna_delta_hen_m: x = H (up), y = E, z = N.
  const Enu d(h.antenna_delta_hen_m.y, h.antenna_delta_hen_m.z, h.antenna_delta_hen_m.x);
  return Ecef(*h.approx_pos_m + geo::enu_to_ecef_vector(d, lla.lat_rad, lla.lon_rad));
}

}  // namespace gnssemu::cli
