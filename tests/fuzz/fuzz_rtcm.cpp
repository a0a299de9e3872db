// SPDX-License-Identifier: Apache-2.0
// RTCM 3 bytes from a host through the frame reader and the decoder into a
// rover's Corrections, whole and split at a point the input chooses; and
// the input's bytes as payloads straight into the decoder (CRC bypassed, so
// masks and fields are reached). Oracles: every frame handed on has a payload
// of at most 1023 bytes and a good CRC; the counters account for every byte;
// the split makes no difference; the decoder never reads past a payload and
// an epoch it hands over holds only valid satellites and finite values.
#include <cstdint>
#include <span>

#include <cmath>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_decoder.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu::protocol::rtcm;

const gnssemu::time::GpsTime kNow(2300, 345600.0);

void check(const gnssemu::receiver::Corrections& c) {
  if (!c.obs_valid) return;
  gnssemu::fuzz::expect(c.obs.num_meas >= 0 && c.obs.num_meas <= gnssemu::receiver::kMaxRawMeasurements,
                        "measurements within the epoch");
  for (int i = 0; i < c.obs.num_meas; ++i) {
    const auto& m = c.obs.meas[static_cast<std::size_t>(i)];
    gnssemu::fuzz::expect(m.sat.valid(), "valid satellite");
    gnssemu::fuzz::expect(std::isfinite(m.pseudorange_m) && std::isfinite(m.carrier_phase_cycles) &&
                              std::isfinite(m.doppler_hz) && std::isfinite(m.lock_time_s),
                          "finite values");
  }
}

struct Sink : FrameSink {
  std::uint64_t frames = 0, bytes = 0;
  Decoder decoder;
  gnssemu::receiver::Corrections corrections;
  void on_frame(std::span<const std::uint8_t> p) override {
    gnssemu::fuzz::expect(p.size() <= kMaxPayloadBytes, "payload within 1023 bytes");
    ++frames;
    bytes += p.size() + kFrameOverheadBytes;
    BitReader r(p);
    r.u(12);
    r.u(64);  // may run past the end: flagged, never read
    decoder.decode(p, kNow, corrections);
    check(corrections);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);
  Sink whole_sink;
  FrameReader whole(whole_sink);
  whole.feed(in);
  whole.finish();
  const FrameStats& s = whole.stats();
  gnssemu::fuzz::expect(s.frames == whole_sink.frames, "every good frame handed on");
  gnssemu::fuzz::expect(whole_sink.bytes + s.skipped_bytes == size, "every byte a frame's or skipped");

  Sink split_sink;
  FrameReader split(split_sink);
  const std::size_t cut = size == 0 ? 0 : data[0] % size;
  split.feed(in.first(cut));
  split.feed(in.subspan(cut));
  split.finish();
  gnssemu::fuzz::expect(split_sink.frames == whole_sink.frames && split_sink.bytes == whole_sink.bytes,
                        "a split stream gives the same frames");

  // The bytes as payloads, in chunks the input sizes: the decoder's fields
  // without a CRC in the way. A payload starting 0x43 0x4x is an MSM7 of GPS.
  Decoder dec;
  gnssemu::receiver::Corrections c;
  std::size_t at = 0;
  while (at < size) {
    const std::size_t n = std::min<std::size_t>(size - at, 8 + data[at] * 4u);
    dec.decode(in.subspan(at, n), kNow, c);
    check(c);
    at += n;
  }
  return 0;
}
