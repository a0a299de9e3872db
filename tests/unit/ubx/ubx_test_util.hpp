// SPDX-License-Identifier: Apache-2.0
#pragma once
// Test helpers for UBX: a complete sample Fix, frame splitting, hex.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/handlers/ubx_handlers.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx::test {

/// Device column of the second output's UART1 (each output has kNumPorts).
inline constexpr std::size_t kUart1OfOutput1 = kNumPorts;

/// nmea::test::sample_fix_3d() (Zurich, 10 satellites, 9 used, 13.4 m/s on
/// 87.3 deg) completed with what UBX also reads: ENU/ECEF velocity, ECEF
/// position, accuracies, residuals, clock.
receiver::Fix sample_fix();
/// Fill vel_enu_m_s from speed/course/climb and pos_m/vel_m_s from lla
/// (closed-form WGS-84) when a JSON-made Fix lacks them.
void complete_fix(receiver::Fix& f);

struct Frame {
  MsgId id;
  std::vector<std::uint8_t> payload;
};
/// Every UBX frame of a byte stream (via StreamDecoder); NMEA lines into nmea if given.
std::vector<Frame> split_frames(std::string_view stream, std::vector<std::string>* nmea = nullptr);

/// "B5 62 0A 04" -> bytes (spaces optional).
std::string from_hex(std::string_view hex);
std::string to_hex(std::string_view bytes);
/// Complete frame bytes.
std::string frame_bytes(MsgId id, const std::vector<std::uint8_t>& payload);

/// Append the UBX messages d sends at at this epoch, in their own order (no
/// NMEA), to out; returns the bytes appended.
std::size_t ubx_epoch(const Device& d, Link at, std::string& out);

/// A chip's configurations and what a handler needs, to call one handler
/// alone: call(handler, frame) as a host on UART1 of output uart (or on port).
struct HandlerRig {
  explicit HandlerRig(std::size_t uarts = 2)
      : defaults(DeviceConfig::factory_defaults(uarts)), saved(defaults), current(defaults), transaction(defaults) {}
  DeviceConfig defaults, saved, current;
  ValTransaction transaction;
  UbxEncoder encoder;
  receiver::Fix fix = sample_fix();
  EpochInfo info;
  std::string out;
  std::optional<Reset> reset;  ///< what the last call's CFG-RST asked for
  Reply call(Handler handler, MsgId id, const std::vector<std::uint8_t>& payload, std::size_t uart = 0,
             std::uint8_t port = kPortUart1);
  /// The frames the last call appended.
  std::vector<Frame> replies() const;
};

/// Little-endian readers for asserting payload fields by offset.
std::uint16_t u2(const std::vector<std::uint8_t>& p, std::size_t off);
std::uint32_t u4(const std::vector<std::uint8_t>& p, std::size_t off);
std::int32_t i4(const std::vector<std::uint8_t>& p, std::size_t off);

}  // namespace gnssemu::protocol::ubx::test
