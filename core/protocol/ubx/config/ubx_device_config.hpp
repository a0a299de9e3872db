// SPDX-License-Identifier: Apache-2.0
#pragma once
// The configuration one emulated M8 keeps: per-port settings (CFG-PRT),
// message rates per port (CFG-MSG), CFG-RATE, CFG-NAV5, and the stored
// payload of every other CFG message it answers polls for. The emulated chip
// has one UART1 per output of the emulator (each host sees its own as port
// 1); DDC, UART2, USB and SPI exist once (docs/ubx.md §One chip). Factory
// defaults are a NEO-M8N's (sources in docs/ubx.md). Sized when made;
// copies between configurations of one chip do not allocate.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/config/ubx_generation.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "core/protocol/ubx/config/ubx_ports.hpp"

namespace gnssemu::protocol::ubx {

/// One port as CFG-PRT describes it (plus PUBX,41 autobauding).
struct PortSettings {
  std::uint8_t port_id = 0;
  bool exists = false;               ///< false for ports an NEO-M8N lacks (UART2, reserved): CFG-PRT NAK
  std::uint16_t tx_ready = 0;
  std::uint32_t mode = 0;            ///< UART framing (0x8C0 = 8N1) or DDC address
  std::uint32_t baud_bps = 0;        ///< UART line rate, bit/s; 0 for DDC/USB/SPI
  std::uint16_t in_proto_mask = 0;   ///< proto:: bits
  std::uint16_t out_proto_mask = 0;  ///< proto:: bits
  std::uint16_t flags = 0;
  bool autobauding = false;          ///< set by $PUBX,41 (recorded only)

  bool outputs_ubx() const noexcept { return out_proto_mask & proto::kUbx; }
  bool outputs_nmea() const noexcept { return out_proto_mask & proto::kNmea; }
  bool accepts_ubx() const noexcept { return in_proto_mask & proto::kUbx; }
  bool accepts_nmea() const noexcept { return in_proto_mask & proto::kNmea; }
};

/// Capacity of the rate table (an M8 accepts CFG-MSG for any output message;
/// 64 distinct ids is far more than any host sets).
inline constexpr std::size_t kMaxRateEntries = 64;
/// Largest stored CFG payload (CFG-USB, 108 bytes).
inline constexpr std::size_t kMaxStoredBytes = 112;
/// Stored CFG payloads (TP5 x2, INF x2, and the other pollable CFG messages).
inline constexpr std::size_t kMaxStoredBlocks = 24;
/// Configuration-interface values no legacy CFG message holds (the plain
/// keys of ubx_config_keys.hpp).
inline constexpr std::size_t kMaxPlainValues = 32;

/// A CFG payload kept verbatim and returned on poll. index distinguishes
/// CFG-TP5 tpIdx and CFG-INF protocolID; 0 otherwise.
struct StoredBlock {
  MsgId id;
  std::uint8_t index = 0;
  std::uint16_t size = 0;
  std::array<std::uint8_t, kMaxStoredBytes> bytes{};
  std::span<const std::uint8_t> payload() const noexcept { return {bytes.data(), size}; }
};

class DeviceConfig {
public:
  /// Factory defaults of a NEO-M8N (docs/ubx.md) with uarts UART1s (one per
  /// output; 0 counts as 1): UART1 9600 8N1 in UBX+NMEA+RTCM2 out UBX+NMEA;
  /// NMEA GGA GLL GSA GSV RMC VTG at 1 on DDC/UART1/USB/SPI; no UBX output;
  /// 1 Hz, GPS time; NAV5 portable/auto; the generation's factory CFG-GNSS
  /// (ubx_gnss.hpp: M8 GPS+GLONASS+QZSS+SBAS, NEO-M9N every system).
  static DeviceConfig factory_defaults(std::size_t uarts = 1, Generation generation = Generation::kM8);
  /// UART1's factory line rate, bit/s: 9600 on the NEO-M8N, 38400 on the
  /// NEO-M9N and ZED-F9P (reference/nmea0183.md §defaults).
  static std::uint32_t factory_uart1_baud(Generation generation) noexcept;

