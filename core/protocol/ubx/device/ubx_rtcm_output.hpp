// SPDX-License-Identifier: Apache-2.0
#pragma once
// The ZED-F9P as a (moving) base: the RTCM 3 messages its CFG-MSGOUT-RTCM_3X
// keys (CFG-MSG class 0xF5) turn on, from its own epoch: 4072.0 with its
// position (gnssemu's layout, rtcm_ublox.hpp), MSM7 or MSM4 of one system
// each (1077/1074 GPS, 1087/1084 GLONASS, 1097/1094 Galileo, 1127/1124
// BeiDou) from the raw measurements, 1005 with its position and 1230 with
// zero biases (the world has none). 4072.1 is not sent: u-blox does not
// publish its layout. ArduPilot's moving-baseline base list (GPS_TYPE 17)
// asks for 4072.0/4072.1/1077/1087/1097/1127/1230 (docs/ubx.md
// "ArduPilot F9P").
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "core/protocol/rtcm/rtcm_msm.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/raw_measurements.hpp"

namespace gnssemu::protocol::ubx {

/// CFG-MSG class of the RTCM 3 output messages (id: the number's low byte).
inline constexpr std::uint8_t kRtcmMsgClass = 0xF5;

class RtcmOutput {
public:
  /// The messages this output knows, in send order.
  struct Kind {
    MsgId id;
    int number;        ///< RTCM message number (4072: sub-type 0)
    const char* label; ///< "RTCM-1077" (static storage)
  };
  static constexpr std::size_t kKinds = 11;
  static const std::array<Kind, kKinds>& kinds() noexcept;

  /// Encodes the epoch's frames of the kinds wanted(id) says some port
  /// sends; nothing without a valid time, position or raw epoch. The
  /// encoders and buffer (≈ 40 KB) are made on the first epoch that wants
  /// one (most receivers never do); no allocation after that.
  template <class Wanted>
  void encode(const receiver::Fix& fix, const receiver::RawEpoch* raw, Wanted wanted) {
    count_ = 0;
    if (raw == nullptr || !raw->time_valid || !fix.time_valid || fix.type == receiver::FixType::kNone) return;
    bool started = false;
    for (std::size_t i = 0; i < kKinds; ++i) {
      if (!wanted(kinds()[i].id)) continue;
      if (!started) start();
      started = true;
      encode_kind(i, fix, *raw);
    }
  }

  /// Frames of the last encode(): id, label and bytes.
  std::size_t size() const noexcept { return count_; }
  MsgId id(std::size_t i) const noexcept { return kinds()[frames_[i].kind].id; }
  const char* label(std::size_t i) const noexcept { return kinds()[frames_[i].kind].label; }
  std::string_view bytes(std::size_t i) const noexcept {
    return std::string_view(state_->buf).substr(frames_[i].begin, frames_[i].end - frames_[i].begin);
  }

private:
  /// Makes the state on first use and empties the buffer.
  void start();
  void encode_kind(std::size_t kind, const receiver::Fix& fix, const receiver::RawEpoch& raw) noexcept;
  struct Frame {
    std::size_t kind = 0, begin = 0, end = 0;
  };
  struct State {
    rtcm::MsmEncoder msm7{0, rtcm::MsmKind::kMsm7};
    rtcm::MsmEncoder msm4{0, rtcm::MsmKind::kMsm4};
    std::string buf;
  };
  std::unique_ptr<State> state_;
  std::array<Frame, kKinds> frames_{};  ///< one per kind (an MSM split by its cell mask stays one)
  std::size_t count_ = 0;
};

}  // namespace gnssemu::protocol::ubx
