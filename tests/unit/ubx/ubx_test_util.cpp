// SPDX-License-Identifier: Apache-2.0
#include "ubx_test_util.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/common/constants.hpp"
#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "nmea_test_util.hpp"

namespace gnssemu::protocol::ubx::test {

void complete_fix(receiver::Fix& f) {
  const double lat = f.lla.lat_rad, lon = f.lla.lon_rad, h = f.lla.height_m;
  const double e2 = kWgs84F * (2.0 - kWgs84F);
  const double n = kWgs84A_m / std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
  f.pos_m = Ecef((n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon),
                 (n * (1.0 - e2) + h) * std::sin(lat));
  if (f.vel_enu_m_s == Enu{}) {
    f.vel_enu_m_s = Enu(f.speed_m_s * std::sin(f.course_rad), f.speed_m_s * std::cos(f.course_rad), f.climb_m_s);
  }
  const Enu& v = f.vel_enu_m_s;
  // ENU -> ECEF rotation at (lat, lon).
  const double sl = std::sin(lat), cl = std::cos(lat), so = std::sin(lon), co = std::cos(lon);
  f.vel_m_s = Ecef(-so * v.x - sl * co * v.y + cl * co * v.z, co * v.x - sl * so * v.y + cl * so * v.z,
                   cl * v.y + sl * v.z);
}

receiver::Fix sample_fix() {
  receiver::Fix f = nmea::test::sample_fix_3d();
  f.climb_m_s = -0.42;
  f.vel_enu_m_s = Enu(13.4 * std::sin(87.3 * kDegToRad), 13.4 * std::cos(87.3 * kDegToRad), -0.42);
  complete_fix(f);
  f.sigma_uere_m = 1.1;
  f.speed_acc_m_s = 0.21;
  f.time_acc_s = 23e-9;
  f.clock_bias_s = 1.2e-4;
  f.noise_rise_db = 3.0;
  double res = -1.5;
  for (int i = 0; i < f.num_sats; ++i) {
    auto& s = f.sats[static_cast<std::size_t>(i)];
    if (s.used) s.residual_m = res += 0.37;
  }
  return f;
}

std::vector<Frame> split_frames(std::string_view stream, std::vector<std::string>* nmea) {
  struct Sink : DecoderSink {
    std::vector<Frame> frames;
    std::vector<std::string>* nmea = nullptr;
    void on_ubx(const FrameView& f) override { frames.push_back({f.id, {f.payload.begin(), f.payload.end()}}); }
    void on_nmea(std::string_view s) override {
      if (nmea) nmea->emplace_back(s);
    }
  } sink;
  sink.nmea = nmea;
  StreamDecoder d;
  d.feed(stream, sink);
  return sink.frames;
}

std::string from_hex(std::string_view hex) {
  std::string out;
  int hi = -1;
  for (char c : hex) {
    if (c == ' ' || c == '\n') continue;
    const int v = std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : std::toupper(c) - 'A' + 10;
    if (v < 0 || v > 15) throw std::runtime_error("bad hex");
    if (hi < 0) {
      hi = v;
    } else {
      out.push_back(static_cast<char>(hi << 4 | v));
      hi = -1;
    }
  }
  if (hi >= 0) throw std::runtime_error("odd hex");
  return out;
}

std::string to_hex(std::string_view bytes) {
  static const char* d = "0123456789ABCDEF";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const auto b = static_cast<unsigned char>(bytes[i]);
    if (i) out.push_back(' ');
    out.push_back(d[b >> 4]);
    out.push_back(d[b & 15]);
  }
  return out;
}

std::string frame_bytes(MsgId id, const std::vector<std::uint8_t>& payload) {
  std::string out;
  append_frame(out, id, payload);
  return out;
}

std::uint16_t u2(const std::vector<std::uint8_t>& p, std::size_t off) {
  return static_cast<std::uint16_t>(p.at(off) | p.at(off + 1) << 8);
}
std::uint32_t u4(const std::vector<std::uint8_t>& p, std::size_t off) {
  return static_cast<std::uint32_t>(u2(p, off)) | static_cast<std::uint32_t>(u2(p, off + 2)) << 16;
}
std::int32_t i4(const std::vector<std::uint8_t>& p, std::size_t off) { return static_cast<std::int32_t>(u4(p, off)); }

std::size_t ubx_epoch(const Device& d, Link at, std::string& out) {
  MessageList list;
  d.compose(at, list, Layout::kPerProtocol);
  const std::size_t before = out.size();
  for (const MessageList::Message& m : list.messages()) {
    if (m.protocol == Protocol::kUbx) out.append(list.bytes(m));
  }
  return out.size() - before;
}

Reply HandlerRig::call(Handler handler, MsgId id, const std::vector<std::uint8_t>& payload, std::size_t uart,
                       std::uint8_t port) {
  out.clear();
  HandlerContext ctx{current, saved, defaults, uart, port, out, encoder, fix, info, false,
                     encoder.mon_ver_config().generation, std::nullopt, &transaction};
  const Reply r = handler(ctx, FrameView{id, payload});
  reset = ctx.reset;
  return r;
}

std::vector<Frame> HandlerRig::replies() const { return split_frames(out); }

}  // namespace gnssemu::protocol::ubx::test
