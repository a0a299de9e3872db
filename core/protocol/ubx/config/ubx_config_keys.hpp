// SPDX-License-Identifier: Apache-2.0
#pragma once
// The configuration keys of the M9's CFG-VALSET/VALGET/VALDEL interface, one
// table: each key's id, u-blox name and where its value lives in a
// DeviceConfig. Keys with a legacy counterpart read and write the same state
// CFG-PRT, CFG-MSG, CFG-RATE, CFG-NAV5, CFG-ODO, CFG-ITFM, CFG-SBAS, CFG-GNSS
// and CFG-NMEA change, so both interfaces see one configuration; the others
// are plain values (stored, returned, not acted on). Key ids and layout:
// u-blox ZED-F9P Interface Description UBX-18010854 §6 (key id bits: 28-30
// size, 16-23 group, 0-11 item), pyubx2 ubxtypes_configdb.py, PX4-GPSDrivers
// ubx.h; docs/ubx.md §Configuration interface lists every key.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "core/protocol/ubx/config/ubx_device_config.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"

namespace gnssemu::protocol::ubx {

/// Where a key's value lives.
enum class KeyStore : std::uint8_t {
  kPlain,        ///< DeviceConfig::plain_value(slot)
  kInProto,      ///< inProtoMask bit `shift` of port `port`
  kOutProto,     ///< outProtoMask bit `shift` of port `port`
  kUartBaud,     ///< baud of UART `port`, a CFG-PRT baud
  kUartFraming,  ///< stop bits / data bits / parity of UART `port`: only 8N1 (offset: 2, 3, 4 = the key's item)
  kMsgOut,       ///< CFG-MSG rate of `msg` on port `port`
  kRate,         ///< bits of CFG-RATE at byte `offset`
  kNav5,         ///< bits of CFG-NAV5 at byte `offset`
  kBlock,        ///< bits of the stored CFG block `msg` (index `port`) at byte `offset`
  kGnss,         ///< bit `shift` of the CFG-GNSS flags of gnssId `offset`
  kNmeaProtver,  ///< CFG-NMEA nmeaVersion (0x41) as the key's decimal (41)
};

struct ConfigKey {
  std::uint32_t id = 0;
  std::string_view name;         ///< "CFG-RATE-MEAS"; MSGOUT keys without the port ("CFG-MSGOUT-UBX_NAV_PVT")
  KeyStore store = KeyStore::kPlain;
  std::uint8_t port = 0;         ///< u-blox port id (< kNumPorts) for port keys; kBlock: the block's index (CFG-INF protocolID)
  MsgId msg{};                   ///< kMsgOut: the message; kBlock: the CFG block
  std::uint8_t offset = 0;       ///< byte offset of the field (kGnss: gnssId; kUartFraming: item)
  std::uint8_t shift = 0;        ///< first bit of the value in the little-endian field
  std::uint8_t width = 8;        ///< bits of the value
  bool is_signed = false;        ///< I1/I4: min/max compare as signed
  std::int64_t min = 0;          ///< smallest value accepted (VALSET to RAM)
  std::int64_t max = 1;          ///< largest value accepted
  std::uint64_t allowed = 0;     ///< non-zero: value must be < 64 with its bit set (enums with gaps)
  std::uint8_t slot = 0;         ///< kPlain: index into DeviceConfig plain values
  std::uint64_t plain_default = 0;  ///< kPlain: factory value
  /// Generations whose firmware knows the key: a VALSET, VALGET or VALDEL
  /// naming it elsewhere is NAKed whole (PX4-GPSDrivers relies on an M9
  /// NAKing CFG-NAVHPG-DGNSSMODE).
  GenerationSet generations = kGen9;

  constexpr bool exists_on(Generation g) const noexcept { return (generations & generation_bit(g)) != 0; }

