// SPDX-License-Identifier: Apache-2.0
#include "core/geo/geoid.hpp"

#include <cmath>
#include <cstdint>

#include "core/common/constants.hpp"

namespace gnssemu::geo {
namespace {

constexpr int kRows = 37;  // latitude -90..+90 deg
constexpr int kCols = 73;  // longitude -180..+180 deg, last column == first
constexpr double kStepDeg = 5.0;

constexpr std::int16_t kGeoidCm[kRows][kCols] = {
#include "core/geo/egm2008_5deg.inc"
};

constexpr bool table_is_consistent() {
  for (int r = 0; r < kRows; ++r) {
    if (kGeoidCm[r][0] != kGeoidCm[r][kCols - 1]) return false;
  }
  for (int c = 1; c < kCols; ++c) {
    if (kGeoidCm[0][c] != kGeoidCm[0][0]) return false;
    if (kGeoidCm[kRows - 1][c] != kGeoidCm[kRows - 1][0]) return false;
  }
  return true;
}
static_assert(table_is_consistent(), "geoid grid: poles constant, -180 == +180");

}  // namespace

double geoid_separation_m(double lat_rad, double lon_rad) noexcept {
  double lat_deg = lat_rad * kRadToDeg;
  double lon_deg = lon_rad * kRadToDeg;
  // Also catches finite radians whose degrees overflow.
  if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return 0.0;
  if (lat_deg > 90.0) lat_deg = 90.0;
  if (lat_deg < -90.0) lat_deg = -90.0;
  lon_deg = std::fmod(lon_deg + 180.0, 360.0);  // (-360, 360)
  if (lon_deg < 0.0) lon_deg += 360.0;           // [0, 360]

  const double y = (lat_deg + 90.0) / kStepDeg;  // [0, 36]
  const double x = lon_deg / kStepDeg;           // [0, 72]
  int r = static_cast<int>(y);
  int c = static_cast<int>(x);
  if (r > kRows - 2) r = kRows - 2;
  if (c > kCols - 2) c = kCols - 2;
  const double fy = y - r;
  const double fx = x - c;

  const double s = (1.0 - fx) * kGeoidCm[r][c] + fx * kGeoidCm[r][c + 1];
  const double n = (1.0 - fx) * kGeoidCm[r + 1][c] + fx * kGeoidCm[r + 1][c + 1];
  return ((1.0 - fy) * s + fy * n) * 0.01;
}

}  // namespace gnssemu::geo
