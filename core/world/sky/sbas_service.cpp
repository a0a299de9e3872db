// SPDX-License-Identifier: Apache-2.0
#include "core/world/sky/sbas_service.hpp"

#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::world {

namespace {

// PRNs: the GEOs each operator has broadcast on (EGNOS also its test and
// retired ones, so older logs and nav files match). Areas: boxes around each
// system's published service area (an estimate). Accuracies: Chen et al.
// 2019 (abstract figures); KASS, BDSBAS and SouthPAN postdate it and are
// taken as EGNOS (an estimate).
constexpr std::array<SbasService, 8> kServices{{
    {"EGNOS", {120, 121, 123, 124, 126, 136}, 25.0, 72.0, -30.0, 45.0, 0.645, 0.491},
    {"WAAS", {131, 133, 135, 138, 0, 0}, 15.0, 72.0, -170.0, -50.0, 0.954, 0.505},
    {"MSAS", {129, 137, 0, 0, 0, 0}, 20.0, 48.0, 122.0, 150.0, 1.931, 0.795},
    {"KASS", {134, 0, 0, 0, 0, 0}, 32.0, 40.0, 124.0, 132.0, 0.645, 0.491},
    {"GAGAN", {127, 128, 132, 0, 0, 0}, 0.0, 38.0, 65.0, 100.0, 1.325, 0.858},
    {"SDCM", {125, 140, 141, 0, 0, 0}, 40.0, 75.0, 25.0, 180.0, 0.650, 0.523},
    {"BDSBAS", {130, 143, 144, 0, 0, 0}, 15.0, 55.0, 73.0, 135.0, 0.645, 0.491},
    {"SouthPAN", {122, 0, 0, 0, 0, 0}, -48.0, -8.0, 108.0, 180.0, 0.645, 0.491},
}};

// Earth radius and shell height of the obliquity factor, m (DO-229 A.4.4.10.4).
constexpr double kRe_m = 6378136.3;
constexpr double kShell_m = 350000.0;

}  // namespace

const std::array<SbasService, 8>& sbas_services() noexcept { return kServices; }

const SbasService* sbas_service_of_prn(int prn) noexcept {
  if (prn <= 0) return nullptr;
  for (const SbasService& s : kServices)
    for (int p : s.prns)
      if (p == prn) return &s;
  return nullptr;
}

bool sbas_covers(const SbasService& s, const Lla& p) noexcept {
  const double lat = p.lat_rad * kRadToDeg, lon = p.lon_rad * kRadToDeg;
  return lat >= s.lat_min_deg && lat <= s.lat_max_deg && lon >= s.lon_min_deg && lon <= s.lon_max_deg;
}

const SbasService* sbas_service_at(const Lla& p) noexcept {
  for (const SbasService& s : kServices)
    if (sbas_covers(s, p)) return &s;
  return nullptr;
}

double sbas_obliquity(double el_rad) noexcept {
  const double c = kRe_m * std::cos(el_rad) / (kRe_m + kShell_m);
  return 1.0 / std::sqrt(1.0 - c * c);
}

}  // namespace gnssemu::world
