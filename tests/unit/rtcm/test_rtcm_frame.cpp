// SPDX-License-Identifier: Apache-2.0
// Frames and CRC-24Q against the frames verified in shared/reference/rtk-raw.md
// §2.1; the frame reader on split, corrupted and truncated input.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/protocol/rtcm/rtcm_station.hpp"

namespace gnssemu::protocol::rtcm {
namespace {

std::string hex(const std::string& s) {
  std::string h;
  char b[4];
  for (unsigned char c : s) {
    std::snprintf(b, sizeof b, "%02X ", c);
    h += b;
  }
  if (!h.empty()) h.pop_back();
  return h;
}

struct Collect : FrameSink {
  std::vector<int> numbers;
  void on_frame(std::span<const std::uint8_t> p) override { numbers.push_back(message_number(p)); }
};

std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(RtcmFrame, EmptyFrameMatchesVerifiedBytes) {
  std::string out;
  ASSERT_TRUE(append_frame({}, out));
  EXPECT_EQ(hex(out), "D3 00 00 47 EA 4B");
}

TEST(RtcmFrame, Station1005MatchesVerifiedBytes) {
  StationInfo st;
  st.station_id = 2003;
  st.arp_ecef_m = Ecef(1114104.5999, -4850729.7108, 3975521.4643);
  st.gps = true;  // the verified frame: GPS only
  std::string out;
  append_station(st, false, out);
  EXPECT_EQ(hex(out), "D3 00 13 3E D7 D3 02 02 98 0E DE EF 34 B4 BD 62 AC 09 41 98 6F 33 36 0B 98");
}

TEST(RtcmFrame, Station1006Is21Bytes) {
  StationInfo st;
  st.antenna_height_m = 1.2345;
  std::string out;
  append_station(st, true, out);
  ASSERT_EQ(out.size(), 21u + kFrameOverheadBytes);
  BitReader r(bytes(out).subspan(3, 21));
  EXPECT_EQ(r.u(12), 1006u);
  r.u(12 + 6 + 4 + 38 + 2 + 38 + 2 + 38);
  EXPECT_EQ(r.u(16), 12345u);
}

TEST(RtcmBits, SignedAndSignMagnitudeRoundTrip) {
  Payload buf;
  BitWriter w(buf);
  w.s(22, -123456);
  w.sm(27, -98765);
  w.u(38, 0x2ABCDEF012ull);
  w.s(38, -1);
  BitReader r(std::span<const std::uint8_t>(buf.data(), w.bytes()));
  EXPECT_EQ(r.s(22), -123456);
  EXPECT_EQ(r.sm(27), -98765);
  EXPECT_EQ(r.u(38), 0x2ABCDEF012ull);
  EXPECT_EQ(r.s(38), -1);
  EXPECT_FALSE(r.overrun());
  r.u(64);
  EXPECT_TRUE(r.overrun());
}

TEST(RtcmBits, WriterStopsAtItsBuffer) {
  std::array<std::uint8_t, 2> small{};
  BitWriter w(small);
  w.u(12, 0xFFF);
  w.u(8, 0xFF);
  EXPECT_TRUE(w.overflow());
  EXPECT_EQ(w.bits(), 12u);
}

TEST(RtcmReader, FramesSplitAnywhereAndGarbageBetween) {
  StationInfo st;
  std::string stream = "junk\xD3";
  append_station(st, false, stream);
  stream += "xx";
  append_glonass_biases(1, true, {0.0, std::nullopt, 0.0, std::nullopt}, stream);
  for (std::size_t cut = 0; cut < stream.size(); ++cut) {
    Collect c;
    FrameReader r(c);
    r.feed(bytes(stream).first(cut));
    r.feed(bytes(stream).subspan(cut));
    r.finish();
    ASSERT_EQ(c.numbers, (std::vector<int>{1005, 1230})) << "cut " << cut;
  }
}

TEST(RtcmReader, CorruptedAndTruncatedFramesAreCountedAndSkipped) {
  StationInfo st;
  std::string good;
  append_station(st, true, good);
  std::string bad = good;
  bad[10] = static_cast<char>(bad[10] ^ 0x40);
  const std::string cut = good.substr(0, 12);  // a frame cut short, then a whole one
  Collect c;
  FrameReader r(c);
  r.feed(bytes(bad + cut + good + good.substr(0, 5)));
  r.finish();
  EXPECT_EQ(c.numbers, (std::vector<int>{1006}));
  EXPECT_EQ(r.stats().frames, 1u);
  EXPECT_GE(r.stats().crc_errors, 2u);
  EXPECT_EQ(r.stats().truncated, 1u);
}

}  // namespace
}  // namespace gnssemu::protocol::rtcm
