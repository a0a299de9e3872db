// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/device/ubx_rtcm_output.hpp"

#include <cmath>

#include "core/protocol/rtcm/rtcm_station.hpp"
#include "core/protocol/rtcm/rtcm_ublox.hpp"

namespace gnssemu::protocol::ubx {
namespace {

/// Largest epoch: MSM7 of four systems on two bands (≈ 1.1 KB each with 16
/// satellites) plus the small messages, rounded up.
constexpr std::size_t kMaxBytes = 8192;

constexpr std::array<RtcmOutput::Kind, RtcmOutput::kKinds> kKindTable{{
    {MsgId{kRtcmMsgClass, 0xFE}, 4072, "RTCM-4072.0"},
    {MsgId{kRtcmMsgClass, 0x05}, 1005, "RTCM-1005"},
    {MsgId{kRtcmMsgClass, 0x4A}, 1074, "RTCM-1074"},
    {MsgId{kRtcmMsgClass, 0x4D}, 1077, "RTCM-1077"},
    {MsgId{kRtcmMsgClass, 0x54}, 1084, "RTCM-1084"},
    {MsgId{kRtcmMsgClass, 0x57}, 1087, "RTCM-1087"},
    {MsgId{kRtcmMsgClass, 0x5E}, 1094, "RTCM-1094"},
    {MsgId{kRtcmMsgClass, 0x61}, 1097, "RTCM-1097"},
    {MsgId{kRtcmMsgClass, 0x7C}, 1124, "RTCM-1124"},
    {MsgId{kRtcmMsgClass, 0x7F}, 1127, "RTCM-1127"},
    {MsgId{kRtcmMsgClass, 0xE6}, 1230, "RTCM-1230"},
}};

GnssSystem msm_system(int number) noexcept {
  switch (number / 10) {
    case 108: return GnssSystem::kGlonass;
    case 109: return GnssSystem::kGalileo;
    case 112: return GnssSystem::kBeiDou;
    default: return GnssSystem::kGps;
  }
}

}  // namespace

const std::array<RtcmOutput::Kind, RtcmOutput::kKinds>& RtcmOutput::kinds() noexcept { return kKindTable; }

void RtcmOutput::start() {
  if (!state_) {
    state_ = std::make_unique<State>();
    state_->buf.reserve(kMaxBytes);
  }
  state_->buf.clear();
}

void RtcmOutput::encode_kind(std::size_t kind, const receiver::Fix& fix, const receiver::RawEpoch& raw) noexcept {
  std::string& buf = state_->buf;
  const std::size_t begin = buf.size();
  const int number = kKindTable[kind].number;
  if (number == 4072) {
    const double tow_ms = std::round(raw.t_rx.tow_s() * 1e3);
    rtcm::append_reference_pvt({0, static_cast<std::uint32_t>(tow_ms) % 604800000u, fix.pos_m}, buf);
  } else if (number == 1005) {
    rtcm::StationInfo st;
    st.arp_ecef_m = fix.pos_m;
    st.glonass = st.galileo = true;
    rtcm::append_station(st, false, buf);
  } else if (number == 1230) {
    // As a u-blox F9 base: phase ranges aligned, no bias fields (docs/base-station.md).
    rtcm::append_glonass_biases(0, true, {}, buf);
  } else {
    rtcm::MsmEncoder& enc = number % 10 == 7 ? state_->msm7 : state_->msm4;
    enc.append_epoch(raw, SystemSet::only(msm_system(number)), buf);
  }
  if (buf.size() > begin) frames_[count_++] = {kind, begin, buf.size()};
}

}  // namespace gnssemu::protocol::ubx
