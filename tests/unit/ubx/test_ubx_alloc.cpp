// SPDX-License-Identifier: Apache-2.0
// The per-epoch path never allocates once buffers have capacity: encoding an
// epoch (RXM-RAWX and RXM-SFRBX of raw firmware too), answering configuration
// input, decoding input. This executable's
// global operator new counts calls (tests/support/alloc_counter).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "tests/support/alloc_counter.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

struct NullSink : DecoderSink {
  Device* r = nullptr;
  std::string* out = nullptr;
  std::size_t frames = 0;
  void on_ubx(const FrameView& f) override {
    ++frames;
    r->handle_ubx({}, f, 0.0, *out);
  }
  void on_nmea(std::string_view s) override {
    ++frames;
    r->handle_nmea({}, s, *out);
  }
};

class UbxAlloc : public ::testing::TestWithParam<Generation> {};

TEST_P(UbxAlloc, EpochEncodeConfigAndDecodeDoNotAllocate) {
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(GetParam());
  Device r(setup);
  // Every output message of the table on, at rate 1, on UART1 (the M9's
  // MON-RF and SEC-SIG included; what the generation lacks is not sent).
  for (const PeriodicMessage& m : kPeriodicMessages) r.config().set_message_rate(kPortUart1, m.id, 1);
  receiver::Fix fix = test::sample_fix();
  fix.num_sats = kMaxSatsInView;  // worst case: every slot, every system
  for (int i = 0; i < kMaxSatsInView; ++i) {
    fix.sats[static_cast<std::size_t>(i)] = fix.sats[static_cast<std::size_t>(i % 10)];
    fix.sats[static_cast<std::size_t>(i)].sat = SatId::from_index(i * (kNumSats / kMaxSatsInView));
  }
  // Host input: a CFG-MSG poll, a CFG-RATE, MON-VER poll, MON-RF poll, PUBX,41, some garbage.
  std::string input = "\x01\x02\x03";
  input += test::frame_bytes(msg::kCfgMsg, {0x01, 0x07});
  input += test::frame_bytes(msg::kCfgRate, {0xC8, 0, 1, 0, 0, 0});
  input += test::frame_bytes(msg::kMonVer, {});
  input += test::frame_bytes(msg::kMonRf, {});
  input += test::frame_bytes(msg::kCfgNav5, {});
  input += "$PUBX,41,1,0007,0003,9600,0*10\r\n";
  input += test::frame_bytes(msg::kCfgValset, {0, 1, 0, 0});

  std::string out;
  out.reserve(16 * kMaxEpochBytes);
  StreamDecoder decoder;
  NullSink sink;
  sink.r = &r;
  sink.out = &out;
  MessageList epoch;
  r.on_epoch(fix, 0.0);  // warm-up
  r.compose({}, epoch);
  decoder.feed(input, sink);
  out.clear();

  const long before = support::allocation_count();
  std::size_t bytes = 0;
  for (int e = 1; e <= 50; ++e) {
    out.clear();
    fix.t += 0.2;
    r.on_epoch(fix, 0.2 * e);
    r.compose({}, epoch);
    for (const MessageList::Message& m : epoch.messages()) bytes += m.protocol == Protocol::kUbx ? m.end - m.begin : 0;
    decoder.feed(input, sink);
  }
  EXPECT_EQ(support::allocation_count(), before);
  // Every message with 32 satellites was really encoded (the M9 has no NAV-SVINFO).
  EXPECT_GT(bytes, 50u * (GetParam() == Generation::kM8 ? 1200u : 850u));
  EXPECT_EQ(sink.frames, 51u * 7u);
}

