// SPDX-License-Identifier: Apache-2.0
#pragma once
// Test helpers: Fix from JSON (golden cases) and a minimal NMEA splitter.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::nmea::test {

/// Fix from a JSON object. Angles in degrees (`lat_deg`, `course_deg`,
/// `el_deg`, `az_deg`), time as GPS `week` + `tow_s`, `type` "none"/"2d"/"3d".
/// num_used / num_tracked / num_visible are counted from `sats` unless given.
receiver::Fix fix_from_json(const nlohmann::json& j);
/// Encoder config from the optional "config" object: `device` "m8"/"m9"
/// (factory_settings), `version` "2.1"/"2.3"/"4.0"/"4.10"/"4.11",
/// `sv_numbering` "strict"/"extended", `max_svs`, `consider`, `systems`
/// ("G,R,E"), booleans per sentence (`gga`, ..., `gns`, `gbs`),
/// `course_min_speed_m_s`. A satellite is `prn` (GPS) or `sat` ("R05").
NmeaConfig config_from_json(const nlohmann::json& j);
/// "2.1", "2.3", "4.0", "4.10", "4.11".
NmeaVersion version_from_text(const std::string& v);

/// Sentences of a CR LF separated stream (CR LF removed).
std::vector<std::string> split_lines(std::string_view stream);

/// One parsed sentence: address without '$' ("GPGGA"), type ("GGA"), fields
/// after the address (checksum removed).
struct Sentence {
  std::string address;
  std::string type;
  std::vector<std::string> fields;
  std::string talker() const { return address.substr(0, 2); }  ///< "GN"
};
/// Splits "$ADDR,f1,...*hh"; the checksum is not verified here.
Sentence parse_sentence(std::string_view line);

/// A plausible 3D fix near Zurich: 10 satellites in view (PRN 16 not tracked),
/// 9 used, moving at 13.4 m/s on course 87.3 deg.
receiver::Fix sample_fix_3d();

}  // namespace gnssemu::protocol::nmea::test
