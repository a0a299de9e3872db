// SPDX-License-Identifier: Apache-2.0
#pragma once
// How u-blox names a satellite in NMEA: its number, the talker of its GSV
// group, the GSA system it is listed under and its GSV signal id, per NMEA
// version and CFG-NMEA svNumbering. Sources: u-blox "Satellite numbering"
// and "Signal identifiers" tables (ZED-F9P interface description
// UBX-18010854 appendix A/B), shared/reference/multi-gnss.md §7, the NEO-M9N
// and MAX-M8Q logs; the tables are reproduced in docs/nmea.md.
#include <array>
#include <cstdint>

#include "core/common/gnss_systems.hpp"
#include "core/common/sat_id.hpp"
#include "core/protocol/nmea/nmea_settings.hpp"

namespace gnssemu::protocol::nmea {

/// The NMEA systems a sentence can be about, in output order (GSA systemId
/// 1-5 - 1). SBAS always reports as GPS, QZSS as GPS before 4.11.
enum class NmeaSystem : std::uint8_t { kGps, kGlonass, kGalileo, kBeiDou, kQzss };
inline constexpr int kNumNmeaSystems = 5;

constexpr NmeaSystem nmea_system(GnssSystem s, NmeaVersion v) noexcept {
  if (s == GnssSystem::kQzss && v != NmeaVersion::k411) return NmeaSystem::kGps;
  return static_cast<NmeaSystem>(system_info(s).nmea_system_id - 1);
}

/// GSA systemId (4.10+): 1 GPS, 2 GLONASS, 3 Galileo, 4 BeiDou, 5 QZSS.
constexpr int system_id(NmeaSystem s) noexcept { return static_cast<int>(s) + 1; }

/// Talker of a single-system sentence about s ("GP", "GL", "GA", "GB" or the
/// configured BeiDou talker, "GQ").
constexpr std::array<char, 2> system_talker(NmeaSystem s, const NmeaSettings& cfg) noexcept {
  switch (s) {
    case NmeaSystem::kGps: return {'G', 'P'};
    case NmeaSystem::kGlonass: return {'G', 'L'};
    case NmeaSystem::kGalileo: return {'G', 'A'};
    case NmeaSystem::kBeiDou: return cfg.beidou_talker;
    case NmeaSystem::kQzss: return {'G', 'Q'};
  }
  return {'G', 'P'};
}

/// The satellite's NMEA number, or 0 when it is not output (no number in
/// this version and strict numbering, or out of the table's range).
constexpr int nmea_sv_number(SatId id, NmeaVersion v, SvNumbering numbering) noexcept {
  if (!id.valid()) return 0;
  const bool v4 = has_system_ids(v);
  const bool extended = numbering == SvNumbering::kExtended;
  const int n = id.number;
  switch (id.system) {
    case GnssSystem::kGps: return n;
    case GnssSystem::kGlonass: return 64 + n;  // slot + 64
    case GnssSystem::kSbas: {
      const int prn = id.prn();
      if (prn <= 151) return prn - 87;  // PRN 120-151 -> 33-64
      return extended ? prn : 0;        // 152-158 only as themselves
    }
    case GnssSystem::kGalileo: return v4 ? n : (extended ? 300 + n : 0);
    case GnssSystem::kBeiDou: return v4 ? n : (extended && n <= 37 ? 400 + n : 0);
    case GnssSystem::kQzss:
      if (v == NmeaVersion::k411) return n;  // GQ, 1-10
      return extended ? id.prn() : 0;        // 193-202 in GP
  }
  return 0;
}

/// GSV signalId (4.10+) of the L1-band signal a satellite is tracked on:
/// the M9's per-system ids (GPS/SBAS/QZSS L1C/A 1, GLONASS L1OF 1, Galileo
/// E1 7, BeiDou B1I 1); the M8 sends 0 ("all signals").
constexpr int l1_signal_id(GnssSystem s, NmeaDevice device) noexcept {
  if (device == NmeaDevice::kM8) return 0;
  return s == GnssSystem::kGalileo ? 7 : 1;
}

}  // namespace gnssemu::protocol::nmea
