#include "tools/gnssemu/sky.hpp"

namespace gnssemu::cli {

int write_sky(const orbit::EphemerisStore&, const SkyRequest&, std::ostream& out) {
  out << "prn,az_deg,el_deg,range_m\n";
  return 0;
}

int write_dop(const orbit::EphemerisStore&, const SkyRequest&, std::ostream& out) {
  out << "gdop,pdop,hdop,vdop,tdop,nsat\n";
  return 0;
}

}  // namespace gnssemu::cli
