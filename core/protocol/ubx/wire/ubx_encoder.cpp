// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/wire/ubx_encoder.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/protocol/ubx/device/ubx_front_end.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "core/time/gps_time.hpp"

#include "core/protocol/ubx/wire/ubx_encoder_detail.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/config/ubx_hpg.hpp"

namespace gnssemu::protocol::ubx {

namespace {

using namespace detail;
using receiver::Fix;
using receiver::FixType;
using receiver::SatInfo;
constexpr std::uint8_t kChipGenM8 = 4;       // NAV-SVINFO globalFlags chipGen (ubx.md §3)
constexpr std::uint8_t kUtcStandardUsno = 3;  // NAV-TIMEUTC: UTC from GPS (USNO)
constexpr std::size_t kMaxExtensions = 10;
constexpr std::size_t kMaxStringChars = 29;   // CH[30] with NUL

/// NAV-PVT flags3 bits 1-4 lastCorrectionAge (protocol 27 and later): 0
/// none, then the age bins < 1, 2, 5, 10, 15, 20, 30, 45, 60, 90, 120 s and >= 120 s.
std::uint8_t last_correction_age(double age_s) noexcept {
  if (!(age_s >= 0.0)) return 0;
  constexpr double kUpper[] = {1, 2, 5, 10, 15, 20, 30, 45, 60, 90, 120};
  std::uint8_t code = 12;
  for (std::uint8_t i = 0; i < std::size(kUpper); ++i) {
    if (age_s < kUpper[i]) {
      code = static_cast<std::uint8_t>(i + 1);
      break;
    }
  }
  return static_cast<std::uint8_t>(code << 1);
}

void put_string(char* dst, std::size_t size, const std::string& s) noexcept {
  std::memset(dst, 0, size);
  std::memcpy(dst, s.data(), std::min(s.size(), size - 1));
}

}  // namespace

std::uint32_t itow_ms(const Fix& fix) noexcept { return derive(fix).itow; }

bool reports_fix_ok(const Fix& fix, FixOverride reported) noexcept {
  if (reported) return gnss_fix_ok(*reported);
  return has_fix(fix) && fix.type != FixType::kDeadReckoning;
}

MonVerConfig mon_ver_of(Generation g) {
  if (g == Generation::kM8) return {};
  MonVerConfig c;
  if (g == Generation::kF9P) {
    c.sw_version = "EXT CORE 1.00 (f4c834)";
    c.hw_version = "00190000";
    c.rom_base = "ROM BASE 0x118B2060";
    c.fw_version = "HPG 1.32";
    c.protocol_version = 27.31;
    c.extensions = {"MOD=ZED-F9P", "GPS;GLO;GAL;BDS", "SBAS;QZSS"};
    c.generation = g;
    return c;
  }
  c.sw_version = "EXT CORE 4.04 (7f89f7)";
  c.hw_version = "00190000";
  c.rom_base = "ROM BASE 0x118B2060";
  c.fw_version = "SPG 4.04";
  c.protocol_version = 32.01;
  c.extensions = {"MOD=NEO-M9N", "GPS;GLO;GAL;BDS", "SBAS;QZSS"};
  c.generation = g;
  return c;
}

void validate(const MonVerConfig& config) {
  const auto bad = [](const std::string& what) { throw Error("ubx", 0, "MON-VER: " + what); };
  if (config.sw_version.empty() || config.sw_version.size() > kMaxStringChars) {
    bad("sw_version must have 1.." + std::to_string(kMaxStringChars) + " characters");
  }
  if (config.hw_version.size() != 8 ||
      !std::all_of(config.hw_version.begin(), config.hw_version.end(), [](char ch) { return std::isxdigit(static_cast<unsigned char>(ch)); })) {
    bad("hw_version must be 8 hex digits (00080000 = M8), got '" + config.hw_version + "'");
  }
  if (config.fw_version.size() + 6 > kMaxStringChars) bad("fw_version too long");
  const bool m9 = is_generation9(config.generation);
  const double lo = m9 ? 27.0 : 18.0, hi = m9 ? 50.0 : 24.0;
  if (!std::isfinite(config.protocol_version) || config.protocol_version < lo || config.protocol_version >= hi) {
    bad(std::string("protocol_version must be in ") + (m9 ? "[27, 50) for a u-blox 9" : "[18, 24) for an M8") +
        " (PX4 uses CFG-VALSET from 27)");
  }
  if (config.rom_base.size() > kMaxStringChars) bad("rom_base too long");
  if (config.extensions.size() + (config.rom_base.empty() ? 2 : 3) > kMaxExtensions) bad("too many extension strings");
  for (const auto& e : config.extensions) {
    if (e.empty() || e.size() > kMaxStringChars) bad("extension '" + e + "' must have 1..29 characters");
  }
}

UbxEncoder::UbxEncoder(const MonVerConfig& config) : config_(config) {
  validate(config_);
  wire::MonVerHead head{};
  put_string(head.swVersion, sizeof head.swVersion, config_.sw_version);
  put_string(head.hwVersion, sizeof head.hwVersion, config_.hw_version);
  mon_ver_payload_.assign(reinterpret_cast<const char*>(&head), sizeof head);
  const auto add_ext = [&](const std::string& s) {
    char ext[wire::kMonVerExtensionBytes];
    put_string(ext, sizeof ext, s);
    mon_ver_payload_.append(ext, sizeof ext);
  };
  if (!config_.rom_base.empty()) add_ext(config_.rom_base);
  add_ext("FWVER=" + config_.fw_version);
  char protver[32];
  std::snprintf(protver, sizeof protver, "PROTVER=%05.2f", config_.protocol_version);
  add_ext(protver);
  for (const auto& e : config_.extensions) add_ext(e);
}

std::size_t UbxEncoder::nav_pvt(const Fix& fix, std::string& out) const { return nav_pvt_as(fix, std::nullopt, out); }

std::size_t UbxEncoder::nav_pvt_as(const Fix& fix, FixOverride reported, std::string& out) const {
  const Common c = derive(fix, reported);
  wire::NavPvt m{};
  m.iTOW = c.itow;
  if (c.has_time) {
    m.year = static_cast<std::uint16_t>(c.year);
    m.month = static_cast<std::uint8_t>(c.month);
    m.day = static_cast<std::uint8_t>(c.day);
    m.hour = static_cast<std::uint8_t>(c.hour);
    m.min = static_cast<std::uint8_t>(c.minute);
    m.sec = static_cast<std::uint8_t>(c.second);
    m.valid = 0x07;  // validDate, validTime, fullyResolved
    m.nano = c.nano;
  }
  m.tAcc = c.has_time ? to_acc<std::uint32_t>(fix.time_acc_s * 1e9) : 0xFFFFFFFF;
  m.fixType = c.fix_type;
  m.flags = c.fix_ok ? 0x01 : 0x00;  // gnssFixOK
  if (c.has_fix && fix.diff_soln) m.flags |= 0x02;  // diffSoln
  if (c.has_fix) m.flags |= static_cast<std::uint8_t>(static_cast<unsigned>(fix.carr_soln) << 6);  // carrSoln
  if (is_generation9(config_.generation)) m.flags3 = last_correction_age(fix.corr_age_s);
  m.numSV = c.num_sv;
  if (c.has_fix) {
    m.lon = to_int<std::int32_t>(c.lon_deg * 1e7);
    m.lat = to_int<std::int32_t>(c.lat_deg * 1e7);
    m.height = to_int<std::int32_t>(c.height_m * 1e3);
    m.hMSL = to_int<std::int32_t>(c.hmsl_m * 1e3);
    m.hAcc = to_acc<std::uint32_t>(fix.h_acc_m * 1e3);
    m.vAcc = to_acc<std::uint32_t>(fix.v_acc_m * 1e3);
    m.velN = to_int<std::int32_t>(c.vel_n * 1e3);
    m.velE = to_int<std::int32_t>(c.vel_e * 1e3);
    m.velD = to_int<std::int32_t>(c.vel_d * 1e3);
    m.gSpeed = to_int<std::int32_t>(c.speed_2d * 1e3);
    m.headMot = to_int<std::int32_t>(c.course_deg * 1e5);
    m.sAcc = to_acc<std::uint32_t>(fix.speed_acc_m_s * 1e3);
    m.headAcc = to_acc<std::uint32_t>(c.course_acc_deg * 1e5);
    m.headVeh = m.headMot;  // no vehicle heading without sensors (headVehValid clear)
  } else {
    m.hAcc = m.vAcc = m.sAcc = 0xFFFFFFFF;
    m.headAcc = to_acc<std::uint32_t>(180.0 * 1e5);
  }
  m.pDOP = dop_u2(fix.dop.pdop, c.has_fix);
  if (!c.has_fix) m.flags3 |= 0x01;  // invalidLlh
  return append_message(out, msg::kNavPvt, m);
}

std::size_t UbxEncoder::nav_posllh(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  wire::NavPosllh m{};
  m.iTOW = c.itow;
  if (c.has_fix) {
    m.lon = to_int<std::int32_t>(c.lon_deg * 1e7);
    m.lat = to_int<std::int32_t>(c.lat_deg * 1e7);
    m.height = to_int<std::int32_t>(c.height_m * 1e3);
    m.hMSL = to_int<std::int32_t>(c.hmsl_m * 1e3);
    m.hAcc = to_acc<std::uint32_t>(fix.h_acc_m * 1e3);
    m.vAcc = to_acc<std::uint32_t>(fix.v_acc_m * 1e3);
  } else {
    m.hAcc = m.vAcc = 0xFFFFFFFF;
  }
  return append_message(out, msg::kNavPosllh, m);
}

std::size_t UbxEncoder::nav_status(const Fix& fix, const EpochInfo& info, std::string& out) const {
  const Common c = derive(fix, info.reported_fix);
  wire::NavStatus m{};
  m.iTOW = c.itow;
  m.gpsFix = c.fix_type;
  m.flags = nav_flags(c);
  // flags2 b3-4 spoofDetState (the receiver's spoofing detection; 1 "no
  // spoofing indicated" in real M8 logs).
  m.flags2 = static_cast<std::uint8_t>(spoof_det_state(fix) << 3);
  m.ttff = info.ttff_ms;
  m.msss = info.msss_ms;
  return append_message(out, msg::kNavStatus, m);
}

std::size_t UbxEncoder::nav_dop(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  wire::NavDop m{};
  m.iTOW = c.itow;
  m.gDOP = dop_u2(fix.dop.gdop, c.has_fix);
  m.pDOP = dop_u2(fix.dop.pdop, c.has_fix);
  m.tDOP = dop_u2(fix.dop.tdop, c.has_fix);
  m.vDOP = dop_u2(fix.dop.vdop, c.has_fix);
  m.hDOP = dop_u2(fix.dop.hdop, c.has_fix);
  // North/east DOP from the solver's sigma_n/sigma_e = sigma_uere * nDOP/eDOP;
  // split HDOP evenly when the solver gave no sigma.
  double ndop = fix.dop.hdop / std::sqrt(2.0), edop = ndop;
  if (std::isfinite(fix.sigma_uere_m) && fix.sigma_uere_m > 0.0 && std::isfinite(fix.sigma_n_m) &&
      std::isfinite(fix.sigma_e_m) && fix.sigma_n_m > 0.0 && fix.sigma_e_m > 0.0) {
    ndop = fix.sigma_n_m / fix.sigma_uere_m;
    edop = fix.sigma_e_m / fix.sigma_uere_m;
  }
  m.nDOP = dop_u2(ndop, c.has_fix);
  m.eDOP = dop_u2(edop, c.has_fix);
  return append_message(out, msg::kNavDop, m);
}

std::size_t UbxEncoder::nav_sol(const Fix& fix, std::string& out) const { return nav_sol_as(fix, std::nullopt, out); }

std::size_t UbxEncoder::nav_sol_as(const Fix& fix, FixOverride reported, std::string& out) const {
  const Common c = derive(fix, reported);
  wire::NavSol m{};
  m.iTOW = c.itow;
  m.fTOW = c.ftow_ns;
  m.week = c.has_time ? c.week : 0;
  m.gpsFix = c.fix_type;
  m.flags = nav_flags(c);
  m.numSV = c.num_sv;
  m.pDOP = dop_u2(fix.dop.pdop, c.has_fix);
  if (c.has_fix && fix.pos_m.finite()) {
    m.ecefX = to_int<std::int32_t>(fix.pos_m.x * 100.0);
    m.ecefY = to_int<std::int32_t>(fix.pos_m.y * 100.0);
    m.ecefZ = to_int<std::int32_t>(fix.pos_m.z * 100.0);
    m.pAcc = to_acc<std::uint32_t>(std::hypot(fix.h_acc_m, fix.v_acc_m) * 100.0);
    if (fix.vel_m_s.finite()) {
      m.ecefVX = to_int<std::int32_t>(fix.vel_m_s.x * 100.0);
      m.ecefVY = to_int<std::int32_t>(fix.vel_m_s.y * 100.0);
      m.ecefVZ = to_int<std::int32_t>(fix.vel_m_s.z * 100.0);
    }
    m.sAcc = to_acc<std::uint32_t>(fix.speed_acc_m_s * 100.0);
  } else {
    m.pAcc = m.sAcc = 0xFFFFFFFF;
  }
  return append_message(out, msg::kNavSol, m);
}

std::size_t UbxEncoder::nav_velned(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  wire::NavVelned m{};
  m.iTOW = c.itow;
  if (c.has_fix) {
    m.velN = to_int<std::int32_t>(c.vel_n * 100.0);
    m.velE = to_int<std::int32_t>(c.vel_e * 100.0);
    m.velD = to_int<std::int32_t>(c.vel_d * 100.0);
    m.speed = to_acc<std::uint32_t>(c.speed_3d * 100.0);
    m.gSpeed = to_acc<std::uint32_t>(c.speed_2d * 100.0);
    m.heading = to_int<std::int32_t>(c.course_deg * 1e5);
    m.sAcc = to_acc<std::uint32_t>(fix.speed_acc_m_s * 100.0);
    m.cAcc = to_acc<std::uint32_t>(c.course_acc_deg * 1e5);
  } else {
    m.sAcc = 0xFFFFFFFF;
    m.cAcc = to_acc<std::uint32_t>(180.0 * 1e5);
  }
  return append_message(out, msg::kNavVelned, m);
}

std::size_t UbxEncoder::nav_timegps(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  wire::NavTimegps m{};
  m.iTOW = c.itow;
  m.fTOW = c.ftow_ns;
  m.week = c.has_time ? c.week : 0;
  m.leapS = static_cast<std::int8_t>(std::clamp(fix.leap_seconds, -128, 127));
  m.valid = c.has_time ? 0x07 : 0x00;  // towValid, weekValid, leapSValid
  m.tAcc = c.has_time ? to_acc<std::uint32_t>(fix.time_acc_s * 1e9) : 0xFFFFFFFF;
  return append_message(out, msg::kNavTimegps, m);
}

std::size_t UbxEncoder::nav_timeutc(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  wire::NavTimeutc m{};
  m.iTOW = c.itow;
  m.tAcc = c.has_time ? to_acc<std::uint32_t>(fix.time_acc_s * 1e9) : 0xFFFFFFFF;
  if (c.has_time) {
    m.nano = c.nano;
    m.year = static_cast<std::uint16_t>(c.year);
    m.month = static_cast<std::uint8_t>(c.month);
    m.day = static_cast<std::uint8_t>(c.day);
    m.hour = static_cast<std::uint8_t>(c.hour);
    m.min = static_cast<std::uint8_t>(c.minute);
    m.sec = static_cast<std::uint8_t>(c.second);
    m.valid = static_cast<std::uint8_t>(0x07 | kUtcStandardUsno << 4);
  }
  return append_message(out, msg::kNavTimeutc, m);
}

std::size_t UbxEncoder::nav_sat(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  std::uint8_t buf[sizeof(wire::NavSatHeader) + kMaxSatsInView * sizeof(wire::NavSatSv)];
  wire::NavSatHeader h{};
  h.iTOW = c.itow;
  h.version = 1;
  std::size_t len = sizeof h;
  for_each_in_ubx_order(fix, [&](const SatInfo& s) {
    wire::NavSatSv sv{};
    sv.gnssId = system_info(s.sat.system).ubx_gnss_id;
    sv.svId = ubx_sv_id(s.sat);
    sv.cno = cno_u1(s);
    sv.elev = elev_i1(s);
    sv.azim = azim_i2(s);
    const bool used = s.used && c.has_fix;
    sv.prRes = used ? to_int<std::int16_t>(s.residual_m * 10.0) : 0;
    std::uint32_t flags = quality_ind(s);
    if (used) flags |= 1u << 3;
    flags |= (s.healthy ? 1u : 2u) << 4;  // health: 1 healthy, 2 unhealthy
    if (s.smoothed) flags |= 1u << 7;
    if (s.healthy) flags |= 1u << 12;                          // almAvail
    if (s.healthy && s.ephemeris) flags |= 1u << 8 | 1u << 11;  // orbitSource ephemeris, ephAvail
    // b6 diffCorr (corrections for it received), b16 sbasCorrUsed (applied in the solution).
    if (s.sbas_corr) flags |= 1u << 6;
    if (used && s.sbas_corr) flags |= 1u << 16;
    sv.flags = flags;
    std::memcpy(buf + len, &sv, sizeof sv);
    len += sizeof sv;
    ++h.numSvs;
  });
  std::memcpy(buf, &h, sizeof h);
  return append_frame(out, msg::kNavSat, {buf, len});
}

std::size_t UbxEncoder::nav_svinfo(const Fix& fix, std::string& out) const {
  const Common c = derive(fix);
  std::uint8_t buf[sizeof(wire::NavSvinfoHeader) + kMaxSatsInView * sizeof(wire::NavSvinfoCh)];
  wire::NavSvinfoHeader h{};
  h.iTOW = c.itow;
  h.globalFlags = kChipGenM8;
  std::size_t len = sizeof h;
  std::uint8_t channel = 0;
  for_each_in_ubx_order(fix, [&](const SatInfo& s) {
    const std::uint8_t svid = svinfo_svid(s.sat);
    if (svid == 0) return;  // no M8 number (BeiDou C38-C63, GLONASS slots > 32)
    wire::NavSvinfoCh ch{};
    const bool tracked = s.tracked && s.cn0_dbhz > 0.0;
    ch.chn = tracked ? channel++ : 255;  // 255: not assigned to a channel (real M8 logs)
    ch.svid = svid;
    const bool used = s.used && c.has_fix;
    std::uint8_t flags = used ? 0x01 : 0x00;
    // orbitAvail + orbitEph (or orbitAlm without its ephemeris), or unhealthy; b7 smoothed
    flags |= s.healthy ? (s.ephemeris ? 0x0C : 0x24) : 0x10;
    if (s.smoothed) flags |= 0x80;
    if (s.sbas_corr) flags |= 0x02;  // diffCorr: differential correction data available
    ch.flags = flags;
    ch.quality = quality_ind(s);
    ch.cno = cno_u1(s);
    ch.elev = elev_i1(s);
    ch.azim = azim_i2(s);
    ch.prRes = used ? to_int<std::int32_t>(s.residual_m * 100.0) : 0;
    std::memcpy(buf + len, &ch, sizeof ch);
    len += sizeof ch;
    ++h.numCh;
  });
  std::memcpy(buf, &h, sizeof h);
  return append_frame(out, msg::kNavSvinfo, {buf, len});
}

std::size_t UbxEncoder::nav_eoe(const Fix& fix, std::string& out) const {
  wire::NavEoe m{};
  m.iTOW = derive(fix).itow;
  return append_message(out, msg::kNavEoe, m);
}

std::size_t UbxEncoder::mon_hw(const Fix& fix, const EpochInfo& info, std::string& out) const {
  const FrontEnd f = front_end(fix, info);
  wire::MonHw m{};
  m.noisePerMS = f.noise_per_ms;
  m.agcCnt = f.agc_cnt;
  m.aStatus = f.ant_status;
  m.aPower = f.ant_power;
  m.jamInd = f.jam_ind;
  m.flags = static_cast<std::uint8_t>(0x01 | static_cast<unsigned>(f.jamming_state) << 2);  // rtcCalib
  m.usedMask = 0x0001FFFF;
  return append_message(out, msg::kMonHw, m);
}

std::size_t UbxEncoder::mon_rf(const Fix& fix, const EpochInfo& info, std::string& out) const {
  const FrontEnd f = front_end(fix, info);
  std::uint8_t buf[sizeof(wire::MonRfHeader) + 2 * sizeof(wire::MonRfBlock)];
  wire::MonRfHeader h{};
  // A NEO-M9N is L1 only; a ZED-F9P has an L1 and an L2/L5 front end (blockId 1).
  h.nBlocks = is_dual_band(config_.generation) ? 2 : 1;
  wire::MonRfBlock b{};
  b.flags = static_cast<std::uint8_t>(f.jamming_state);
  b.antStatus = f.ant_status;
  b.antPower = f.ant_power;
  b.noisePerMS = f.noise_per_ms;
  b.agcCnt = f.agc_cnt;
  b.jamInd = f.jam_ind;
  b.magI = b.magQ = f.mag_iq;  // ofsI, ofsQ 0: a balanced front end
  std::memcpy(buf, &h, sizeof h);
  for (std::uint8_t i = 0; i < h.nBlocks; ++i) {
    b.blockId = i;  // the second band shares the first's front end until the world models its own
    std::memcpy(buf + sizeof h + i * sizeof b, &b, sizeof b);
  }
  return append_frame(out, msg::kMonRf, {buf, sizeof h + h.nBlocks * sizeof b});
}

std::size_t UbxEncoder::sec_sig(const Fix& fix, const EpochInfo& info, std::string& out) const {
  const std::uint8_t spoof = spoof_det_state(fix);
  wire::SecSigV1 m{};
  m.version = 1;
  m.jamFlags = static_cast<std::uint8_t>((info.itfm.enabled ? 0x01 : 0x00) |
                                         static_cast<unsigned>(front_end(fix, info).jamming_state) << 1);
  // Spoofing detection is on unless the receiver reports it deactivated (0).
  m.spfFlags = static_cast<std::uint8_t>((spoof != 0 ? 0x01 : 0x00) | spoof << 1);
  return append_message(out, msg::kSecSig, m);
}

std::size_t UbxEncoder::mon_ver(std::string& out) const {
  return append_frame(out, msg::kMonVer,
                      {reinterpret_cast<const std::uint8_t*>(mon_ver_payload_.data()), mon_ver_payload_.size()});
}

std::size_t UbxEncoder::ack(MsgId acked, bool is_ack, std::string& out) {
  const wire::Ack m{acked.cls, acked.id};
  return append_message(out, is_ack ? msg::kAckAck : msg::kAckNak, m);
}

bool UbxEncoder::can_encode(MsgId id) noexcept {
  return id == msg::kNavPvt || id == msg::kNavPosllh || id == msg::kNavStatus || id == msg::kNavDop ||
         id == msg::kNavSol || id == msg::kNavVelned || id == msg::kNavTimegps || id == msg::kNavTimeutc ||
         id == msg::kNavSat || id == msg::kNavSvinfo || id == msg::kNavEoe || id == msg::kMonHw ||
         id == msg::kMonRf || id == msg::kSecSig || id == msg::kMonVer || id == msg::kNavSig ||
         id == msg::kNavTimeglo || id == msg::kNavTimegal || id == msg::kNavTimebds || id == msg::kMonHw2 ||
         id == msg::kNavHpposllh || id == msg::kNavHpposecef || id == msg::kNavRelposned;
}

std::size_t UbxEncoder::encode(MsgId id, const Fix& fix, const EpochInfo& info, std::string& out) const {
  if (!message_exists(id, config_.generation)) return 0;
  if (id == msg::kNavPvt) return nav_pvt_as(fix, info.reported_fix, out);
  if (id == msg::kNavPosllh) return nav_posllh(fix, out);
  if (id == msg::kNavStatus) return nav_status(fix, info, out);
  if (id == msg::kNavDop) return nav_dop(fix, out);
  if (id == msg::kNavSol) return nav_sol_as(fix, info.reported_fix, out);
  if (id == msg::kNavVelned) return nav_velned(fix, out);
  if (id == msg::kNavTimegps) return nav_timegps(fix, out);
  if (id == msg::kNavTimeutc) return nav_timeutc(fix, out);
  if (id == msg::kNavSat) return nav_sat(fix, out);
  if (id == msg::kNavSvinfo) return nav_svinfo(fix, out);
  if (id == msg::kNavEoe) return nav_eoe(fix, out);
  if (id == msg::kMonHw) return mon_hw(fix, info, out);
  if (id == msg::kMonRf) return mon_rf(fix, info, out);
  if (id == msg::kSecSig) return sec_sig(fix, info, out);
  if (id == msg::kMonVer) return mon_ver(out);
  if (id == msg::kNavSig) return nav_sig(fix, out);
  if (id == msg::kNavTimeglo) return nav_timeglo(fix, out);
  if (id == msg::kNavTimegal) return nav_timegal(fix, out);
  if (id == msg::kNavTimebds) return nav_timebds(fix, out);
  if (id == msg::kMonHw2) return mon_hw2(fix, info, out);
  if (id == msg::kNavHpposllh) return ubx::nav_hpposllh(fix, out);
  if (id == msg::kNavHpposecef) return ubx::nav_hpposecef(fix, out);
  if (id == msg::kNavRelposned) return ubx::nav_relposned(fix, out);
  return 0;
}

}  // namespace gnssemu::protocol::ubx
