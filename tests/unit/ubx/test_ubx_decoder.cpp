// SPDX-License-Identifier: Apache-2.0
// Stream decoder: UBX and NMEA interleaved with garbage, resync after false
// syncs, bad checksums and impossible lengths counted, bounded memory.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using test::frame_bytes;

struct Collect : DecoderSink {
  std::vector<test::Frame> ubx;
  std::vector<std::string> nmea;
  void on_ubx(const FrameView& f) override { ubx.push_back({f.id, {f.payload.begin(), f.payload.end()}}); }
  void on_nmea(std::string_view s) override { nmea.emplace_back(s); }
};

const std::string kPubx41 = "$PUBX,41,1,0007,0001,115200,0*1A\r\n";

TEST(UbxDecoder, Pubx41ChecksumIsRight) {
  // Independent XOR over "PUBX,41,1,0007,0001,115200,0".
  std::uint8_t x = 0;
  for (char c : std::string("PUBX,41,1,0007,0001,115200,0")) x ^= static_cast<std::uint8_t>(c);
  EXPECT_EQ(x, 0x1A);
}

TEST(UbxDecoder, InterleavedUbxNmeaAndGarbage) {
  const std::string a = frame_bytes(msg::kCfgPrt, {1});
  const std::string b = frame_bytes(msg::kMonVer, {});
  const std::string stream = "\x01\x02garbage" + a + "\xB5\xB5zz" + kPubx41 + "\r\n\x62" + b + "$GPGGA,junk";
  Collect c;
  StreamDecoder d;
  d.feed(stream, c);
  ASSERT_EQ(c.ubx.size(), 2u);
  EXPECT_EQ(c.ubx[0].id, msg::kCfgPrt);
  EXPECT_EQ(c.ubx[0].payload, std::vector<std::uint8_t>{1});
  EXPECT_EQ(c.ubx[1].id, msg::kMonVer);
  ASSERT_EQ(c.nmea.size(), 1u);
  EXPECT_EQ(c.nmea[0], "$PUBX,41,1,0007,0001,115200,0*1A");
  EXPECT_EQ(d.stats().ubx_frames, 2u);
  EXPECT_EQ(d.stats().nmea_sentences, 1u);
  EXPECT_EQ(d.pending_bytes(), 11u);  // "$GPGGA,junk" waits for its line end
  EXPECT_EQ(d.stats().garbage_bytes, 9u + 4u + 3u);
}

TEST(UbxDecoder, ByteByByteEqualsOneChunk) {
  const std::string stream = "xx" + frame_bytes(msg::kCfgRate, {0xE8, 0x03, 1, 0, 1, 0}) + kPubx41 +
                             frame_bytes(msg::kCfgMsg, {1, 7, 1});
  Collect whole, bytes;
  StreamDecoder d1, d2;
  d1.feed(stream, whole);
  for (char ch : stream) d2.feed(std::string_view(&ch, 1), bytes);
  ASSERT_EQ(whole.ubx.size(), 2u);
  ASSERT_EQ(bytes.ubx.size(), 2u);
  EXPECT_EQ(whole.ubx[1].payload, bytes.ubx[1].payload);
  EXPECT_EQ(whole.nmea, bytes.nmea);
}

TEST(UbxDecoder, BadChecksumRejectedAndFrameAfterItFound) {
  std::string bad = frame_bytes(msg::kCfgRate, {0xE8, 0x03, 1, 0, 1, 0});
  bad.back() = static_cast<char>(bad.back() ^ 0x55);
  const std::string good = frame_bytes(msg::kCfgNav5, std::vector<std::uint8_t>(36, 0));
  Collect c;
  StreamDecoder d;
  d.feed(bad + good, c);
  ASSERT_EQ(c.ubx.size(), 1u);
  EXPECT_EQ(c.ubx[0].id, msg::kCfgNav5);
  EXPECT_EQ(d.stats().ubx_bad_checksum, 1u);
}

TEST(UbxDecoder, FrameHiddenInsideAFalseFrameIsRecovered) {
  // A false sync whose length swallows a real frame: the rescan after the
  // checksum failure still finds the real one.
  const std::string real = frame_bytes(msg::kMonVer, {});
  std::string stream("\xB5\x62\x06\x00\x10\x00", 6);  // claims 16 bytes of payload
  stream += real;                                    // 8 bytes
  stream += std::string(10, 'q');                    // rest of the fake payload + fake checksum
  Collect c;
  StreamDecoder d;
  d.feed(stream, c);
  ASSERT_EQ(c.ubx.size(), 1u);
  EXPECT_EQ(c.ubx[0].id, msg::kMonVer);
  EXPECT_EQ(d.stats().ubx_bad_checksum, 1u);
}

TEST(UbxDecoder, ImpossibleLengthRejectedAtOnce) {
  const std::string stream = std::string("\xB5\x62\x06\x8A\xFF\xFF", 6) + frame_bytes(msg::kCfgRate, {});
  Collect c;
  StreamDecoder d;
  d.feed(stream, c);
  EXPECT_EQ(d.stats().ubx_bad_length, 1u);
  ASSERT_EQ(c.ubx.size(), 1u);
  EXPECT_EQ(c.ubx[0].id, msg::kCfgRate);
}

TEST(UbxDecoder, MaximumLengthFrameAccepted) {
  std::vector<std::uint8_t> payload(kMaxPayloadBytes);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(i * 7);
  Collect c;
  StreamDecoder d;
  d.feed(frame_bytes(msg::kCfgValset, payload) + frame_bytes(msg::kMonVer, {}), c);
  ASSERT_EQ(c.ubx.size(), 2u);
  EXPECT_EQ(c.ubx[0].payload, payload);
  // One byte more is refused as impossible.
  payload.push_back(0);
  StreamDecoder d2;
  Collect c2;
  d2.feed(frame_bytes(msg::kCfgValset, payload), c2);
  EXPECT_TRUE(c2.ubx.empty());
  EXPECT_EQ(d2.stats().ubx_bad_length, 1u);
}

