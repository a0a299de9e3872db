// SPDX-License-Identifier: Apache-2.0
#pragma once
// u-blox proprietary NMEA input commands (UBX-13003221 §31.3): PUBX,41 sets
// a port's protocols and baud, PUBX,40 sets NMEA message rates per port.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gnssemu::protocol::ubx {

/// $PUBX,41,portId,inProto,outProto,baudrate,autobauding*cs
struct Pubx41 {
  std::uint8_t port_id = 0;
  std::uint16_t in_proto_mask = 0;   ///< hex field, e.g. 0007
  std::uint16_t out_proto_mask = 0;  ///< hex field, e.g. 0003
  std::uint32_t baud_bps = 0;
  bool autobauding = false;
};

/// $PUBX,40,msgId,rddc,rus1,rus2,rusb,rspi,reserved*cs (msgId e.g. "GGA")
struct Pubx40 {
  std::uint8_t nmea_id = 0;  ///< CFG-MSG id in class 0xF0
  std::array<std::uint8_t, 6> rates{};  ///< DDC, UART1, UART2, USB, SPI, reserved
};

/// sentence as StreamDecoder delivers it ("$PUBX,...*hh", checksum already
/// verified). nullopt when it is not that command or a field is malformed
/// (port > 5, mask not hex, baud not a u-blox rate, unknown sentence).
std::optional<Pubx41> parse_pubx41(std::string_view sentence) noexcept;
std::optional<Pubx40> parse_pubx40(std::string_view sentence) noexcept;

/// Class 0xF0 id of a standard sentence formatter ("GGA" -> 0x00), or -1.
int nmea_msg_id(std::string_view formatter) noexcept;

}  // namespace gnssemu::protocol::ubx
