// SPDX-License-Identifier: Apache-2.0
#pragma once
// The NMEA output settings a host sets through CFG-NMEA (every length: 4,
// 12, 20 bytes) or the CFG-NMEA-* keys (M9): one stored CFG-NMEA version-1
// payload, read here field by field for the NMEA encoder. Layout: u-blox M8
// Receiver Description UBX-13003221 CFG-NMEA; keys: ubx_config_keys.cpp.
#include <array>
#include <cstdint>

#include "core/protocol/nmea/nmea_settings.hpp"
#include "core/protocol/ubx/config/ubx_device_config.hpp"

namespace gnssemu::protocol::ubx {

struct CfgNmeaSettings {
  /// filter b0 posFilt, b1 mskPosFilt, b2 timeFilt, b3 dateFilt, b4 gpsOnlyFilter, b5 trackFilt
  /// (CFG-NMEA-OUT_INVFIX, _MSKFIX, _INVTIME, _INVDATE, _ONLYGPS, _FROZENCOG).
  std::uint8_t filter = 0;
  std::uint8_t nmea_version = 0x40;  ///< 0x21, 0x23, 0x40, 0x41 (4.10), 0x4B (4.11)
  std::uint8_t max_svs = 0;          ///< SVs per talker: 0 unlimited, 8, 12, 16
  bool compat = false;               ///< compatibility mode
  bool consider = false;             ///< considering mode
  bool limit82 = false;              ///< sentences of at most 82 characters
  bool high_prec = false;            ///< high-precision position digits
  /// Systems not reported: b0 GPS, b1 SBAS, b2 Galileo, b4 QZSS, b5 GLONASS, b6 BeiDou.
  std::uint32_t gnss_to_filter = 0;
  std::uint8_t sv_numbering = 0;     ///< 0 strict, 1 extended
  std::uint8_t main_talker_id = 0;   ///< 0 by system, 1 GP, 2 GL, 3 GN, 4 GA, 5 GB, 7 GQ
  std::uint8_t gsv_talker_id = 0;    ///< 0 the system's talker, 1 the main talker
  std::array<char, 2> bds_talker_id{};  ///< BeiDou talker; zeros: GB
};

/// The settings the stored CFG-NMEA block of c holds (defaults without one).
inline CfgNmeaSettings cfg_nmea_settings(const DeviceConfig& c) noexcept {
  CfgNmeaSettings s;
  const StoredBlock* b = c.stored(msg::kCfgNmea);
  if (b == nullptr || b->size < 4) return s;
  const auto& p = b->bytes;
  s.filter = p[0];
  s.nmea_version = p[1];
  s.max_svs = p[2];
  s.compat = p[3] & 0x01;
  s.consider = p[3] & 0x02;
  s.limit82 = p[3] & 0x04;
  s.high_prec = p[3] & 0x08;
  if (b->size < 12) return s;
  s.gnss_to_filter = static_cast<std::uint32_t>(p[4]) | static_cast<std::uint32_t>(p[5]) << 8 |
                     static_cast<std::uint32_t>(p[6]) << 16 | static_cast<std::uint32_t>(p[7]) << 24;
  s.sv_numbering = p[8];
  s.main_talker_id = p[9];
  s.gsv_talker_id = p[10];
  if (b->size < 20) return s;
  s.bds_talker_id = {static_cast<char>(p[12]), static_cast<char>(p[13])};
  return s;
}

/// CFG-NMEA nmeaVersion of an NMEA version (0x21, 0x23, 0x40, 0x41, 0x4B).
constexpr std::uint8_t cfg_nmea_version(nmea::NmeaVersion v) noexcept {
  switch (v) {
    case nmea::NmeaVersion::k21: return 0x21;
    case nmea::NmeaVersion::k23: return 0x23;
    case nmea::NmeaVersion::k40: return 0x40;
    case nmea::NmeaVersion::k410: return 0x41;
    case nmea::NmeaVersion::k411: return 0x4B;
  }
  return 0x40;
}

/// The encoder's settings from a host's CFG-NMEA: base supplies what CFG-NMEA
/// does not carry (the device); systems are the ones the channels are
/// assigned to. Values outside the message's ranges keep base's (the
/// handlers store only what the device accepts).
nmea::NmeaSettings nmea_settings_from(const CfgNmeaSettings& c, nmea::NmeaSettings base, SystemSet systems) noexcept;

}  // namespace gnssemu::protocol::ubx
