#include "daemon/message_split.hpp"

#include <array>
#include <cstdint>

#include "config/message_names.hpp"

namespace gnssemu::daemon {

std::size_t message_length(std::string_view data) noexcept {
  if (data.empty()) return 0;
  const auto byte = [&](std::size_t i) { return static_cast<uint8_t>(data[i]); };
  if (data.size() >= 6 && byte(0) == 0xB5 && byte(1) == 0x62) {
    const std::size_t n = 8 + (byte(4) | static_cast<std::size_t>(byte(5)) << 8);
    return n <= data.size() ? n : data.size();
  }
  if (data[0] == '$') {
    const std::size_t lf = data.find('\n');
    return lf == std::string_view::npos ? data.size() : lf + 1;
  }
  std::size_t i = 1;
  while (i < data.size() && data[i] != '$' && !(byte(i) == 0xB5 && i + 1 < data.size() && byte(i + 1) == 0x62)) ++i;
  return i;
}

std::string_view message_label(std::string_view data) noexcept {
  const auto byte = [&](std::size_t i) { return static_cast<uint8_t>(data[i]); };
  if (data.size() >= 6 && byte(0) == 0xB5 && byte(1) == 0x62) {
    const std::string_view name = config::message_name(byte(2), byte(3));
    if (!name.empty()) return name;
    // Replies and polls answered (ACK, CFG, MON-VER) are not in the table.
    if (byte(2) == 0x05) return byte(3) == 0x01 ? "ACK-ACK" : "ACK-NAK";
    if (byte(2) == 0x0A && byte(3) == 0x04) return "MON-VER";
    if (byte(2) == 0x06) return "CFG";
    return "UBX";
  }
  if (data.size() >= 6 && data[0] == '$') return data.substr(3, 3);  // "$GPGGA" -> "GGA"
  return "bytes";
}

}  // namespace gnssemu::daemon