  wire::CfgRate rate{};
  wire::CfgNav5 nav5{};

  /// UART1s of the chip (>= 1).
  std::size_t uarts() const noexcept { return ports_.size() - kNumPorts + 1; }
  /// Settings columns: the kNumPorts u-blox ports (UART1 of the first
  /// output at kPortUart1), then UART1 of outputs 1, 2, ...
  std::size_t columns() const noexcept { return ports_.size(); }
  /// Column of u-blox port port_id (< kNumPorts) as a host on UART1 number
  /// uart (< uarts()) sees it: port 1 is that host's own UART1.
  std::size_t column(std::size_t uart, std::uint8_t port_id) const noexcept {
    return port_id != kPortUart1 || uart == 0 ? port_id : kNumPorts + uart - 1;
  }
  /// Settings of a column (< columns()).
  PortSettings& port(std::size_t column) noexcept { return ports_[column]; }
  const PortSettings& port(std::size_t column) const noexcept { return ports_[column]; }

  /// Rate of id in column (0 when not in the table or column >= columns()).
  std::uint8_t message_rate(std::size_t column, MsgId id) const noexcept;
  /// Set one column's rate; false when the table is full or column >= columns().
  bool set_message_rate(std::size_t column, MsgId id, std::uint8_t value) noexcept;
  /// Every rate of every column equal to o's (o: a configuration of the same chip).
  bool same_rates(const DeviceConfig& o) const noexcept;
  /// Ids in the rate table (some may be at rate 0 everywhere).
  std::span<const MsgId> rated_messages() const noexcept { return {rate_ids_.data(), num_rates_}; }

  /// Stored payload of (id, index), or nullptr.
  const StoredBlock* stored(MsgId id, std::uint8_t index = 0) const noexcept;
  /// Store a payload (size <= kMaxStoredBytes); false when full or too big.
  bool store(MsgId id, std::uint8_t index, std::span<const std::uint8_t> payload) noexcept;

  /// A plain configuration-key value (slot < kMaxPlainValues; ubx_config_keys.hpp).
  std::uint64_t plain_value(std::size_t slot) const noexcept { return slot < plain_.size() ? plain_[slot] : 0; }
  void set_plain_value(std::size_t slot, std::uint64_t value) noexcept {
    if (slot < plain_.size()) plain_[slot] = value;
  }

  /// Navigation epoch period measRate * navRate, s.
  double nav_period_s() const noexcept { return 1e-3 * rate.measRate * rate.navRate; }

  /// Equal settings; rate tables compare as sets of non-zero rates.
  bool operator==(const DeviceConfig&) const;

  /// CFG-CFG mask sections (b0 ioPort, b1 msgConf, b2 infMsg, b3 navConf,
  /// b4 rxmConf, b9 rinvConf, b10 antConf, b11 logConf): copy those sections
  /// from src (a configuration of the same chip) into this. The plain
  /// values, which no M8 section holds, travel with any non-zero mask.
  void copy_sections(const DeviceConfig& src, std::uint32_t mask) noexcept;

  /// The configuration as text, one setting per line (ubx_state_text.cpp):
  /// what a state file holds of a chip's BBR/flash. Allocates (load/save time only).
  std::string to_text() const;
  /// Read to_text() output into this configuration (a factory one of the
  /// same chip): ports and columns beyond this chip's are skipped. Throws
  /// gnssemu::Error("source:line: reason") on a malformed line; nothing is
  /// changed then.
  void read_text(std::string_view text, const std::string& source);

private:
  DeviceConfig() = default;
  std::size_t row(MsgId id) const noexcept;  ///< rate table row of id, num_rates_ when absent

  std::vector<PortSettings> ports_;
  std::array<MsgId, kMaxRateEntries> rate_ids_{};
  std::size_t num_rates_ = 0;
  std::vector<std::uint8_t> rates_;  ///< kMaxRateEntries rows of columns() rates
  std::array<StoredBlock, kMaxStoredBlocks> blocks_{};
  std::size_t num_blocks_ = 0;
  std::array<std::uint64_t, kMaxPlainValues> plain_{};
};

}  // namespace gnssemu::protocol::ubx
