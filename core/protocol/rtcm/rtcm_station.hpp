// SPDX-License-Identifier: Apache-2.0
#pragma once
// Station messages: 1005/1006 (antenna reference point, without/with antenna
// height) and 1230 (GLONASS L1/L2 code-phase biases). Field order and scales:
// RTCM 10403.3 via shared/reference/rtk-raw.md §2.2 and §2.6.
#include <array>
#include <optional>
#include <string>

#include "core/common/vec3.hpp"

namespace gnssemu::protocol::rtcm {

/// What 1005/1006 say about a reference station.
struct StationInfo {
  int station_id = 0;            ///< DF003, 0..4095
  Ecef arp_ecef_m;               ///< antenna reference point, ECEF, m (DF025-027, 0.1 mm)
  double antenna_height_m = 0.0; ///< DF028 (1006 only), 0..6.5535 m
  bool gps = true;               ///< DF022: the station observes GPS
  bool glonass = false;          ///< DF023
  bool galileo = false;          ///< DF024
};

/// Appends a framed 1005 (with_height false) or 1006.
void append_station(const StationInfo& st, bool with_height, std::string& out);

/// The four code-phase biases of 1230 in the order of its mask (DF422, MSB
/// first): L1 C/A, L1 P, L2 C/A, L2 P; m, resolution 0.02 m; empty = not sent.
using GlonassBiases = std::array<std::optional<double>, 4>;

/// Appends a framed 1230. aligned: DF421, the observations' code and phase
/// are aligned (1) or not (0).
void append_glonass_biases(int station_id, bool aligned, const GlonassBiases& biases_m, std::string& out);

}  // namespace gnssemu::protocol::rtcm