// Raw-data firmware at 10 Hz with RXM-RAWX and RXM-SFRBX on: GPS, GLONASS,
// Galileo and BeiDou (GEOs with their D2 pages among them), every
// measurement slot filled, one minute after a minute's warm-up (every
// subframe, string, page and D2 page cycle sent at least once before).
TEST_P(UbxAlloc, RawxAndSfrbxAtTenHertzDoNotAllocate) {
  const orbit::NavData nav =
      orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz");
  const orbit::EphemerisStore store(nav.ephemerides);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2024, 1, 10, 2, 5, 0.0}) + 0.05;
  // Up to a quarter of the slots per system, in SatId order as RawEpoch has them.
  std::vector<const orbit::Ephemeris*> sats;
  std::array<int, 4> per_system{};
  const GnssSystem systems[4] = {GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo, GnssSystem::kBeiDou};
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    const auto sys = std::find(std::begin(systems), std::end(systems), sat.system) - std::begin(systems);
    if (sys == 4 || per_system[static_cast<std::size_t>(sys)] >= kMaxSatsInView / 4) continue;
    const orbit::Ephemeris* e = store.select(sat, t0);
    if (e == nullptr) continue;
    sats.push_back(e);
    ++per_system[static_cast<std::size_t>(sys)];
  }
  int geos = 0;
  for (const orbit::Ephemeris* e : sats) geos += is_beidou_geo(e->sat);
  ASSERT_GE(geos, 3);
  for (int n : per_system) ASSERT_GE(n, 20);

  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(GetParam());
  setup.raw_firmware = true;
  Device r(setup);
  std::string out;
  for (const MsgId id : {msg::kRxmRawx, msg::kRxmSfrbx}) {
    const std::uint8_t p[3] = {id.cls, id.id, 1};
    ASSERT_EQ(r.handle_ubx({}, FrameView{msg::kCfgMsg, p}, 0.0, out).reply, Reply::kAck);
  }
  const std::uint8_t rate[6] = {100, 0, 1, 0, 0, 0};  // measRate 100 ms, navRate 1, GPS time
  ASSERT_EQ(r.handle_ubx({}, FrameView{msg::kCfgRate, rate}, 0.0, out).reply, Reply::kAck);

  receiver::RawEpoch raw;
  raw.time_valid = true;
  raw.leap_seconds_valid = true;
  raw.num_meas = static_cast<int>(sats.size());
  for (std::size_t i = 0; i < sats.size(); ++i) {
    receiver::RawMeasurement& m = raw.meas[i];
    m.sat = sats[i]->sat;
    m.signal = *signal_of(m.sat.system, 0);
    m.glonass_channel = sats[i]->glo_channel;
    // GEO and IGSO about 120 ms away, the others about 70 ms.
    m.pseudorange_m = m.sat.system == GnssSystem::kBeiDou && m.sat.number <= 18 ? 3.7e7 : 2.2e7;
    m.carrier_phase_cycles = m.pseudorange_m / kL1Wavelength_m;
    m.cn0_dbhz = 40.0;
    m.pseudorange_valid = m.carrier_valid = m.half_cycle_resolved = true;
  }
  receiver::Fix fix = test::sample_fix();
  MessageList epoch;
  std::array<int, 8> sfrbx{};  // per gnssId
  int rawx = 0, geo_pages = 0;
  const auto run = [&](int first, int epochs) {
    for (int e = first; e < first + epochs; ++e) {
      raw.t_rx = t0 + 0.1 * e;
      for (int i = 0; i < raw.num_meas; ++i) raw.meas[static_cast<std::size_t>(i)].lock_time_s = 100.0 + 0.1 * e;
      fix.t = raw.t_rx;
      r.on_epoch(fix, 0.1 * e, RawSource{&raw, &store, {}});
      r.compose({}, epoch);
      for (const MessageList::Message& m : epoch.messages()) {
        const std::string_view f = epoch.bytes(m);
        if (m.protocol != Protocol::kUbx || f.size() < 8 || f[2] != 0x02) continue;
        rawx += f[3] == 0x15;
        if (f[3] != 0x13) continue;
        ++sfrbx[static_cast<std::size_t>(f[6]) & 7];
        geo_pages += f[6] == 3 && is_beidou_geo(SatId(GnssSystem::kBeiDou, static_cast<std::uint8_t>(f[7])));
      }
    }
  };
  run(0, 600);  // warm-up
  sfrbx = {};
  rawx = geo_pages = 0;
  const long before = support::allocation_count();
  run(600, 600);
  EXPECT_EQ(support::allocation_count(), before);
  EXPECT_EQ(rawx, 600);
  // A minute of each system's navigation data, per satellite: GPS subframes
  // 1-3 of two 30-s frames, GLONASS strings 1-5 of two 30-s frames (one
  // string may fall across the minute's ends), Galileo word types 0-6 of two
  // 30-s subframes, BeiDou D1 subframes 1-3 of two 30-s frames and a D2 page
  // of every 3-s frame of a GEO.
  EXPECT_GE(sfrbx[0], 6 * per_system[0]);  // gnssId 0 GPS
  EXPECT_GE(sfrbx[6], 9 * per_system[1]);  // 6 GLONASS
  EXPECT_GE(sfrbx[2], 14 * per_system[2]);  // 2 Galileo
  EXPECT_GE(geo_pages, 20 * geos);         // 3 BeiDou GEO (D2)
  EXPECT_GE(sfrbx[3] - geo_pages, 6 * (per_system[3] - geos));  // 3 BeiDou MEO and IGSO (D1)
}