  /// Bytes of the value on the wire: key id bits 28-30 (1: one bit in a
  /// byte, 2: 1, 3: 2, 4: 4, 5: 8 bytes); 0 for reserved size codes.
  constexpr std::size_t value_bytes() const noexcept { return value_bytes_of(id); }
  static constexpr std::size_t value_bytes_of(std::uint32_t key_id) noexcept {
    switch (key_id >> 28 & 0x7) {
      case 1: case 2: return 1;
      case 3: return 2;
      case 4: return 4;
      case 5: return 8;
      default: return 0;
    }
  }
};

/// Port name suffixes of MSGOUT keys, by u-blox port id (I2C = DDC).
inline constexpr std::array<std::string_view, 5> kMsgOutPortSuffix{"_I2C", "_UART1", "_UART2", "_USB", "_SPI"};

/// Every key of every generation, in table order (VALGET wildcards answer
/// in it; skip the rows !exists_on the chip's generation).
std::span<const ConfigKey> config_keys() noexcept;
/// The row of key_id, or nullptr when unknown to every generation.
const ConfigKey* find_config_key(std::uint32_t key_id) noexcept;
/// The row of key_id when generation g knows it, else nullptr.
const ConfigKey* find_config_key(std::uint32_t key_id, Generation g) noexcept;
/// Full u-blox name ("CFG-MSGOUT-UBX_NAV_PVT_UART1"), for docs and tests.
std::string config_key_name(const ConfigKey& k);

/// Wildcards of CFG-VALGET/VALDEL (UBX-18010854 §6.7): item id 0xfff asks
/// for every key of the group (bits 16-23); group 0xff with item 0xfff for
/// every key. The size bits are ignored.
constexpr bool is_key_wildcard(std::uint32_t key_id) noexcept { return (key_id & 0xFFF) == 0xFFF; }
constexpr bool key_matches(std::uint32_t pattern, std::uint32_t key_id) noexcept {
  if (!is_key_wildcard(pattern)) return pattern == key_id;
  const std::uint32_t group = pattern >> 16 & 0xFF;
  return group == 0xFF || group == (key_id >> 16 & 0xFF);
}

/// Value of k in c as the host on UART1 number uart sees the ports.
std::uint64_t read_config_key(const ConfigKey& k, const DeviceConfig& c, std::size_t uart) noexcept;
/// The value is one u-blox accepts for k (range, enum, the line settings
/// the emulator can really run).
bool valid_config_value(const ConfigKey& k, std::uint64_t value) noexcept;
/// Write value into c; false when the CFG-MSG rate table is full or the
/// block is missing (nothing written then).
bool write_config_key(const ConfigKey& k, DeviceConfig& c, std::size_t uart, std::uint64_t value) noexcept;
/// The interference monitor as the CFG-ITFM block of c holds it (the key
/// rows own the bit layout). No block: off.
ItfmSettings itfm_settings(const DeviceConfig& c) noexcept;

/// Factory plain values (DeviceConfig::factory_defaults fills them).
void set_plain_defaults(DeviceConfig& c) noexcept;

/// A CFG-VALSET v1 transaction in progress and the scratch configuration
/// VALSET/VALDEL apply to before committing (so a failing key leaves the
/// configuration untouched). Sized once; never allocates afterwards.
struct ValTransaction {
  explicit ValTransaction(const DeviceConfig& like) : scratch(like), scratch_ram(like) {}
  struct Pending {
    std::uint32_t key = 0;
    std::uint64_t value = 0;
  };
  bool open = false;
  std::uint8_t layers = 0;   ///< VALSET layers bits of the transaction
  std::size_t size = 0;      ///< pending pairs
  std::array<Pending, 512> pending{};  ///< last value per key (a transaction holds at most every key once)
  DeviceConfig scratch, scratch_ram;  ///< staged saved and RAM configurations

  void cancel() noexcept {
    open = false;
    size = 0;
  }
};

}  // namespace gnssemu::protocol::ubx
