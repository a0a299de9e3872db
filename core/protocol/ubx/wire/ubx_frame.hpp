// SPDX-License-Identifier: Apache-2.0
#pragma once
// UBX frame: sync B5 62, class, id, U2 length (LE), payload, 8-bit Fletcher
// checksum over class..payload (u-blox M8 Receiver Description UBX-13003221,
// §32.2-32.4; shared/reference/ubx.md §1). Output goes into std::string so
// that NMEA and UBX bytes share one transmit buffer per port.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

namespace gnssemu::protocol::ubx {

static_assert(std::endian::native == std::endian::little,
              "wire structs are memcpy'd: UBX is little-endian");

inline constexpr std::uint8_t kSync1 = 0xB5;
inline constexpr std::uint8_t kSync2 = 0x62;
inline constexpr std::size_t kHeaderBytes = 6;         ///< sync(2) class id length(2)
inline constexpr std::size_t kFrameOverheadBytes = 8;  ///< header + CK_A CK_B
/// Largest payload the decoder accepts. An M8's largest host input is far
/// smaller (CFG-USB 108 bytes, MGA-DBD records); 1 KiB bounds memory and still
/// passes CFG-VALSET with 64 keys (772 bytes) so it can be NAKed properly.
inline constexpr std::size_t kMaxPayloadBytes = 1024;

/// Message class and id.
struct MsgId {
  std::uint8_t cls = 0;
  std::uint8_t id = 0;
  constexpr bool operator==(const MsgId&) const = default;
  /// cls << 8 | id, for tables and logging.
  constexpr std::uint16_t key() const noexcept { return static_cast<std::uint16_t>(cls << 8 | id); }
};

namespace cls {
inline constexpr std::uint8_t kNav = 0x01, kRxm = 0x02, kInf = 0x04, kAck = 0x05, kCfg = 0x06,
                              kUpd = 0x09, kMon = 0x0A, kAid = 0x0B, kTim = 0x0D, kMga = 0x13,
                              kLog = 0x21, kSec = 0x27, kNmeaStd = 0xF0, kNmeaPubx = 0xF1;
}  // namespace cls

/// Message ids used here (ubx.md §2; M8 spec §32.10 ff.). NMEA ids are the
/// class 0xF0/0xF1 ids CFG-MSG uses to rate NMEA sentences.
namespace msg {
inline constexpr MsgId kNavPosllh{0x01, 0x02}, kNavStatus{0x01, 0x03}, kNavDop{0x01, 0x04},
    kNavSol{0x01, 0x06}, kNavPvt{0x01, 0x07}, kNavVelned{0x01, 0x12}, kNavTimegps{0x01, 0x20},
    kNavTimeutc{0x01, 0x21}, kNavTimeglo{0x01, 0x23}, kNavTimebds{0x01, 0x24}, kNavTimegal{0x01, 0x25},
    kNavSvinfo{0x01, 0x30}, kNavSat{0x01, 0x35}, kNavSig{0x01, 0x43}, kNavEoe{0x01, 0x61};
inline constexpr MsgId kRxmSfrbx{0x02, 0x13}, kRxmRawx{0x02, 0x15}, kRxmRtcm{0x02, 0x32};
inline constexpr MsgId kAckNak{0x05, 0x00}, kAckAck{0x05, 0x01};
inline constexpr MsgId kCfgPrt{0x06, 0x00}, kCfgMsg{0x06, 0x01}, kCfgInf{0x06, 0x02},
    kCfgRst{0x06, 0x04}, kCfgDat{0x06, 0x06}, kCfgRate{0x06, 0x08}, kCfgCfg{0x06, 0x09},
    kCfgRxm{0x06, 0x11}, kCfgAnt{0x06, 0x13}, kCfgSbas{0x06, 0x16}, kCfgNmea{0x06, 0x17},
    kCfgUsb{0x06, 0x1B}, kCfgOdo{0x06, 0x1E}, kCfgNavx5{0x06, 0x23}, kCfgNav5{0x06, 0x24},
    kCfgTp5{0x06, 0x31}, kCfgRinv{0x06, 0x34}, kCfgItfm{0x06, 0x39}, kCfgPm2{0x06, 0x3B},
    kCfgGnss{0x06, 0x3E}, kCfgLogfilter{0x06, 0x47}, kCfgPwr{0x06, 0x57}, kCfgGeofence{0x06, 0x69},
    kCfgPms{0x06, 0x86}, kCfgValset{0x06, 0x8A},
    kCfgValget{0x06, 0x8B}, kCfgValdel{0x06, 0x8C};
inline constexpr MsgId kMonVer{0x0A, 0x04}, kMonHw{0x0A, 0x09}, kMonHw2{0x0A, 0x0B}, kMonGnss{0x0A, 0x28},
    kMonRf{0x0A, 0x38};
/// M9 and later (ubx_generation.hpp).
inline constexpr MsgId kSecSig{0x27, 0x09};
/// ZED-F9P high-precision firmware (ubx_hpg.hpp).
inline constexpr MsgId kNavHpposecef{0x01, 0x13}, kNavHpposllh{0x01, 0x14}, kNavRelposned{0x01, 0x3C},
    kRxmCor{0x02, 0x34}, kCfgDgnss{0x06, 0x70}, kCfgTmode3{0x06, 0x71};
inline constexpr MsgId kNmeaGga{0xF0, 0x00}, kNmeaGll{0xF0, 0x01}, kNmeaGsa{0xF0, 0x02},
    kNmeaGsv{0xF0, 0x03}, kNmeaRmc{0xF0, 0x04}, kNmeaVtg{0xF0, 0x05}, kNmeaGst{0xF0, 0x07},
    kNmeaZda{0xF0, 0x08};
}  // namespace msg

/// A decoded frame: payload points into the decoder's buffer (valid until the
/// next feed) or into caller memory.
struct FrameView {
  MsgId id;
  std::span<const std::uint8_t> payload;
};

struct Checksum {
  std::uint8_t ck_a = 0;
  std::uint8_t ck_b = 0;
  constexpr bool operator==(const Checksum&) const = default;
};

/// 8-bit Fletcher over bytes (class, id, length, payload of a frame).
constexpr Checksum fletcher8(std::span<const std::uint8_t> bytes) noexcept {
  std::uint8_t a = 0, b = 0;
  for (std::uint8_t v : bytes) {
    a = static_cast<std::uint8_t>(a + v);
    b = static_cast<std::uint8_t>(b + a);
  }
  return {a, b};
}

/// Append one complete frame (sync .. checksum) to out. Returns bytes appended
/// (payload.size() + 8). Allocates only if out lacks capacity. payload.size()
/// must be <= 65535 (callers pass fixed wire structs or bounded buffers).
std::size_t append_frame(std::string& out, MsgId id, std::span<const std::uint8_t> payload);

/// Append a frame whose payload is a packed wire struct (ubx_messages.hpp).
template <class Wire>
std::size_t append_message(std::string& out, MsgId id, const Wire& wire) {
  return append_frame(out, id, {reinterpret_cast<const std::uint8_t*>(&wire), sizeof(Wire)});
}

/// The n (<= 8) little-endian bytes of bytes at offset as an unsigned value
/// (UBX is little-endian throughout); the caller checks offset + n <= size.
constexpr std::uint64_t load_le(std::span<const std::uint8_t> bytes, std::size_t offset, std::size_t n) noexcept {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) v |= std::uint64_t{bytes[offset + i]} << (8 * i);
  return v;
}

/// Write the low n (<= 8) bytes of value little-endian at offset; the caller
/// checks offset + n <= size.
constexpr void store_le(std::span<std::uint8_t> bytes, std::size_t offset, std::size_t n,
                        std::uint64_t value) noexcept {
  for (std::size_t i = 0; i < n; ++i) bytes[offset + i] = static_cast<std::uint8_t>(value >> (8 * i));
}

/// Copy a wire struct out of a payload. False when the payload is shorter.
template <class Wire>
bool read_wire(std::span<const std::uint8_t> payload, Wire& wire, std::size_t offset = 0) noexcept {
  if (payload.size() < offset + sizeof(Wire)) return false;
  std::memcpy(&wire, payload.data() + offset, sizeof(Wire));
  return true;
}

}  // namespace gnssemu::protocol::ubx
