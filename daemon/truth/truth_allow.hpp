// SPDX-License-Identifier: Apache-2.0
#pragma once
// TruthAllowList: the senders [truth] allow accepts (addresses and CIDR
// blocks; empty: any sender). Checked per datagram: no allocation.
#include <vector>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/ip/address.hpp>

#include "config/address_block.hpp"

namespace gnssemu::daemon {

class TruthAllowList {
public:
  TruthAllowList() = default;
  /// blocks: as [truth] allow holds them; empty: everyone is allowed.
  explicit TruthAllowList(std::vector<config::AddressBlock> blocks) : blocks_(std::move(blocks)) {}

  /// Whether a datagram from sender is accepted.
  bool allows(const boost::asio::ip::address& sender) const noexcept;
  bool empty() const noexcept { return blocks_.empty(); }
  /// "127.0.0.1/32, 10.0.0.0/8" for logs; "any sender" when empty.
  std::string describe() const;

private:
  std::vector<config::AddressBlock> blocks_;
};

}  // namespace gnssemu::daemon
