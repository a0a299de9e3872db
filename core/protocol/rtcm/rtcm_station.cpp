// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/rtcm/rtcm_station.hpp"

#include <algorithm>
#include <cmath>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"

namespace gnssemu::protocol::rtcm {

namespace {

std::int64_t round_to(double v, double unit) noexcept { return static_cast<std::int64_t>(std::floor(v / unit + 0.5)); }

}  // namespace

void append_station(const StationInfo& st, bool with_height, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  w.u(12, with_height ? 1006 : 1005);
  w.u(12, static_cast<std::uint64_t>(st.station_id));
  w.u(6, 0);  // DF021 ITRF realisation year: not given
  w.u(1, st.gps ? 1 : 0);
  w.u(1, st.glonass ? 1 : 0);
  w.u(1, st.galileo ? 1 : 0);
  w.u(1, 0);  // DF141: physical reference station
  w.s(38, round_to(st.arp_ecef_m.x, 1e-4));
  w.u(1, 0);  // DF142 single receiver oscillator indicator
  w.u(1, 0);  // reserved
  w.s(38, round_to(st.arp_ecef_m.y, 1e-4));
  w.u(2, 0);  // DF364 quarter-cycle indicator: correction status unspecified
  w.s(38, round_to(st.arp_ecef_m.z, 1e-4));
  if (with_height) w.u(16, static_cast<std::uint64_t>(std::clamp<std::int64_t>(round_to(st.antenna_height_m, 1e-4), 0, 65535)));
  append_frame(std::span<const std::uint8_t>(buf.data(), w.bytes()), out);
}

void append_glonass_biases(int station_id, bool aligned, const GlonassBiases& biases_m, std::string& out) {
  Payload buf;
  BitWriter w(buf);
  w.u(12, 1230);
  w.u(12, static_cast<std::uint64_t>(station_id));
  w.u(1, aligned ? 1 : 0);
  w.u(3, 0);  // reserved
  unsigned mask = 0;
  for (std::size_t i = 0; i < biases_m.size(); ++i)
    if (biases_m[i]) mask |= 8u >> i;
  w.u(4, mask);
  for (const auto& b : biases_m) {
    if (!b) continue;
    const std::int64_t v = round_to(*b, 0.02);
    w.s(16, std::abs(v) > 32767 ? -32768 : v);
  }
  append_frame(std::span<const std::uint8_t>(buf.data(), w.bytes()), out);
}

}  // namespace gnssemu::protocol::rtcm
