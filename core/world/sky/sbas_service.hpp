// SPDX-License-Identifier: Apache-2.0
#pragma once
// SBAS services: which GEO PRNs broadcast each system's L1 messages, the
// region its ground network corrects, and how well its corrections do there
// (docs/models.md "SBAS"). The world draws the corrections' residual errors
// at these figures; the receiver picks a service whose GEO it decodes.
#include <array>
#include <string_view>

#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"

namespace gnssemu::world {

struct SbasService {
  std::string_view name;
  /// GEO PRNs (120-158) that broadcast the service's messages; 0: unused entry.
  std::array<int, 6> prns;
  /// Service area as a latitude/longitude box, deg (an estimate of each
  /// system's published service area, docs/models.md).
  double lat_min_deg, lat_max_deg, lon_min_deg, lon_max_deg;
  /// RMS of the corrected orbit/clock range error (SISRE) and of the
  /// ionospheric correction (vertical, L1), m: Chen et al., Remote Sens.
  /// 11(4):411, 2019, 181 days of each service's messages.
  double sisre_m, iono_vertical_m;
};

/// Every service in the order a receiver prefers where areas overlap.
const std::array<SbasService, 8>& sbas_services() noexcept;

/// The service whose messages GEO prn carries; nullptr: none.
const SbasService* sbas_service_of_prn(int prn) noexcept;

/// Whether s's area covers the geodetic position p.
bool sbas_covers(const SbasService& s, const Lla& p) noexcept;

/// The first service (sbas_services() order) whose area covers p; nullptr: none.
const SbasService* sbas_service_at(const Lla& p) noexcept;

/// SBAS L1 (RTCA DO-229) corrects GPS satellites only; the L1 services in
/// operation broadcast no GLONASS, Galileo or BeiDou corrections.
constexpr bool sbas_corrects(GnssSystem s) noexcept { return s == GnssSystem::kGps; }

/// Slant over vertical ionospheric delay at elevation el_rad: the thin-shell
/// obliquity factor at 350 km (RTCA DO-229 A.4.4.10.4).
double sbas_obliquity(double el_rad) noexcept;

}  // namespace gnssemu::world
