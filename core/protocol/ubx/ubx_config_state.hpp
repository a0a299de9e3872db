#pragma once
// The configuration an M8 keeps: per-port settings (CFG-PRT), message rates
// per port (CFG-MSG), CFG-RATE, CFG-NAV5, and the stored payload of every
// other CFG message it answers polls for. Factory defaults are a NEO-M8N's
// (sources in docs/ubx.md). Plain data: copyable, no allocation.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/protocol/ubx/ubx_frame.hpp"
#include "core/protocol/ubx/ubx_messages.hpp"
#include "core/protocol/ubx/ubx_ports.hpp"

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

/// Output rate of one message on each port: emitted once every rate[port]
/// navigation epochs, 0 = off.
struct MessageRate {
  MsgId id;
  std::array<std::uint8_t, kNumPorts> rate{};
};

/// Capacity of the rate table (an M8 accepts CFG-MSG for any output message;
/// 64 distinct ids is far more than any host sets).
inline constexpr std::size_t kMaxRateEntries = 64;
/// Largest stored CFG payload (CFG-USB, 108 bytes).
inline constexpr std::size_t kMaxStoredBytes = 112;
/// Stored CFG payloads (TP5 x2, INF x2, and the other pollable CFG messages).
inline constexpr std::size_t kMaxStoredBlocks = 24;

/// A CFG payload kept verbatim and returned on poll. index distinguishes
/// CFG-TP5 tpIdx and CFG-INF protocolID; 0 otherwise.
struct StoredBlock {
  MsgId id;
  std::uint8_t index = 0;
  std::uint16_t size = 0;
  std::array<std::uint8_t, kMaxStoredBytes> bytes{};
  std::span<const std::uint8_t> payload() const noexcept { return {bytes.data(), size}; }
};

class ReceiverConfig {
public:
  /// Factory defaults of a NEO-M8N (docs/ubx.md): UART1 9600 8N1 in
  /// UBX+NMEA+RTCM2 out UBX+NMEA; NMEA GGA GLL GSA GSV RMC VTG at 1 on
  /// DDC/UART1/USB/SPI; no UBX output; 1 Hz, GPS time; NAV5 portable/auto.
  static ReceiverConfig factory_defaults();

  std::array<PortSettings, kNumPorts> ports{};
  wire::CfgRate rate{};
  wire::CfgNav5 nav5{};

  /// Rate of id on port_id (0 when not in the table or port_id >= kNumPorts).
  std::uint8_t message_rate(std::uint8_t port_id, MsgId id) const noexcept;
  /// All six rates of id (zeros when absent).
  std::array<std::uint8_t, kNumPorts> message_rates(MsgId id) const noexcept;
  /// Set one port's rate; false when the table is full.
  bool set_message_rate(std::uint8_t port_id, MsgId id, std::uint8_t value) noexcept;
  /// Set all six rates; false when the table is full.
  bool set_message_rates(MsgId id, const std::array<std::uint8_t, kNumPorts>& rates) noexcept;
  std::span<const MessageRate> rate_table() const noexcept { return {rates_.data(), num_rates_}; }

  /// Stored payload of (id, index), or nullptr.
  const StoredBlock* stored(MsgId id, std::uint8_t index = 0) const noexcept;
  /// Store a payload (size <= kMaxStoredBytes); false when full or too big.
  bool store(MsgId id, std::uint8_t index, std::span<const std::uint8_t> payload) noexcept;

  /// Navigation epoch period measRate * navRate, s.
  double nav_period_s() const noexcept { return 1e-3 * rate.measRate * rate.navRate; }

  bool operator==(const ReceiverConfig&) const;

  /// CFG-CFG mask sections (b0 ioPort, b1 msgConf, b2 infMsg, b3 navConf,
  /// b4 rxmConf, b9 rinvConf, b10 antConf, b11 logConf): copy those sections
  /// from src into this.
  void copy_sections(const ReceiverConfig& src, std::uint32_t mask) noexcept;

private:
  std::array<MessageRate, kMaxRateEntries> rates_{};
  std::size_t num_rates_ = 0;
  std::array<StoredBlock, kMaxStoredBlocks> blocks_{};
  std::size_t num_blocks_ = 0;
};

}  // namespace gnssemu::protocol::ubx
