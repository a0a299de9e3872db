// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/rtcm/rtcm_ublox.hpp"

#include <cmath>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"

namespace gnssemu::protocol::rtcm {

int ublox_subtype(std::span<const std::uint8_t> payload) noexcept {
  if (payload.size() < 3) return -1;
  BitReader r(payload);
  if (r.u(12) != kUbloxMessage) return -1;
  return static_cast<int>(r.u(12));
}

void append_reference_pvt(const ReferencePvt& pvt, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  w.u(12, kUbloxMessage);
  w.u(12, 0);
  w.u(12, static_cast<std::uint64_t>(pvt.station_id));
  w.u(30, pvt.tow_ms);
  for (const double v : {pvt.arp_ecef_m.x, pvt.arp_ecef_m.y, pvt.arp_ecef_m.z})
    w.s(38, static_cast<std::int64_t>(std::floor(v / 1e-4 + 0.5)));
  append_frame(std::span<const std::uint8_t>(buf.data(), w.bytes()), out);
}

std::optional<ReferencePvt> decode_reference_pvt(std::span<const std::uint8_t> payload) noexcept {
  if (payload.size() != kReferencePvtBytes || ublox_subtype(payload) != 0) return std::nullopt;
  BitReader r(payload);
  r.u(24);
  ReferencePvt p;
  p.station_id = static_cast<int>(r.u(12));
  p.tow_ms = static_cast<std::uint32_t>(r.u(30));
  p.arp_ecef_m.x = static_cast<double>(r.s(38)) * 1e-4;
  p.arp_ecef_m.y = static_cast<double>(r.s(38)) * 1e-4;
  p.arp_ecef_m.z = static_cast<double>(r.s(38)) * 1e-4;
  if (p.tow_ms >= 604800000u) return std::nullopt;
  return p;
}

}  // namespace gnssemu::protocol::rtcm
