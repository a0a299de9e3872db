// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/rtcm/rtcm_decoder.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/protocol/rtcm/rtcm_ublox.hpp"

namespace gnssemu::protocol::rtcm {

namespace {

/// Bits of 1005 and 1006 (rtk-raw.md §2.2), 1230's fixed part (§2.6).
constexpr std::size_t k1005Bits = 152, k1006Bits = 168, k1230HeadBits = 32;

/// Messages a rover knows but takes nothing from here: MSM1-3, legacy
/// observations 1001-1004/1009-1012, antenna and receiver descriptors
/// 1007/1008/1033, ephemerides 1019/1020/1041-1046, text 1029, 1013.
bool known_not_used(int n) noexcept {
  if (n >= 1071 && n <= 1137 && n % 10 >= 1 && n % 10 <= 3) return true;
  if ((n >= 1001 && n <= 1004) || (n >= 1009 && n <= 1012)) return true;
  switch (n) {
    case 1007: case 1008: case 1013: case 1019: case 1020: case 1029: case 1033:
    case 1041: case 1042: case 1043: case 1044: case 1045: case 1046:
      return true;
    default:
      return false;
  }
}

bool is_msm(int n) noexcept {
  const int sys = n / 10;
  return sys >= 107 && sys <= 112 && n % 10 >= 4 && n % 10 <= 7;
}

}  // namespace

void Decoder::set_glonass_channel(int slot, int channel) noexcept {
  if (slot < 1 || slot >= static_cast<int>(glonass_fcn_.size()) || channel < -7 || channel > 6) return;
  glonass_fcn_[static_cast<std::size_t>(slot)] = static_cast<std::int8_t>(channel);
}

DecodeResult Decoder::decode(std::span<const std::uint8_t> payload, time::GpsTime now, receiver::Corrections& out,
                             int leap_seconds) noexcept {
  out_ = &out;
  DecodeResult res;
  res.message = message_number(payload);
  if (payload.size() >= 3) {
    BitReader r(payload);
    r.u(12);
    res.station_id = static_cast<int>(r.u(12));
  }
  const int n = res.message;
  if (is_msm(n)) {
    res.used = decode_msm(payload, n, now, leap_seconds, res);
  } else if (n == 1005 || n == 1006) {
    res.used = decode_station(payload, n, now, res);
  } else if (n == 1230) {
    res.used = decode_biases(payload, res);
  } else if (n == kUbloxMessage) {
    res.station_id = 0;
    res.used = decode_ublox(payload, now, res);
  } else if (known_not_used(n)) {
    ++stats_.not_used;
  } else {
    ++stats_.unknown_messages;
    res.station_id = 0;
  }
  return res;
}

bool Decoder::decode_station(std::span<const std::uint8_t> payload, int number, time::GpsTime now,
                             DecodeResult& res) noexcept {
  const bool with_height = number == 1006;
  if (payload.size() * 8 < (with_height ? k1006Bits : k1005Bits)) {
    ++stats_.truncated;
    res.station_id = 0;
    return false;
  }
  BitReader r(payload);
  r.u(12);
  receiver::ReferenceStation& st = out_->station;
  st.station_id = static_cast<int>(r.u(12));
  r.u(6 + 4);  // DF021 ITRF year, DF022-024 systems, DF141
  st.arp_ecef_m.x = static_cast<double>(r.s(38)) * 1e-4;
  r.u(2);  // DF142, reserved
  st.arp_ecef_m.y = static_cast<double>(r.s(38)) * 1e-4;
  r.u(2);  // DF364
  st.arp_ecef_m.z = static_cast<double>(r.s(38)) * 1e-4;
  st.antenna_height_m = with_height ? static_cast<double>(r.u(16)) * 1e-4 : 0.0;
  st.position_valid = true;
  st.moving = false;
  st.position_time = now;
  ++out_->revision;
  ++stats_.station;
  return true;
}

bool Decoder::decode_biases(std::span<const std::uint8_t> payload, DecodeResult& res) noexcept {
  BitReader r(payload);
  r.u(24);
  const bool aligned = r.u(1) != 0;  // DF421
  r.u(3);                            // reserved
  const auto mask = static_cast<unsigned>(r.u(4));
  const std::size_t need = k1230HeadBits + 16u * static_cast<std::size_t>(std::popcount(mask));
  if (payload.size() * 8 < need) {
    ++stats_.truncated;
    res.station_id = 0;
    return false;
  }
  for (std::size_t i = 0; i < out_->glonass_cpb_m.size(); ++i) {
    if (!((mask << i) & 8u)) {
      out_->glonass_cpb_m[i] = 0.0;
      continue;
    }
    const std::int64_t v = r.s(16);
    out_->glonass_cpb_m[i] = v == -32768 ? 0.0 : static_cast<double>(v) * 0.02;
  }
  out_->glonass_cpb_aligned = aligned;
  // Aligned phase ranges need no bias; unaligned ones without biases cannot be aligned.
  out_->glonass_cpb_valid = aligned || mask != 0;
  ++stats_.glonass_biases;
  return true;
}

bool Decoder::decode_ublox(std::span<const std::uint8_t> payload, time::GpsTime now, DecodeResult& res) noexcept {
  const int sub = ublox_subtype(payload);
  if (sub < 0) {
    ++stats_.truncated;
    return false;
  }
  res.subtype = sub;
  ++stats_.ublox;
  if (sub > 1) return false;
  ++stats_.ublox_subtype[sub];
  if (sub == 1) return true;
  // A moving base: the rover solves the baseline. Its position only where
  // the layout is ours (a real F9P's is not public).
  receiver::ReferenceStation& st = out_->station;
  st.moving = true;
  if (const auto pvt = decode_reference_pvt(payload)) {
    res.station_id = pvt->station_id;
    st.station_id = pvt->station_id;
    st.arp_ecef_m = pvt->arp_ecef_m;
    st.antenna_height_m = 0.0;
    st.position_valid = true;
    st.position_time = now;
  }
  ++out_->revision;
  return true;
}

void Decoder::complete(time::GpsTime now) noexcept {
  auto& m = pending_.meas;
  std::sort(m.begin(), m.begin() + pending_.num_meas,
            [](const receiver::RawMeasurement& a, const receiver::RawMeasurement& b) {
              const int ia = a.sat.index(), ib = b.sat.index();
              return ia != ib ? ia < ib : signal_info(a.signal).band < signal_info(b.signal).band;
            });
  out_->obs = pending_;
  out_->obs_valid = true;
  out_->obs_received = now;
  out_->obs_station_id = pending_station_;
  ++out_->revision;
  ++stats_.epochs;
  pending_valid_ = false;
}

}  // namespace gnssemu::protocol::rtcm