TEST(UbxDecoder, TruncatedFrameWaitsThenIdleResyncs) {
  const std::string f = frame_bytes(msg::kCfgPrt, std::vector<std::uint8_t>(20, 1));
  Collect c;
  StreamDecoder d;
  d.feed(std::string_view(f).substr(0, 10), c);
  EXPECT_TRUE(c.ubx.empty());
  EXPECT_EQ(d.pending_bytes(), 10u);
  // Garbage header announcing 900 bytes, then the host's real command.
  const std::string stuck = std::string("\xB5\x62\x06\x00\x84\x03", 6) + frame_bytes(msg::kMonVer, {});
  StreamDecoder d2;
  Collect c2;
  d2.feed(stuck, c2);
  EXPECT_TRUE(c2.ubx.empty());  // swallowed while the fake frame is pending
  d2.on_idle(c2);
  ASSERT_EQ(c2.ubx.size(), 1u);
  EXPECT_EQ(c2.ubx[0].id, msg::kMonVer);
  EXPECT_EQ(d2.stats().idle_resyncs, 1u);
  EXPECT_EQ(d2.pending_bytes(), 0u);
}

TEST(UbxDecoder, NmeaRejections) {
  Collect c;
  StreamDecoder d;
  d.feed(std::string("$PUBX,41,1,0007,0001,115200,0*1B\r\n"), c);  // wrong checksum
  d.feed(std::string("$PUBX,41,1,0007,0001,115200,0\r\n"), c);     // no checksum
  d.feed("$" + std::string(200, 'A') + "*00\r\n", c);               // too long
  d.feed(std::string("$PUB\x01X*00\r\n"), c);                       // control character
  d.feed(kPubx41, c);
  ASSERT_EQ(c.nmea.size(), 1u);
  EXPECT_EQ(d.stats().nmea_bad_checksum, 1u);
  EXPECT_EQ(d.stats().nmea_no_checksum, 1u);
  EXPECT_EQ(d.stats().nmea_too_long, 1u);
  EXPECT_EQ(d.stats().nmea_bad_char, 1u);
}

TEST(UbxDecoder, FuzzRandomGarbageWithEmbeddedFramesFindsEveryFrame) {
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> gap(0, 300);
  std::uniform_int_distribution<int> len(0, 120);
  std::string stream;
  std::vector<std::vector<std::uint8_t>> sent;
  for (int k = 0; k < 400; ++k) {
    const int g = gap(rng);
    for (int i = 0; i < g; ++i) {
      int b = byte(rng);
      if (b == 0xB5 && (i % 3 == 0)) b = 0x62;  // keep some false syncs, not too many
      stream.push_back(static_cast<char>(b));
    }
    std::vector<std::uint8_t> payload(static_cast<std::size_t>(len(rng)));
    for (auto& v : payload) v = static_cast<std::uint8_t>(byte(rng));
    payload.insert(payload.begin(), {static_cast<std::uint8_t>(k & 0xFF), static_cast<std::uint8_t>(k >> 8)});
    sent.push_back(payload);
    stream += frame_bytes(MsgId{0x06, 0x01}, payload);
  }
  Collect c;
  StreamDecoder d;
  // Feed in random chunks.
  std::size_t pos = 0;
  while (pos < stream.size()) {
    const std::size_t n = std::min<std::size_t>(stream.size() - pos, static_cast<std::size_t>(1 + gap(rng)));
    d.feed(std::string_view(stream).substr(pos, n), c);
    pos += n;
    EXPECT_LE(d.pending_bytes(), kMaxPayloadBytes + kFrameOverheadBytes);
  }
  d.on_idle(c);
  for (int i = 0; i < 3 && d.pending_bytes() > 0; ++i) d.on_idle(c);
  // Every sent frame arrives, in order (random garbage may add a rare
  // extra frame that happens to check out, but none is lost).
  std::size_t found = 0;
  for (const auto& f : c.ubx) {
    if (found < sent.size() && f.payload == sent[found]) ++found;
  }
  EXPECT_EQ(found, sent.size());
  EXPECT_LE(c.ubx.size(), sent.size() + 2);
}

TEST(UbxDecoder, PureGarbageNeverEmitsAndStaysBounded) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string stream(200000, '\0');
  for (auto& ch : stream) ch = static_cast<char>(byte(rng));
  for (std::size_t i = 0; i + 1 < stream.size(); i += 97) {  // plenty of false syncs
    stream[i] = '\xB5';
    stream[i + 1] = '\x62';
  }
  Collect c;
  StreamDecoder d;
  d.feed(stream, c);
  EXPECT_LE(d.pending_bytes(), kMaxPayloadBytes + kFrameOverheadBytes);
  // A random 16-bit checksum matches about once per 65536 candidate frames:
  // allow a handful, never many.
  EXPECT_LE(c.ubx.size(), 3u);
  EXPECT_GT(d.stats().ubx_bad_checksum + d.stats().ubx_bad_length, 1500u);
  EXPECT_EQ(d.stats().garbage_bytes + d.pending_bytes() +
                [&] { std::size_t n = 0; for (auto& f : c.ubx) n += f.payload.size() + 8; return n; }() +
                [&] { std::size_t n = 0; for (auto& s : c.nmea) n += s.size() + 1; return n; }(),
            stream.size());
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