INSTANTIATE_TEST_SUITE_P(Generations, UbxAlloc, ::testing::Values(Generation::kM8, Generation::kM9),
                         [](const ::testing::TestParamInfo<Generation>& p) { return std::string(generation_name(p.param)); });

TEST(UbxAlloc, ConfigInterfaceDoesNotAllocate) {
  // An M9: VALSET (a transaction and a transaction-less set on RAM+BBR), a
  // VALGET of every key (paged), a VALDEL, and their NAKs.
  DeviceSetup setup;
  setup.mon_ver = mon_ver_of(Generation::kM9);
  Device r(setup);
  const auto le = [](std::uint32_t v) {
    return std::vector<std::uint8_t>{static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                     static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
  };
  const auto cat = [](std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  std::string input;
  input += test::frame_bytes(msg::kCfgValset, cat(cat({1, 1, 1, 0}, le(0x30210001)), {0xC8, 0}));   // start: RATE-MEAS 200
  input += test::frame_bytes(msg::kCfgValset, cat(cat({1, 1, 3, 0}, le(0x20910007)), {1}));         // apply: NAV-PVT UART1 1
  input += test::frame_bytes(msg::kCfgValset, cat(cat({0, 3, 0, 0}, le(0x40520001)), le(9600)));    // RAM+BBR baud
  input += test::frame_bytes(msg::kCfgValset, cat(cat({0, 1, 0, 0}, le(0x20110021)), {1}));         // NAK: dynModel 1
  input += test::frame_bytes(msg::kCfgValget, cat({0, 0, 0, 0}, le(0x0FFFFFFF)));                   // every key, page 1
  input += test::frame_bytes(msg::kCfgValget, cat({0, 7, 64, 0}, le(0x0FFFFFFF)));                  // page 2, defaults
  input += test::frame_bytes(msg::kCfgValdel, cat({0, 2, 0, 0}, le(0x0091FFFF)));                   // every MSGOUT in BBR
  std::string out;
  out.reserve(64 * 1024);
  StreamDecoder decoder;
  NullSink sink;
  sink.r = &r;
  sink.out = &out;
  decoder.feed(input, sink);  // warm-up
  const long before = support::allocation_count();
  for (int i = 0; i < 20; ++i) {
    out.clear();
    decoder.feed(input, sink);
  }
  EXPECT_EQ(support::allocation_count(), before);
  EXPECT_EQ(sink.frames, 21u * 7u);
  EXPECT_GT(out.size(), 2u * 64u * 5u);  // the VALGET pages were really written
  EXPECT_EQ(r.config().rate.measRate, 200);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
