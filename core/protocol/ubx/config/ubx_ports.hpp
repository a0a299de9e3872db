// SPDX-License-Identifier: Apache-2.0
#pragma once
// The ports of a u-blox M8 as UBX addresses them: port ids (CFG-PRT portID,
// CFG-MSG rate columns), protocol mask bits and the UART rates the
// firmware accepts (UBX-13003221 CFG-PRT, $PUBX,41).
#include <array>
#include <cstddef>
#include <cstdint>

namespace gnssemu::protocol::ubx {

/// Ports in CFG-MSG rate order (M8 spec CFG-MSG, CFG-PRT portID).
inline constexpr std::size_t kNumPorts = 6;
inline constexpr std::uint8_t kPortDdc = 0, kPortUart1 = 1, kPortUart2 = 2, kPortUsb = 3, kPortSpi = 4;

constexpr bool is_uart(std::uint8_t port_id) noexcept { return port_id == kPortUart1 || port_id == kPortUart2; }

/// inProtoMask / outProtoMask bits.
namespace proto {
inline constexpr std::uint16_t kUbx = 0x0001, kNmea = 0x0002, kRtcm2 = 0x0004, kRtcm3 = 0x0020;
}

/// UART line rates a u-blox accepts (CFG-PRT baudRate, $PUBX,41), bit/s, ascending.
inline constexpr std::array<std::uint32_t, 9> kUartBauds{4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600};

constexpr bool is_ubx_baud(std::uint32_t baud_bps) noexcept {
  for (const std::uint32_t b : kUartBauds) {
    if (b == baud_bps) return true;
  }
  return false;
}

/// CFG-PRT UART mode 8N1 (UBX-13003221 CFG-PRT): charLen b6-7 (3 = 8 bit),
/// parity b9-11 (10x = none), nStopBits b12-13 (0 = 1 stop bit).
constexpr bool is_8n1(std::uint32_t mode) noexcept {
  return (mode >> 6 & 0x3U) == 0x3U && (mode >> 9 & 0x6U) == 0x4U && (mode >> 12 & 0x3U) == 0U;
}

}  // namespace gnssemu::protocol::ubx
