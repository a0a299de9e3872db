// SPDX-License-Identifier: Apache-2.0
#pragma once
// What u-blox CFG-NMEA (legacy message and CFG-NMEA-* keys) sets, plus the
// two device facts the sentences depend on: which systems the channels are
// assigned to (CFG-GNSS / CFG-SIGNAL-*) and the hardware generation.
// Sources: CFG-NMEA field list (ZED-F9P interface description UBX-18010854
// §UBX-CFG-NMEA; KumarRobotics/ublox CfgNMEA.msg from the M8 spec),
// CFG-NMEA-* key meanings (pyubx2 configdb); docs/nmea.md §Multi-GNSS.
#include <array>
#include <cstdint>

#include "core/common/sat_id.hpp"

namespace gnssemu::protocol::nmea {

/// NMEA standard version (CFG-NMEA nmeaVersion 0x21, 0x23, 0x40, 0x41, 0x4B;
/// CFG-NMEA-PROTVER 21, 23, 40, 41, 42). 2.1 drops the posMode fields; 2.3
/// and 4.0 print the same sentences; 4.10 adds RMC/GNS navStatus, GSA
/// systemId, GSV signalId and native Galileo/BeiDou numbers; 4.11 moves
/// QZSS to its own talker (GQ) and system id (5).
enum class NmeaVersion : std::uint8_t { k21, k23, k40, k410, k411 };

constexpr bool has_system_ids(NmeaVersion v) noexcept { return v == NmeaVersion::k410 || v == NmeaVersion::k411; }

/// CFG-NMEA svNumbering: what happens to satellites without an NMEA-defined
/// number (Galileo and BeiDou before 4.10, QZSS, SBAS PRN 152-158).
enum class SvNumbering : std::uint8_t {
  kStrict = 0,    ///< not output
  kExtended = 1,  ///< u-blox numbers (Galileo 301-336, BeiDou 401-437, QZSS 193-202)
};

/// CFG-NMEA mainTalkerId / CFG-NMEA-MAINTALKERID (values as the key's).
enum class MainTalker : std::uint8_t { kAuto = 0, kGp = 1, kGl = 2, kGn = 3, kGa = 4, kGb = 5, kGq = 7 };

/// CFG-NMEA gsvTalkerId / CFG-NMEA-GSVTALKERID.
enum class GsvTalker : std::uint8_t {
  kPerSystem = 0,  ///< each system's own talker (GP, GL, GA, GB, GQ)
  kMain = 1,       ///< the main talker for every GSV
};

/// The u-blox generation the sentences imitate (ubx::Generation one to one).
enum class NmeaDevice : std::uint8_t {
  kM8,  ///< NEO-M8N/MAX-M8Q: GSV signalId 0 (all signals) in 4.10 mode
  kM9,  ///< NEO-M9N: GSV signalId of the L1 signal (1; Galileo E1 7)
  kF9,  ///< ZED-F9P: as the M9, with a GSV group per signal
};

struct NmeaSettings {
  NmeaVersion version = NmeaVersion::k411;
  SvNumbering sv_numbering = SvNumbering::kStrict;
  /// Most satellites reported per talker in GSV and per system in GSA:
  /// 0 (unlimited), 8, 12 or 16 (CFG-NMEA numSV / CFG-NMEA-MAXSVS).
  int max_svs = 0;
  /// Compatibility mode: fixed number of digits in the coordinates. Ours
  /// always have them (ddmm.mmmmm, dddmm.mmmmm), so it changes nothing.
  bool compat = false;
  /// Considering mode: satellites the solution considered but excluded
  /// (RAIM) count as used in GGA/GNS numSV and GSA.
  bool consider = false;
  /// Strict 82-character limit. Every sentence we write fits in 82
  /// characters in every mode (a GSA of twelve three-digit numbers lists
  /// eleven), so it changes nothing (docs/nmea.md).
  bool limit82 = false;
  MainTalker main_talker = MainTalker::kAuto;
  GsvTalker gsv_talker = GsvTalker::kPerSystem;
  /// BeiDou talker (CFG-NMEA bdsTalkerId; "GB" is u-blox's default).
  std::array<char, 2> beidou_talker{'G', 'B'};
  /// Systems whose satellites are not output (CFG-NMEA gnssToFilter).
  SystemSet filtered;
  /// Systems the receiver's channels are assigned to (CFG-GNSS enabled,
  /// CFG-SIGNAL-*_ENA). Each gets its GSA and GSV even with no satellite;
  /// more than one NMEA system makes the main talker GN. Systems with
  /// satellites in the Fix count as enabled too.
  SystemSet systems;
  NmeaDevice device = NmeaDevice::kM9;

  constexpr bool operator==(const NmeaSettings&) const = default;
};

/// A factory-fresh device's settings: NMEA 4.0 on the M8 (MAX-M8Q log in
/// gpsd's ublox-8.log), 4.10 on the NEO-M9N (ublox-neo-m9n-nmea.log);
/// strict numbering, unlimited SVs, considering mode on; enabled systems
/// as the factory CFG-GNSS has them (M8: GPS, GLONASS, QZSS, SBAS; M9N:
/// GPS, GLONASS, Galileo, BeiDou, QZSS, SBAS).
constexpr NmeaSettings factory_settings(NmeaDevice device) noexcept {
  NmeaSettings s;
  s.device = device;
  s.consider = true;
  s.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGlonass).with(GnssSystem::kQzss).with(GnssSystem::kSbas);
  if (device == NmeaDevice::kM8) {
    s.version = NmeaVersion::k40;
  } else {
    s.version = NmeaVersion::k410;
    s.systems = s.systems.with(GnssSystem::kGalileo).with(GnssSystem::kBeiDou);
  }
  return s;
}

}  // namespace gnssemu::protocol::nmea
