// SPDX-License-Identifier: Apache-2.0
#include "daemon/truth/truth_allow.hpp"

namespace gnssemu::daemon {

bool TruthAllowList::allows(const boost::asio::ip::address& sender) const noexcept {
  if (blocks_.empty()) return true;
  if (sender.is_v4()) {
    const auto b = sender.to_v4().to_bytes();
    for (const config::AddressBlock& blk : blocks_) {
      if (blk.contains(b.data(), false)) return true;
    }
    return false;
  }
  const auto b = sender.to_v6().to_bytes();
  for (const config::AddressBlock& blk : blocks_) {
    if (blk.contains(b.data(), true)) return true;
  }
  return false;
}

std::string TruthAllowList::describe() const {
  if (blocks_.empty()) return "any sender";
  std::string out;
  for (const config::AddressBlock& b : blocks_) out += (out.empty() ? "" : ", ") + b.text();
  return out;
}

}  // namespace gnssemu::daemon
