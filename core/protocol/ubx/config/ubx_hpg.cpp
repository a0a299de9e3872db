// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/config/ubx_hpg.hpp"

#include <algorithm>
#include <cmath>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/wire/ubx_encoder_detail.hpp"

namespace gnssemu::protocol::ubx {

namespace {

using namespace detail;
using receiver::CarrierSolution;
using receiver::Fix;

/// The value of key id in c (0 when no generation has it), as the signed
/// integer of its wire size when the key is signed.
double key_value(const DeviceConfig& c, std::uint32_t id) noexcept {
  const ConfigKey* k = find_config_key(id);
  if (k == nullptr) return 0.0;
  const std::uint64_t v = read_config_key(*k, c, 0);
  if (!k->is_signed) return static_cast<double>(v);
  const std::size_t bits = 8 * k->value_bytes();
  const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
  const std::uint64_t m = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
  return static_cast<double>(static_cast<std::int64_t>((v & m) ^ sign) - static_cast<std::int64_t>(sign));
}

// Key ids (docs/ubx.md key table).
constexpr std::uint32_t kDgnssMode = 0x20140011, kDgnssTo = 0x201100C4, kUart2Enabled = 0x10530005,
                        kUart2Baud = 0x40530001, kTmodeMode = 0x20030001, kTmodePosType = 0x20030002,
                        kTmodeEcefX = 0x40030003, kTmodeEcefXHp = 0x20030006, kTmodeLat = 0x40030009,
                        kTmodeLon = 0x4003000A, kTmodeHeight = 0x4003000B, kTmodeLatHp = 0x2003000C,
                        kTmodeLonHp = 0x2003000D, kTmodeHeightHp = 0x2003000E, kTmodeFixedAcc = 0x4003000F,
                        kTmodeSvinDur = 0x40030010, kTmodeSvinAcc = 0x40030011;

std::uint32_t acc_01mm(double m) noexcept { return to_acc<std::uint32_t>(m * 1e4); }

}  // namespace

HpSplit hp_split(double value, double fine, int ratio) noexcept {
  if (!std::isfinite(value)) return {};
  const double lim = static_cast<double>(ratio) * 2147483647.0;
  const std::int64_t total = std::llround(std::clamp(value / fine, -lim, lim));
  return {static_cast<std::int32_t>(total / ratio), static_cast<std::int8_t>(total % ratio)};
}

HpgSettings hpg_settings(const DeviceConfig& c) noexcept {
  HpgSettings s;
  const double mode = key_value(c, kDgnssMode);
  s.dgnss_mode = mode == 2.0 ? DgnssMode::kRtkFloat : DgnssMode::kRtkFixed;
  s.dgnss_timeout_s = key_value(c, kDgnssTo);
  s.uart2.enabled = key_value(c, kUart2Enabled) != 0.0;
  s.uart2.baud_bps = static_cast<std::uint32_t>(key_value(c, kUart2Baud));
  s.uart2.in_proto_mask = c.port(kPortUart2).in_proto_mask;
  s.uart2.out_proto_mask = c.port(kPortUart2).out_proto_mask;
  const double tmode = key_value(c, kTmodeMode);
  s.tmode.mode = tmode == 1.0 ? TimeMode::kSurveyIn : tmode == 2.0 ? TimeMode::kFixed : TimeMode::kDisabled;
  s.tmode.llh = key_value(c, kTmodePosType) != 0.0;
  for (std::uint32_t i = 0; i < 3; ++i) {
    s.tmode.ecef_m[i] = 1e-2 * key_value(c, kTmodeEcefX + i) + 1e-4 * key_value(c, kTmodeEcefXHp + i);
  }
  s.tmode.lat_deg = 1e-7 * key_value(c, kTmodeLat) + 1e-9 * key_value(c, kTmodeLatHp);
  s.tmode.lon_deg = 1e-7 * key_value(c, kTmodeLon) + 1e-9 * key_value(c, kTmodeLonHp);
  s.tmode.height_m = 1e-2 * key_value(c, kTmodeHeight) + 1e-4 * key_value(c, kTmodeHeightHp);
  s.tmode.fixed_pos_acc_m = 1e-4 * key_value(c, kTmodeFixedAcc);
  s.tmode.svin_min_dur_s = key_value(c, kTmodeSvinDur);
  s.tmode.svin_acc_limit_m = 1e-4 * key_value(c, kTmodeSvinAcc);
  return s;
}

std::size_t nav_hpposllh(const Fix& fix, std::string& out) {
  const Common c = derive(fix);
  wire::NavHpposllh m{};
  m.iTOW = c.itow;
  if (c.has_fix) {
    const HpSplit lon = hp_split(c.lon_deg, 1e-9), lat = hp_split(c.lat_deg, 1e-9);
    const HpSplit h = hp_split(c.height_m, 1e-4, 10), msl = hp_split(c.hmsl_m, 1e-4, 10);
    m.lon = lon.coarse;
    m.lonHp = lon.hp;
    m.lat = lat.coarse;
    m.latHp = lat.hp;
    m.height = h.coarse;
    m.heightHp = h.hp;
    m.hMSL = msl.coarse;
    m.hMSLHp = msl.hp;
    m.hAcc = acc_01mm(fix.h_acc_m);
    m.vAcc = acc_01mm(fix.v_acc_m);
  } else {
    m.flags = 0x01;  // invalidLlh
    m.hAcc = m.vAcc = 0xFFFFFFFF;
  }
  return append_message(out, msg::kNavHpposllh, m);
}

std::size_t nav_hpposecef(const Fix& fix, std::string& out) {
  const Common c = derive(fix);
  wire::NavHpposecef m{};
  m.iTOW = c.itow;
  if (c.has_fix && fix.pos_m.finite()) {
    const HpSplit x = hp_split(fix.pos_m.x, 1e-4), y = hp_split(fix.pos_m.y, 1e-4), z = hp_split(fix.pos_m.z, 1e-4);
    m.ecefX = x.coarse;
    m.ecefXHp = x.hp;
    m.ecefY = y.coarse;
    m.ecefYHp = y.hp;
    m.ecefZ = z.coarse;
    m.ecefZHp = z.hp;
    m.pAcc = acc_01mm(std::hypot(fix.h_acc_m, fix.v_acc_m));
  } else {
    m.flags = 0x01;  // invalidEcef
    m.pAcc = 0xFFFFFFFF;
  }
  return append_message(out, msg::kNavHpposecef, m);
}

std::size_t nav_relposned(const Fix& fix, std::string& out) {
  const Common c = derive(fix);
  const receiver::RelativePosition& r = fix.rel_pos;
  wire::NavRelposnedV1 m{};
  m.version = 1;
  m.iTOW = c.itow;
  if (r.late) {
    // A moving-base rover's time-matched baseline: the iTOW of its epoch (rounded as derive() does).
    std::int64_t ms = std::llround(r.t.tow_s() * 1000.0);
    if (ms >= kMsPerWeek) ms -= kMsPerWeek;
    m.iTOW = static_cast<std::uint32_t>(std::max<std::int64_t>(ms, 0));
  }
  m.refStationId = static_cast<std::uint16_t>(std::clamp(r.ref_station_id, 0, 4095));
  std::uint32_t flags = 0;
  if (c.fix_ok) flags |= 1u << 0;
  // A relative position is differential by construction: with a moving base
  // the rover's NAV-PVT stays standalone (diff_soln false) but RELPOSNED's
  // baseline comes from the base's observations.
  if (fix.diff_soln || r.valid) flags |= 1u << 1;
  if (r.valid) {
    const HpSplit n = hp_split(r.n_m, 1e-4), e = hp_split(r.e_m, 1e-4), d = hp_split(r.d_m, 1e-4),
                  len = hp_split(r.length_m, 1e-4);
    m.relPosN = n.coarse;
    m.relPosHPN = n.hp;
    m.relPosE = e.coarse;
    m.relPosHPE = e.hp;
    m.relPosD = d.coarse;
    m.relPosHPD = d.hp;
    m.relPosLength = len.coarse;
    m.relPosHPLength = len.hp;
    m.accN = acc_01mm(r.acc_n_m);
    m.accE = acc_01mm(r.acc_e_m);
    m.accD = acc_01mm(r.acc_d_m);
    m.accLength = acc_01mm(r.acc_length_m);
    flags |= 1u << 2;
    flags |= static_cast<std::uint32_t>(r.carr_soln) << 3;
    if (r.heading_valid) {
      m.relPosHeading = to_int<std::int32_t>(deg0_360(r.heading_rad) * 1e5);
      m.accHeading = to_acc<std::uint32_t>(r.acc_heading_rad * kRadToDeg * 1e5);
      flags |= 1u << 8;
    }
  }
  if (r.moving_base) flags |= 1u << 5;
  if (r.ref_pos_miss) flags |= 1u << 6;
  if (r.ref_obs_miss) flags |= 1u << 7;
  m.flags = flags;
  return append_message(out, msg::kNavRelposned, m);
}

std::size_t rxm_cor_rtcm(std::uint16_t msg_type, std::uint16_t sub_type, bool crc_ok, bool used, std::string& out) {
  wire::RxmCor m{};
  m.version = 1;
  constexpr std::uint32_t kProtocolRtcm3 = 1;
  std::uint32_t status = kProtocolRtcm3;
  status |= (crc_ok ? 1u : 2u) << 5;   // errStatus
  status |= (used ? 2u : 1u) << 7;     // msgUsed
  status |= 1u << 25;                  // msgTypeValid
  if (msg_type == 4072) status |= 1u << 26;  // msgSubTypeValid
  m.statusInfo = status;
  m.msgType = msg_type;
  m.msgSubType = msg_type == 4072 ? sub_type : 0;
  return append_message(out, msg::kRxmCor, m);
}

}  // namespace gnssemu::protocol::ubx
