// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/satpos.hpp"

#include <fmt/format.h>

#include <iterator>

namespace gnssemu::cli {

int write_satpos(const orbit::EphemerisStore& store, const time::GpsTime& t, std::ostream& out, SystemSet systems) {
  out << "sat,prn,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,clk_bias_s,toe_tow_s,iode\n";
  int rows = 0;
  fmt::memory_buffer buf;
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    if (!systems.has(sat.system)) continue;
    const orbit::Ephemeris* eph = store.select(sat, t);
    if (eph == nullptr) continue;
    const orbit::SatState s = orbit::sat_state(*eph, t);
    buf.clear();
    fmt::format_to(std::back_inserter(buf), "{},{},{:.4f},{:.4f},{:.4f},{:.6f},{:.6f},{:.6f},{:.15f},{:.3f},{}\n",
                   sat_name(sat).data(), sat.prn(),
                   s.pos_m.x, s.pos_m.y, s.pos_m.z, s.vel_m_s.x, s.vel_m_s.y, s.vel_m_s.z, s.clk_bias_s,
                   eph->toe.tow_s(), eph->iode);
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    ++rows;
  }
  return rows;
}

}  // namespace gnssemu::cli
