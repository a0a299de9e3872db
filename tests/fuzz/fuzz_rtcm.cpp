// SPDX-License-Identifier: Apache-2.0
// RTCM 3 bytes from a host through the frame reader, whole and split at a
// point the input chooses. Oracles: every frame handed on has a payload of
// at most 1023 bytes and a good CRC; the counters account for every byte;
// the split makes no difference.
#include <cstdint>
#include <span>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu::protocol::rtcm;

struct Sink : FrameSink {
  std::uint64_t frames = 0, bytes = 0;
  void on_frame(std::span<const std::uint8_t> p) override {
    gnssemu::fuzz::expect(p.size() <= kMaxPayloadBytes, "payload within 1023 bytes");
    ++frames;
    bytes += p.size() + kFrameOverheadBytes;
    BitReader r(p);
    r.u(12);
    r.u(64);  // may run past the end: flagged, never read
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
  return 0;
}
