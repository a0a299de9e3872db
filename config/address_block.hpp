// SPDX-License-Identifier: Apache-2.0
#pragma once
// AddressBlock: an IPv4 or IPv6 address with a prefix length ("10.0.0.0/8",
// "::1", "192.168.1.20"), as [truth] allow lists senders. IPv4 blocks also
// match IPv4-mapped IPv6 peers (::ffff:a.b.c.d) of a dual-stack socket.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace gnssemu::config {

struct AddressBlock {
  std::array<uint8_t, 16> bytes{};  ///< network order; IPv4 in the first 4
  bool v6 = false;
  int prefix_bits = 32;             ///< [0, 32] IPv4, [0, 128] IPv6

  /// addr: 4 (IPv4) or 16 (IPv6) bytes in network order.
  bool contains(const uint8_t* addr, bool addr_v6) const noexcept;
  /// "a.b.c.d/n" as given (host bits kept: "10.1.2.3/8" is the block 10/8).
  std::string text() const;
};

/// Parses "addr" or "addr/prefix"; on failure returns nullopt and sets why.
std::optional<AddressBlock> parse_address_block(std::string_view text, std::string& why);

}  // namespace gnssemu::config
