// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/device/ubx_rtcm_input.hpp"

#include <array>

#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/protocol/rtcm/rtcm_ublox.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"

namespace gnssemu::protocol::ubx {

namespace {

void put_u2(std::uint8_t* p, int v) noexcept {
  p[0] = static_cast<std::uint8_t>(v & 0xFF);
  p[1] = static_cast<std::uint8_t>((v >> 8) & 0xFF);
}

}  // namespace

std::size_t rxm_rtcm(const rtcm::DecodeResult& r, bool crc_failed, std::string& out) {
  std::array<std::uint8_t, kRxmRtcmBytes> p{};
  p[0] = 0x02;  // version
  // msgUsed: 0 unknown (a CRC failure), 1 not used, 2 used.
  const unsigned used = crc_failed ? 0u : r.used ? 2u : 1u;
  p[1] = static_cast<std::uint8_t>((crc_failed ? 1u : 0u) | used << 1);
  put_u2(&p[2], r.subtype);
  put_u2(&p[4], r.station_id);
  put_u2(&p[6], r.message);
  return append_frame(out, msg::kRxmRtcm, p);
}

void RtcmInput::learn_glonass_channels(const receiver::RawEpoch& own) noexcept {
  for (int i = 0; i < own.num_meas && i < receiver::kMaxRawMeasurements; ++i) {
    const receiver::RawMeasurement& m = own.meas[static_cast<std::size_t>(i)];
    if (m.sat.system == GnssSystem::kGlonass) decoder_.set_glonass_channel(m.sat.number, m.glonass_channel);
  }
}

rtcm::DecodeResult RtcmInput::take(std::span<const std::uint8_t> payload, bool crc_ok) noexcept {
  if (outage_) {
    ++stats_.outage;
    return {};
  }
  if (!crc_ok) {
    ++stats_.crc_failed;
    rtcm::DecodeResult r;
    r.message = rtcm::message_number(payload);
    if (r.message == rtcm::kUbloxMessage) r.subtype = std::max(0, rtcm::ublox_subtype(payload));
    return r;
  }
  ++stats_.frames;
  if (stale_) ++stats_.stale;
  const rtcm::DecodeResult r = decoder_.decode(payload, now_, stale_ ? stale_sink_ : corrections_, leap_seconds_);
  if (r.used) ++stats_.used;
  return r;
}

}  // namespace gnssemu::protocol::ubx
