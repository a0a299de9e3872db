// SPDX-License-Identifier: Apache-2.0
// docs/ubx.md lists every configuration key the emulated M9 knows: the table
// between the markers is generated from config_keys() and must match it, so a
// key cannot be readable but undocumented (GNSSEMU_REBUILD_DOCS=1 rewrites it).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "core/protocol/ubx/config/ubx_config_keys.hpp"

namespace gnssemu::protocol::ubx {
namespace {

constexpr std::string_view kBegin = "<!-- config-keys (generated: GNSSEMU_REBUILD_DOCS=1 test_ubx) -->";
constexpr std::string_view kEnd = "<!-- /config-keys -->";
constexpr std::string_view kPortNames[] = {"I2C", "UART1", "UART2", "USB", "SPI"};

std::string hex(std::uint64_t v, int digits) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%0*llX", digits, static_cast<unsigned long long>(v));
  return buf;
}

/// Size from the key id: "bit" (L, one byte on the wire) or bytes, signed or not.
std::string type_of(const ConfigKey& k) {
  if ((k.id >> 28 & 7) == 1) return "bit";
  const std::size_t n = k.value_bytes();
  return std::to_string(n) + (n == 1 ? " byte" : " bytes") + (k.is_signed ? " signed" : "");
}

std::string block_name(MsgId id) {
  if (id == msg::kCfgOdo) return "CFG-ODO";
  if (id == msg::kCfgNmea) return "CFG-NMEA";
  if (id == msg::kCfgItfm) return "CFG-ITFM";
  if (id == msg::kCfgSbas) return "CFG-SBAS";
  return "CFG " + hex(id.id, 2);
}

std::string where(const ConfigKey& k) {
  const std::string port(kPortNames[k.port]);
  const std::string bit =
      k.width == 1 ? " bit " + std::to_string(k.shift)
                   : " bits " + std::to_string(k.shift) + "-" + std::to_string(k.shift + k.width - 1);
  switch (k.store) {
    case KeyStore::kPlain: return "stored only";
    case KeyStore::kInProto: return "CFG-PRT " + port + " inProtoMask bit " + std::to_string(k.shift);
    case KeyStore::kOutProto: return "CFG-PRT " + port + " outProtoMask bit " + std::to_string(k.shift);
    case KeyStore::kUartBaud: return "CFG-PRT " + port + " baudRate (a u-blox rate)";
    case KeyStore::kUartFraming: return "CFG-PRT " + port + " mode: 8N1 only";
    case KeyStore::kMsgOut: return "CFG-MSG rate of " + hex(k.msg.cls, 2) + " " + hex(k.msg.id, 2) + " per port";
    case KeyStore::kRate: return "CFG-RATE byte " + std::to_string(k.offset);
    case KeyStore::kNav5: return "CFG-NAV5 byte " + std::to_string(k.offset);
    case KeyStore::kBlock:
      if (k.msg == msg::kCfgInf) return std::string(k.port == 0 ? "CFG-INF UBX" : "CFG-INF NMEA") + " infMsgMask of " +
                                        std::string(kPortNames[k.offset - 4]);
      return block_name(k.msg) + " byte " + std::to_string(k.offset) + bit;
    case KeyStore::kGnss: return "CFG-GNSS gnssId " + std::to_string(k.offset) + " flags" + bit;
    case KeyStore::kNmeaProtver: return "CFG-NMEA nmeaVersion (0x41 = 41, 0x4B = 42)";
  }
  return "";
}

std::string range_of(const ConfigKey& k) {
  if (k.store == KeyStore::kUartBaud) return "4800 … 921600 (u-blox rates)";
  if (k.allowed != 0) {
    std::string s;
    for (int v = 0; v < 64; ++v) {
      if (k.allowed >> v & 1u) s += (s.empty() ? "" : ", ") + std::to_string(v);
    }
    return s;
  }
  return std::to_string(k.min) + " … " + std::to_string(k.max);
}

std::string generate() {
  // Defaults as the first generation that knows the key has them.
  const DeviceConfig m9 = DeviceConfig::factory_defaults(1, Generation::kM9);
  const DeviceConfig f9p = DeviceConfig::factory_defaults(1, Generation::kF9P);
  std::ostringstream s;
  s << kBegin << "\n\n";
  s << "| key id | name | size | values | default (I2C/UART1/UART2/USB/SPI) | chips | state it reads and writes |\n";
  s << "|---|---|---|---|---|---|---|\n";
  const auto keys = config_keys();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const ConfigKey& k = keys[i];
    const DeviceConfig& defaults = k.exists_on(Generation::kM9) ? m9 : f9p;
    const char* chips = k.exists_on(Generation::kM9) ? "m9, f9p" : "f9p";
    if (k.store == KeyStore::kMsgOut) {
      // One row per message: ids I2C, UART1, UART2, USB, SPI = base + 0..4.
      std::string defaults_per_port;
      for (std::uint8_t p = 0; p < kMsgOutPortSuffix.size(); ++p) {
        if (p) defaults_per_port += '/';
        defaults_per_port += std::to_string(read_config_key(keys[i + p], defaults, 0));
      }
      s << "| " << hex(k.id, 8) << "+0..4 | " << k.name << "_{I2C,UART1,UART2,USB,SPI} | 1 byte | 0 … 255 | "
        << defaults_per_port << " | " << chips << " | " << where(k) << " |\n";
      i += kMsgOutPortSuffix.size() - 1;
      continue;
    }
    s << "| " << hex(k.id, 8) << " | " << config_key_name(k) << " | " << type_of(k) << " | " << range_of(k) << " | "
      << read_config_key(k, defaults, 0) << " | " << chips << " | " << where(k) << " |\n";
  }
  s << "\n" << kEnd;
  return s.str();
}

TEST(UbxConfigDocs, KeyTableInDocsIsCurrent) {
  const std::string path = std::string(GNSSEMU_SOURCE_DIR) + "/docs/ubx.md";
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::string doc = text.str();
  const std::size_t b = doc.find(kBegin);
  const std::size_t e = doc.find(kEnd);
  ASSERT_NE(b, std::string::npos) << path << ": no " << kBegin;
  ASSERT_NE(e, std::string::npos) << path << ": no " << kEnd;
  const std::string table = generate();
  if (std::getenv("GNSSEMU_REBUILD_DOCS") != nullptr) {
    doc.replace(b, e + kEnd.size() - b, table);
    std::ofstream(path, std::ios::binary) << doc;
    GTEST_SKIP() << "rewrote the key table of " << path;
  }
  EXPECT_EQ(doc.substr(b, e + kEnd.size() - b), table)
      << path << ": the configuration key table is stale; GNSSEMU_REBUILD_DOCS=1 build/tests/test_ubx rewrites it";
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
