// SPDX-License-Identifier: Apache-2.0
// ubx_bench: UBX output of real receiver Fixes (brdc0010.22n): bytes per
// epoch for the message sets PX4, ArduPilot and gpsd configure, what that
// needs of a UART at 5 and 10 Hz, encode cost per epoch and heap allocations,
// and the cost of answering the PX4 configuration sequence. Prints figures.
//   ubx_bench [nav_file] [epochs]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "tests/support/alloc_counter.hpp"

namespace {

using namespace gnssemu;
namespace ubx = protocol::ubx;

struct MessageSet {
  const char* name;
  std::vector<std::pair<ubx::MsgId, int>> rates;
};

struct Feed : ubx::DecoderSink {
  ubx::Device* r = nullptr;
  std::string* out = nullptr;
  void on_ubx(const ubx::FrameView& f) override { r->handle_ubx({}, f, 0.0, *out); }
  void on_nmea(std::string_view s) override { r->handle_nmea({}, s, *out); }
};

std::string frame(ubx::MsgId id, std::vector<std::uint8_t> p) {
  std::string s;
  ubx::append_frame(s, id, p);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string nav_path =
      argc > 1 ? argv[1] : std::string(GNSSEMU_SOURCE_DIR) + "/tests/data/nav/brdc0010.22n";
  const int epochs = argc > 2 ? std::max(100, std::atoi(argv[2])) : 3000;
  try {
    const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
    const orbit::EphemerisStore store(nav.ephemerides);
    pipeline::Pipeline rx(store, pipeline::PipelineConfig{});
    const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
    const Ecef p0 = geo::ecef_from_lla(site);
    const time::GpsTime t0 = store.first_valid() + 8 * 3600.0;
    std::vector<receiver::Fix> fixes;
    for (int k = 0; k < epochs; ++k) {
      world::Truth tr;
      tr.t = t0 + 0.2 * k;
      tr.pos_m = p0;
      tr.valid = true;
      fixes.push_back(rx.step(tr.t, tr));
    }
    const MessageSet sets[] = {
        {"px4", {{ubx::msg::kNavPvt, 1}, {ubx::msg::kNavStatus, 1}, {ubx::msg::kNavDop, 1},
                 {ubx::msg::kNavSvinfo, 5}, {ubx::msg::kMonHw, 2}}},
        {"ardupilot", {{ubx::msg::kNavPvt, 1}, {ubx::msg::kNavPosllh, 1}, {ubx::msg::kNavStatus, 1},
                       {ubx::msg::kNavSol, 1}, {ubx::msg::kNavVelned, 1}, {ubx::msg::kNavTimegps, 5},
                       {ubx::msg::kNavDop, 1}, {ubx::msg::kMonHw, 2}}},
        {"gpsd", {{ubx::msg::kNavPvt, 1}, {ubx::msg::kNavTimegps, 1}, {ubx::msg::kNavSat, 1},
                  {ubx::msg::kNavDop, 1}, {ubx::msg::kNavEoe, 1}}},
        {"all", {{ubx::msg::kNavPvt, 1}, {ubx::msg::kNavPosllh, 1}, {ubx::msg::kNavStatus, 1},
                 {ubx::msg::kNavDop, 1}, {ubx::msg::kNavSol, 1}, {ubx::msg::kNavVelned, 1},
                 {ubx::msg::kNavTimegps, 1}, {ubx::msg::kNavTimeutc, 1}, {ubx::msg::kNavSat, 1},
                 {ubx::msg::kNavSvinfo, 1}, {ubx::msg::kMonHw, 1}, {ubx::msg::kNavEoe, 1}}},
    };
    std::printf("ubx_bench: %s, %d epochs, static 39.6N 22.4E, mean satellites in Fix %.1f\n", nav_path.c_str(),
                epochs, [&] {
                  double n = 0;
                  for (const auto& f : fixes) n += f.num_sats;
                  return n / static_cast<double>(fixes.size());
                }());
    std::printf("%-10s %10s %10s %12s %12s %10s %10s %10s\n", "set", "bytes/ep", "max_bytes", "B/s@5Hz", "B/s@10Hz",
                "baud@10Hz", "enc_us", "allocs/ep");
    for (const auto& s : sets) {
      ubx::Device r({});
      r.config().port(ubx::kPortUart1).out_proto_mask = ubx::proto::kUbx;
      for (const auto& [id, rate] : s.rates) r.config().set_message_rate(ubx::kPortUart1, id, static_cast<std::uint8_t>(rate));
      ubx::MessageList out;
      std::size_t total = 0, max_bytes = 0;
      double us = 0;
      long allocs = 0;
      for (std::size_t k = 0; k < fixes.size(); ++k) {
        const long a0 = support::allocation_count();
        const auto c0 = std::chrono::steady_clock::now();
        r.on_epoch(fixes[k], 0.2 * static_cast<double>(k));
        r.compose({}, out);
        const std::size_t n = out.bytes().size();
        const auto c1 = std::chrono::steady_clock::now();
        allocs += support::allocation_count() - a0;
        us += std::chrono::duration<double, std::micro>(c1 - c0).count();
        total += n;
        max_bytes = std::max(max_bytes, n);
      }
      const double per_epoch = static_cast<double>(total) / static_cast<double>(fixes.size());
      // 8N1: 10 bits per byte on the line.
      std::printf("%-10s %10.1f %10zu %12.0f %12.0f %10.0f %10.2f %10.3f\n", s.name, per_epoch, max_bytes,
                  per_epoch * 5, per_epoch * 10, per_epoch * 10 * 10, us / static_cast<double>(fixes.size()),
                  static_cast<double>(allocs) / static_cast<double>(fixes.size()));
    }
    // PX4 configuration sequence through the decoder and the device.
    std::string seq = frame(ubx::msg::kCfgValset, {0, 1, 0, 0, 1, 0, 0x52, 0x40, 0, 0xC2, 1, 0});
    std::vector<std::uint8_t> prt(20, 0);
    prt[0] = 1;
    prt[4] = 0xD0;
    prt[5] = 0x08;
    prt[8] = 0x80;
    prt[9] = 0x25;
    prt[12] = 1;
    prt[14] = 1;
    seq += frame(ubx::msg::kCfgPrt, prt) + frame(ubx::msg::kMonVer, {}) + frame(ubx::msg::kCfgRate, {200, 0, 1, 0, 0, 0});
    std::vector<std::uint8_t> nav5(36, 0);
    nav5[0] = 5;
    nav5[2] = 8;
    nav5[3] = 3;
    seq += frame(ubx::msg::kCfgNav5, nav5);
    for (auto m : std::vector<std::vector<std::uint8_t>>{{1, 7, 1}, {1, 3, 1}, {1, 4, 1}, {1, 0x30, 5}, {0x0A, 9, 2}}) {
      seq += frame(ubx::msg::kCfgMsg, m);
    }
    const int reps = 2000;
    std::string reply;
    reply.reserve(4096);
    double us = 0;
    for (int i = 0; i < reps; ++i) {
      ubx::Device r({});
      ubx::StreamDecoder d;
      Feed f;
      f.r = &r;
      f.out = &reply;
      reply.clear();
      const auto c0 = std::chrono::steady_clock::now();
      d.feed(seq, f);
      us += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - c0).count();
    }
    std::printf("px4 configuration sequence: %zu bytes in, %zu bytes out (10 messages: 1 NAK, 8 ACK, MON-VER), %.2f us to decode and answer\n",
                seq.size(), reply.size(), us / reps);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ubx_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
