// SPDX-License-Identifier: Apache-2.0
#pragma once
// Encoder of the binary truth record, version 1 (docs/truth-protocol.md
// §Binary record). Standard library only, so a simulator can copy this one
// header. Independent of the daemon's parser on purpose: a round-trip test
// and a pinned golden record (tests/unit/senders/test_truth_record.cpp)
// hold the two to the same bytes.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace gnssemu::senders {

/// Size of a version-1 record, bytes.
inline constexpr std::size_t kRecordBytes = 160;
/// Size of the NUL-padded vehicle id field, bytes.
inline constexpr std::size_t kRecordVehicleBytes = 64;
using RecordBytes = std::array<uint8_t, kRecordBytes>;

/// Frame of TruthRecord::position (flags bits 0-1).
enum class PositionFrame : uint8_t {
  kLla = 0,   ///< lat_deg [-90, 90], lon_deg [-180, 360], height_m above the ellipsoid
  kEcef = 1,  ///< WGS-84 ECEF x, y, z m
  kEnu = 2,   ///< east, north, up m from the daemon's configured [origin]
};

/// Frame of TruthRecord::vel_m_s (flags bits 2-3).
enum class VelocityFrame : uint8_t {
  kNone = 0,  ///< no velocity: the daemon differentiates positions
  kEnu = 1,   ///< east, north, up m/s, axes at the vehicle
  kEcef = 2,  ///< ECEF m/s
};

/// One truth sample as a sender knows it. The daemon validates the values;
/// this encoder only lays them out.
struct TruthRecord {
  std::string_view vehicle;                   ///< 1..64 printable bytes; must outlive encode_truth_record
  double sim_time_s = 0.0;                    ///< simulation clock, s, increasing per vehicle
  PositionFrame position_frame = PositionFrame::kLla;
  std::array<double, 3> position{};           ///< in position_frame's units (deg, deg, m or m, m, m)
  VelocityFrame velocity_frame = VelocityFrame::kNone;
  std::array<double, 3> vel_m_s{};            ///< m/s, |v| <= 1000; sent as zeros when kNone
  bool has_attitude = false;
  std::array<double, 3> attitude_rad{};       ///< roll [-pi, pi], pitch [-pi/2, pi/2], yaw [-pi, 2 pi] rad
  bool has_gps_time = false;
  uint16_t gps_week = 0;                      ///< continuous GPS week 0..9999
  double gps_tow_s = 0.0;                     ///< time of week, s, [0, 604800)
};

namespace detail {

inline void put_u16(RecordBytes& out, std::size_t off, uint16_t v) noexcept {
  out[off] = static_cast<uint8_t>(v & 0xFF);
  out[off + 1] = static_cast<uint8_t>(v >> 8);
}

// Little-endian IEEE 754 binary64, whatever the host's byte order.
inline void put_f64(RecordBytes& out, std::size_t off, double v) noexcept {
  const auto bits = std::bit_cast<uint64_t>(v);
  for (std::size_t i = 0; i < 8; ++i) out[off + i] = static_cast<uint8_t>(bits >> (8 * i));
}

inline void put_vec3(RecordBytes& out, std::size_t off, const std::array<double, 3>& v) noexcept {
  for (std::size_t i = 0; i < 3; ++i) put_f64(out, off + 8 * i, v[i]);
}

}  // namespace detail

/// Lays rec out as a version-1 record in out. Returns false, leaving out
/// unspecified, when rec.vehicle is empty, longer than 64 bytes or holds a
/// NUL (it would not survive the NUL padding).
inline bool encode_truth_record(const TruthRecord& rec, RecordBytes& out) noexcept {
  if (rec.vehicle.empty() || rec.vehicle.size() > kRecordVehicleBytes ||
      rec.vehicle.find('\0') != std::string_view::npos) {
    return false;
  }
  out.fill(0);
  out[0] = 0xF7;  // never a UTF-8 byte, so never the start of a JSON text
  out[1] = 'G';
  out[2] = 'T';
  out[3] = 'R';
  out[4] = 1;  // version
  out[5] = static_cast<uint8_t>(static_cast<uint8_t>(rec.position_frame) |
                                (static_cast<uint8_t>(rec.velocity_frame) << 2) |
                                (rec.has_attitude ? 0x10 : 0x00) | (rec.has_gps_time ? 0x20 : 0x00));
  if (rec.has_gps_time) detail::put_u16(out, 6, rec.gps_week);
  for (std::size_t i = 0; i < rec.vehicle.size(); ++i) out[8 + i] = static_cast<uint8_t>(rec.vehicle[i]);
  detail::put_f64(out, 72, rec.sim_time_s);
  if (rec.has_gps_time) detail::put_f64(out, 80, rec.gps_tow_s);
  detail::put_vec3(out, 88, rec.position);
  if (rec.velocity_frame != VelocityFrame::kNone) detail::put_vec3(out, 112, rec.vel_m_s);
  if (rec.has_attitude) detail::put_vec3(out, 136, rec.attitude_rad);
  return true;
}

}  // namespace gnssemu::senders
