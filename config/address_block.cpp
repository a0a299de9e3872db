// SPDX-License-Identifier: Apache-2.0
#include "config/address_block.hpp"

#include <arpa/inet.h>

#include <charconv>

namespace gnssemu::config {
namespace {

bool prefix_matches(const uint8_t* a, const uint8_t* b, int bits) noexcept {
  int i = 0;
  for (; bits >= 8; bits -= 8, ++i) {
    if (a[i] != b[i]) return false;
  }
  if (bits == 0) return true;
  const auto mask = static_cast<uint8_t>(0xFFu << (8 - bits));
  return (a[i] & mask) == (b[i] & mask);
}

// ::ffff:a.b.c.d (RFC 4291 §2.5.5.2).
bool is_v4_mapped(const uint8_t* a) noexcept {
  for (int i = 0; i < 10; ++i) {
    if (a[i] != 0) return false;
  }
  return a[10] == 0xFF && a[11] == 0xFF;
}

}  // namespace

bool AddressBlock::contains(const uint8_t* addr, bool addr_v6) const noexcept {
  if (v6 == addr_v6) return prefix_matches(bytes.data(), addr, prefix_bits);
  if (!v6 && addr_v6 && is_v4_mapped(addr)) return prefix_matches(bytes.data(), addr + 12, prefix_bits);
  return false;
}

std::string AddressBlock::text() const {
  char buf[INET6_ADDRSTRLEN] = {};
  inet_ntop(v6 ? AF_INET6 : AF_INET, bytes.data(), buf, sizeof buf);
  return std::string(buf) + "/" + std::to_string(prefix_bits);
}

std::optional<AddressBlock> parse_address_block(std::string_view text, std::string& why) {
  const std::size_t slash = text.find('/');
  const std::string addr(text.substr(0, slash));
  AddressBlock b;
  if (inet_pton(AF_INET, addr.c_str(), b.bytes.data()) == 1) {
    b.prefix_bits = 32;
  } else if (inet_pton(AF_INET6, addr.c_str(), b.bytes.data()) == 1) {
    b.v6 = true;
    b.prefix_bits = 128;
  } else {
    why = "'" + addr + "' is not an IPv4 or IPv6 address (host names are not accepted)";
    return std::nullopt;
  }
  if (slash == std::string_view::npos) return b;
  const std::string_view bits = text.substr(slash + 1);
  int n = -1;
  const auto [end, ec] = std::from_chars(bits.data(), bits.data() + bits.size(), n);
  const int max_bits = b.v6 ? 128 : 32;
  if (bits.empty() || ec != std::errc() || end != bits.data() + bits.size() || n < 0 || n > max_bits) {
    why = "prefix length '" + std::string(bits) + "' is not an integer in [0, " + std::to_string(max_bits) + "]";
    return std::nullopt;
  }
  b.prefix_bits = n;
  return b;
}

}  // namespace gnssemu::config
