// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/delay_line.hpp"

#include <algorithm>

#include "core/protocol/ubx/wire/ubx_message_list.hpp"

namespace gnssemu::daemon {

DelayLine::Entry& DelayLine::next_slot(double due_s) {
  if (count_ == slots_.size()) {
    // Full: unroll the ring so the new slot goes at its end.
    std::rotate(slots_.begin(), slots_.begin() + static_cast<std::ptrdiff_t>(head_), slots_.end());
    head_ = 0;
    Entry& e = slots_.emplace_back();
    e.bytes.reserve(protocol::ubx::MessageList::kMaxBytes);
    e.ends.reserve(protocol::ubx::MessageList::kMaxMessages);
  }
  if (count_ == 0) last_due_s_ = due_s;
  last_due_s_ = std::max(last_due_s_, due_s);
  Entry& e = slots_[(head_ + count_) % slots_.size()];
  e.due_s = last_due_s_;
  ++count_;
  return e;
}

void DelayLine::push(double due_s, std::string_view bytes, std::span<const std::size_t> ends) {
  Entry& e = next_slot(due_s);
  e.bytes.assign(bytes.data(), bytes.size());
  e.ends.assign(ends.begin(), ends.end());
  e.reply = false;
}

void DelayLine::push_reply(double due_s, int source, std::string_view bytes) {
  Entry& e = next_slot(due_s);
  e.bytes.assign(bytes.data(), bytes.size());
  e.ends.clear();
  e.reply = true;
  e.source = source;
}

void DelayLine::pop() noexcept {
  if (count_ == 0) return;
  head_ = (head_ + 1) % slots_.size();
  --count_;
}

}  // namespace gnssemu::daemon
