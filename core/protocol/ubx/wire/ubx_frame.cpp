// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/wire/ubx_frame.hpp"

namespace gnssemu::protocol::ubx {

std::size_t append_frame(std::string& out, MsgId id, std::span<const std::uint8_t> payload) {
  const auto len = static_cast<std::uint16_t>(payload.size());
  const std::uint8_t head[6] = {kSync1, kSync2, id.cls, id.id, static_cast<std::uint8_t>(len & 0xFF),
                                static_cast<std::uint8_t>(len >> 8)};
  std::uint8_t a = 0, b = 0;
  const auto add = [&](std::uint8_t v) {
    a = static_cast<std::uint8_t>(a + v);
    b = static_cast<std::uint8_t>(b + a);
  };
  for (int i = 2; i < 6; ++i) add(head[i]);
  for (std::uint8_t v : payload) add(v);
  out.append(reinterpret_cast<const char*>(head), sizeof head);
  out.append(reinterpret_cast<const char*>(payload.data()), payload.size());
  out.push_back(static_cast<char>(a));
  out.push_back(static_cast<char>(b));
  return payload.size() + kFrameOverheadBytes;
}

}  // namespace gnssemu::protocol::ubx
