// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/config/ubx_cfg_nmea.hpp"

namespace gnssemu::protocol::ubx {
namespace {

// gnssToFilter bits (CFG-NMEA; CFG-NMEA-FILT_*).
constexpr struct {
  std::uint32_t bit;
  GnssSystem system;
} kFilterBits[] = {{1u << 0, GnssSystem::kGps},   {1u << 1, GnssSystem::kSbas},    {1u << 2, GnssSystem::kGalileo},
                   {1u << 4, GnssSystem::kQzss},  {1u << 5, GnssSystem::kGlonass}, {1u << 6, GnssSystem::kBeiDou}};

}  // namespace

nmea::NmeaSettings nmea_settings_from(const CfgNmeaSettings& c, nmea::NmeaSettings base, SystemSet systems) noexcept {
  using nmea::NmeaVersion;
  switch (c.nmea_version) {
    case 0x21: base.version = NmeaVersion::k21; break;
    case 0x23: base.version = NmeaVersion::k23; break;
    case 0x40: base.version = NmeaVersion::k40; break;
    case 0x41: base.version = NmeaVersion::k410; break;
    case 0x4B: base.version = NmeaVersion::k411; break;
    default: break;
  }
  if (c.max_svs == 0 || c.max_svs == 8 || c.max_svs == 12 || c.max_svs == 16) base.max_svs = c.max_svs;
  base.compat = c.compat;
  base.consider = c.consider;
  base.limit82 = c.limit82;
  if (c.sv_numbering <= 1) base.sv_numbering = static_cast<nmea::SvNumbering>(c.sv_numbering);
  if (c.main_talker_id <= 5 || c.main_talker_id == 7) base.main_talker = static_cast<nmea::MainTalker>(c.main_talker_id);
  if (c.gsv_talker_id <= 1) base.gsv_talker = static_cast<nmea::GsvTalker>(c.gsv_talker_id);
  // Zeros: u-blox's default "GB" (CFG-NMEA bdsTalkerId).
  if (c.bds_talker_id[0] != 0 && c.bds_talker_id[1] != 0) base.beidou_talker = c.bds_talker_id;
  else base.beidou_talker = {'G', 'B'};
  base.filtered = SystemSet{};
  for (const auto& f : kFilterBits) {
    if ((c.gnss_to_filter & f.bit) != 0) base.filtered = base.filtered.with(f.system);
  }
  base.systems = systems;
  return base;
}

}  // namespace gnssemu::protocol::ubx
