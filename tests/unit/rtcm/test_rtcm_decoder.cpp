// SPDX-License-Identifier: Apache-2.0
// The RTCM 3 decoder against our own encoders: RawEpoch -> MSM4/MSM7 ->
// Corrections.obs gives the same values within each field's resolution;
// 1005/1006, 1230 and 4072 into the station; epochs across several MSMs and
// systems; epoch times resolved per system; and bad input (inconsistent
// masks, unknown messages and signals, short payloads) counted, never used.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_decoder.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/protocol/rtcm/rtcm_msm.hpp"
#include "core/protocol/rtcm/rtcm_msm_fields.hpp"
#include "core/protocol/rtcm/rtcm_station.hpp"
#include "core/protocol/rtcm/rtcm_ublox.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::protocol::rtcm {
namespace decoder_test {

using receiver::Corrections;
using receiver::RawEpoch;
using receiver::RawMeasurement;

const time::GpsTime kNow(2300, 345600.7);

void add(RawEpoch& e, SatId sat, int band, double pr_m) {
  RawMeasurement& m = e.meas[static_cast<std::size_t>(e.num_meas++)];
  m.sat = sat;
  m.signal = *signal_of(sat.system, band);
  m.glonass_channel = sat.system == GnssSystem::kGlonass ? (sat.number % 14) - 7 : 0;
  const double lam = kSpeedOfLight_m_s / signal_carrier_hz(m.signal, m.glonass_channel);
  m.pseudorange_m = pr_m;
  m.carrier_phase_cycles = pr_m / lam + 0.25 + sat.number;
  m.doppler_hz = -(234.567 + sat.number) / lam;  // one range rate on every band
  m.cn0_dbhz = 43.3;
  m.lock_time_s = 100.0;
  m.pseudorange_valid = m.carrier_valid = m.half_cycle_resolved = true;
}

/// An epoch at a whole millisecond (the MSM time tag), nsat satellites of each system.
RawEpoch epoch_of(std::initializer_list<GnssSystem> systems, int nsat, int nband) {
  RawEpoch e;
  e.t_rx = time::GpsTime(2300, 345600.5);
  e.time_valid = true;
  for (GnssSystem sys : systems)
    for (int n = 1; n <= nsat; ++n)
      for (int b = 0; b < nband; ++b)
        if (signal_of(sys, b)) add(e, SatId(sys, n), b, 2.1e7 + n * 1.0e5 + 0.123 + b * 3.0);
  return e;
}

/// Every frame of bytes through the decoder.
struct Feed : FrameSink {
  Decoder& dec;
  Corrections& c;
  std::vector<DecodeResult> results;
  Feed(Decoder& d, Corrections& out) : dec(d), c(out) {}
  void on_frame(std::span<const std::uint8_t> p) override { results.push_back(dec.decode(p, kNow, c)); }
  void run(const std::string& s) {
    FrameReader r(*this);
    r.feed({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
  }
};

TEST(RtcmDecoder, Msm7AndMsm4RoundTripWithinResolution) {
  for (MsmKind kind : {MsmKind::kMsm4, MsmKind::kMsm7}) {
    const bool msm7 = kind == MsmKind::kMsm7;
    const MsmFields& f = msm_fields(static_cast<int>(kind));
    const RawEpoch e = epoch_of({GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo, GnssSystem::kBeiDou,
                                 GnssSystem::kQzss},
                                6, 2);
    MsmEncoder enc(77, kind);
    std::string out;
    enc.append_epoch(e, SystemSet::all(), out);
    Corrections c;
    Decoder dec;
    // MSM4 has no GLONASS channel: the receiver learns it elsewhere.
    for (int n = 1; n <= 6; ++n) dec.set_glonass_channel(n, (n % 14) - 7);
    Feed feed(dec, c);
    feed.run(out);
    ASSERT_EQ(feed.results.size(), 5u);
    EXPECT_TRUE(feed.results.back().epoch_complete);
    EXPECT_EQ(dec.stats().epochs, 1u);
    EXPECT_EQ(dec.stats().msm, 5u);
    ASSERT_TRUE(c.obs_valid);
    EXPECT_EQ(c.obs_station_id, 77);
    EXPECT_EQ(c.revision, 1u);
    EXPECT_NEAR(c.obs.t_rx - e.t_rx, 0.0, 1e-9);
    ASSERT_EQ(c.obs.num_meas, e.num_meas);
    const double psr_res_m = kMsmRangeMs_m * f.psr_unit_ms;
    const double phr_res_m = kMsmRangeMs_m * f.phr_unit_ms;
    for (int i = 0; i < e.num_meas; ++i) {
      const RawMeasurement& want = e.meas[static_cast<std::size_t>(i)];
      const RawMeasurement& got = c.obs.meas[static_cast<std::size_t>(i)];  // same SatId/band order
      SCOPED_TRACE(std::string(1, system_letter(want.sat.system)) + std::to_string(want.sat.number));
      ASSERT_EQ(got.sat, want.sat);
      EXPECT_EQ(got.signal, want.signal);
      EXPECT_EQ(got.glonass_channel, want.glonass_channel);
      EXPECT_TRUE(got.pseudorange_valid);
      EXPECT_TRUE(got.carrier_valid);
      EXPECT_NEAR(got.pseudorange_m, want.pseudorange_m, psr_res_m / 2 + 1e-6);
      const double lam = kSpeedOfLight_m_s / signal_carrier_hz(want.signal, want.glonass_channel);
      // The encoder takes a whole number of cycles off the phase (a new lock offset).
      const double dphi = got.carrier_phase_cycles - want.carrier_phase_cycles;
      EXPECT_NEAR((dphi - std::round(dphi)) * lam, 0.0, phr_res_m / 2 + 1e-6);
      EXPECT_NEAR(got.cn0_dbhz, want.cn0_dbhz, f.cnr_unit_dbhz / 2 + 1e-9);
      EXPECT_TRUE(got.half_cycle_resolved);
      EXPECT_LE(got.lock_time_s, want.lock_time_s);
      EXPECT_GT(got.lock_time_s, want.lock_time_s * 0.49);
      if (msm7) {
        EXPECT_NEAR(got.doppler_hz, want.doppler_hz, 1e-4 / lam / 2 + 1e-6);
      }
    }
  }
}

TEST(RtcmDecoder, Msm4GlonassWithoutChannelHasNoPhase) {
  const RawEpoch e = epoch_of({GnssSystem::kGlonass}, 3, 1);
  MsmEncoder enc(1, MsmKind::kMsm4);
  std::string out;
  enc.append_epoch(e, SystemSet::all(), out);
  Corrections c;
  Decoder dec;
  Feed(dec, c).run(out);
  ASSERT_EQ(c.obs.num_meas, 3);
  EXPECT_TRUE(c.obs.meas[0].pseudorange_valid);
  EXPECT_FALSE(c.obs.meas[0].carrier_valid);
}

TEST(RtcmDecoder, EpochSpansSplitMessagesAndCompletesOnTheLast) {
  const RawEpoch e = epoch_of({GnssSystem::kGalileo, GnssSystem::kBeiDou}, 36, 2);  // 72 cells each: split
  MsmEncoder enc(5, MsmKind::kMsm7);
  std::string out;
  const MsmEpochStats st = enc.append_epoch(e, SystemSet::all(), out);
  ASSERT_GT(st.messages, 2);
  Corrections c;
  Decoder dec;
  Feed feed(dec, c);
  feed.run(out);
  for (std::size_t i = 0; i + 1 < feed.results.size(); ++i) EXPECT_FALSE(feed.results[i].epoch_complete);
  EXPECT_TRUE(feed.results.back().epoch_complete);
  EXPECT_EQ(c.obs.num_meas, e.num_meas);
  EXPECT_EQ(dec.stats().unterminated_epochs, 0u);
  // The next epoch's first message arriving without the previous last: handed over anyway.
  std::string first_only(out.begin(), out.begin() + 6 + ((out[1] & 3) << 8 | static_cast<std::uint8_t>(out[2])));
  RawEpoch later = e;
  later.t_rx += 1.0;
  std::string next;
  enc.append_epoch(later, SystemSet::all(), next);
  Feed again(dec, c);
  again.run(first_only);
  again.run(next);
  EXPECT_EQ(dec.stats().unterminated_epochs, 1u);
  EXPECT_NEAR(c.obs.t_rx - later.t_rx, 0.0, 1e-6);
}

TEST(RtcmDecoder, EpochTimesPerSystem) {
  const time::GpsTime now(2300, 1.0);  // just after the week began
  // GPS tow late in the previous week.
  auto t = msm_epoch_time(GnssSystem::kGps, 604799000u, now, 18);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->week(), 2299);
  EXPECT_NEAR(t->tow_s(), 604799.0, 1e-9);
  // BeiDou: BDT 0.5 s of week = GPST 14.5 s.
  t = msm_epoch_time(GnssSystem::kBeiDou, 500u, now, 18);
  EXPECT_NEAR(*t - time::GpsTime(2300, 14.5), 0.0, 1e-9);
  // GLONASS: Sunday 03:00:00 Moscow = Sunday 00:00:00 UTC = GPS 18 s.
  t = msm_epoch_time(GnssSystem::kGlonass, 0u << 27 | 10800000u, now, 18);
  EXPECT_NEAR(*t - time::GpsTime(2300, 18.0), 0.0, 1e-9);
  // Day of week unknown (7): the nearest day.
  t = msm_epoch_time(GnssSystem::kGlonass, 7u << 27 | 10800000u, time::GpsTime(2300, 86400.0 * 3 + 5), 18);
  EXPECT_NEAR(*t - time::GpsTime(2300, 86400.0 * 3 + 18.0), 0.0, 1e-9);
  EXPECT_FALSE(msm_epoch_time(GnssSystem::kGps, 604800000u, now, 18));
}

TEST(RtcmDecoder, StationBiasesAnd4072) {
  std::string out;
  StationInfo st;
  st.station_id = 2003;
  st.arp_ecef_m = Ecef{1114104.5999, -4850729.7108, 3975521.4643};
  st.antenna_height_m = 1.2345;
  append_station(st, true, out);
  append_glonass_biases(2003, true, {0.5, std::nullopt, -1.24, std::nullopt}, out);
  Corrections c;
  Decoder dec;
  Feed feed(dec, c);
  feed.run(out);
  ASSERT_EQ(feed.results.size(), 2u);
  EXPECT_EQ(feed.results[0].message, 1006);
  EXPECT_EQ(feed.results[0].station_id, 2003);
  EXPECT_TRUE(feed.results[0].used);
  EXPECT_TRUE(c.station.position_valid);
  EXPECT_FALSE(c.station.moving);
  EXPECT_EQ(c.station.station_id, 2003);
  EXPECT_NEAR(c.station.arp_ecef_m.x, 1114104.5999, 1e-6);
  EXPECT_NEAR(c.station.arp_ecef_m.y, -4850729.7108, 1e-6);
  EXPECT_NEAR(c.station.arp_ecef_m.z, 3975521.4643, 1e-6);
  EXPECT_NEAR(c.station.antenna_height_m, 1.2345, 1e-6);
  EXPECT_TRUE(c.glonass_cpb_valid);
  EXPECT_TRUE(c.glonass_cpb_aligned);
  EXPECT_NEAR(c.glonass_cpb_m[0], 0.5, 1e-9);
  EXPECT_EQ(c.glonass_cpb_m[1], 0.0);
  EXPECT_NEAR(c.glonass_cpb_m[2], -1.24, 1e-9);

  // 4072.0 in our layout: a moving base with its position; a foreign 4072.1 is recognised.
  std::string mb;
  append_reference_pvt({12, 345600000u, Ecef{4e6, 5e5, 4.9e6}}, mb);
  const std::array<std::uint8_t, 5> sub1{0xFE, 0x80, 0x01, 0x12, 0x34};
  append_frame(sub1, mb);
  Feed f2(dec, c);
  f2.run(mb);
  ASSERT_EQ(f2.results.size(), 2u);
  EXPECT_EQ(f2.results[0].message, 4072);
  EXPECT_EQ(f2.results[0].subtype, 0);
  EXPECT_EQ(f2.results[0].station_id, 12);
  EXPECT_EQ(f2.results[1].subtype, 1);
  EXPECT_TRUE(c.station.moving);
  EXPECT_EQ(c.station.station_id, 12);
  EXPECT_NEAR(c.station.arp_ecef_m.z, 4.9e6, 1e-6);
  EXPECT_EQ(dec.stats().ublox_subtype[0], 1u);
  EXPECT_EQ(dec.stats().ublox_subtype[1], 1u);
}

/// One MSM7 frame of GPS with its payload, to edit.
std::vector<std::uint8_t> gps_msm7_payload() {
  const RawEpoch e = epoch_of({GnssSystem::kGps}, 4, 1);
  MsmEncoder enc(1, MsmKind::kMsm7);
  std::string out;
  enc.append_epoch(e, SystemSet::all(), out);
  return {out.begin() + 3, out.end() - 3};
}

// DF421 decides what a rover may do with GLONASS phase: aligned ranges need
// no bias (what a u-blox F9 base sends: no bias fields), unaligned ones need
// the biases, and without them cannot be used for GLONASS ambiguities.
TEST(RtcmDecoder, GlonassBiasIndicatorDecidesUsability) {
  struct Case {
    bool aligned;
    GlonassBiases biases;
    bool valid;
  };
  const Case cases[] = {
      {true, {}, true},
      {false, {}, false},
      {false, {2.5, std::nullopt, -3.0, std::nullopt}, true},
  };
  for (const Case& k : cases) {
    std::string out;
    append_glonass_biases(7, k.aligned, k.biases, out);
    Corrections c;
    c.glonass_cpb_m = {9.0, 9.0, 9.0, 9.0};
    Decoder dec;
    Feed feed(dec, c);
    feed.run(out);
    ASSERT_EQ(feed.results.size(), 1u);
    EXPECT_EQ(out.size(), 6u + 4u + (k.biases[0] ? 4u : 0u));  // frame + 32-bit head + 16 bits per bias
    EXPECT_EQ(c.glonass_cpb_aligned, k.aligned);
    EXPECT_EQ(c.glonass_cpb_valid, k.valid);
    EXPECT_EQ(c.glonass_cpb_m[0], k.biases[0].value_or(0.0));
    EXPECT_EQ(c.glonass_cpb_m[1], 0.0);
    EXPECT_EQ(c.glonass_cpb_m[2], k.biases[2].value_or(0.0));
  }
}

TEST(RtcmDecoder, BadInputIsCountedNeverUsed) {
  Corrections c;
  Decoder dec;
  // Unknown message number, ephemeris (known, not used), an empty payload.
  std::array<std::uint8_t, 4> unknown{0x3E, 0x70, 0, 0};  // 999
  EXPECT_FALSE(dec.decode(unknown, kNow, c).used);
  std::array<std::uint8_t, 4> eph{0x3F, 0xB0, 0, 0};      // 1019
  EXPECT_FALSE(dec.decode(eph, kNow, c).used);
  EXPECT_EQ(dec.decode({}, kNow, c).message, 0);
  EXPECT_EQ(dec.stats().unknown_messages, 2u);
  EXPECT_EQ(dec.stats().not_used, 1u);
  // A satellite mask bit more than the payload holds: dropped whole.
  std::vector<std::uint8_t> p = gps_msm7_payload();
  p[10] |= 0x01;  // a satellite of the mask's first bytes
  EXPECT_FALSE(dec.decode(p, kNow, c).used);
  EXPECT_EQ(dec.stats().bad_masks, 1u);
  // Truncated MSM and truncated 1005.
  p = gps_msm7_payload();
  p.resize(p.size() - 5);
  EXPECT_FALSE(dec.decode(p, kNow, c).used);
  EXPECT_EQ(dec.stats().bad_masks, 2u);
  std::array<std::uint8_t, 6> short1005{0x3E, 0xD7, 0xD3, 0, 0, 0};
  EXPECT_FALSE(dec.decode(short1005, kNow, c).used);
  EXPECT_EQ(dec.stats().truncated, 1u);
  EXPECT_FALSE(c.obs_valid);
  EXPECT_FALSE(c.station.position_valid);
  // The signal 1C (id 2) relabelled 1W (id 4), which the signal table does
  // not have: its cells are ignored and counted, the message still decodes.
  p = gps_msm7_payload();
  BitReader r(p);
  r.u(kMsmHeaderBits + 64);
  EXPECT_EQ(r.u(32), 1u << 30);  // 1C only
  auto flip = [&p](std::size_t bit) { p[bit / 8] = static_cast<std::uint8_t>(p[bit / 8] ^ (0x80u >> (bit % 8))); };
  flip(kMsmHeaderBits + 64 + 1);
  flip(kMsmHeaderBits + 64 + 3);
  EXPECT_TRUE(dec.decode(p, kNow, c).used);
  EXPECT_EQ(dec.stats().unknown_signals, 4u);
  EXPECT_EQ(c.obs.num_meas, 0);
}

TEST(RtcmDecoder, DecodingDoesNotAllocate) {
  const RawEpoch e = epoch_of({GnssSystem::kGps, GnssSystem::kGalileo}, 20, 2);
  MsmEncoder enc(1, MsmKind::kMsm7);
  std::string out;
  enc.append_epoch(e, SystemSet::all(), out);
  Corrections c;
  Decoder dec;
  struct Sink : FrameSink {
    Decoder* d;
    Corrections* c;
    void on_frame(std::span<const std::uint8_t> p) override { d->decode(p, kNow, *c); }
  } sink;
  sink.d = &dec;
  sink.c = &c;
  FrameReader reader(sink);
  const long before = support::allocation_count();
  for (int i = 0; i < 5; ++i) reader.feed({reinterpret_cast<const std::uint8_t*>(out.data()), out.size()});
  EXPECT_EQ(support::allocation_count(), before);
  EXPECT_EQ(dec.stats().epochs, 5u);
}

}  // namespace decoder_test
}  // namespace gnssemu::protocol::rtcm

namespace gnssemu::protocol::rtcm {
namespace decoder_real_test {

/// RTKLIB's str2str made MSM7 from a real NEO-M8T's RXM-RAWX (tests/data/README.md);
/// RTKLIB's convbin decodes the same file into the RINEX values below.
TEST(RtcmDecoderRealFile, Str2strMsm7OfANeoM8tAgreesWithConvbin) {
  std::ifstream f(std::string(GNSSEMU_TEST_DATA) + "/receiver-logs/ublox-neo-m8t-str2str.rtcm3", std::ios::binary);
  ASSERT_TRUE(f) << "missing test data";
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  receiver::Corrections c;
  Decoder dec;
  const time::GpsTime now = time::GpsTime::from_calendar({2017, 12, 28, 20, 56, 0.0});
  struct Sink : FrameSink {
    Decoder* d;
    receiver::Corrections* c;
    time::GpsTime now;
    std::vector<receiver::RawEpoch> epochs;
    void on_frame(std::span<const std::uint8_t> p) override {
      if (d->decode(p, now, *c).epoch_complete) epochs.push_back(c->obs);
    }
  } sink;
  sink.d = &dec;
  sink.c = &c;
  sink.now = now;
  FrameReader reader(sink);
  reader.feed({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
  reader.finish();
  EXPECT_EQ(reader.stats().crc_errors, 0u);
  EXPECT_EQ(dec.stats().bad_masks, 0u);
  ASSERT_EQ(sink.epochs.size(), 39u);  // convbin: 39 epochs
  const receiver::RawEpoch& first = sink.epochs.front();
  // convbin: "> 2017 12 28 20 56 03.9920000  0 10" (GPS time, leap seconds not applied).
  const time::GpsTime want_t = time::GpsTime::from_calendar({2017, 12, 28, 20, 56, 3.992});
  EXPECT_NEAR(first.t_rx - want_t, 0.0, 1e-6);
  ASSERT_EQ(first.num_meas, 10);
  struct Row {
    int prn;
    double c1c_m, l1c_cycles;
  };
  // convbin's C1C and L1C of the first epoch.
  const Row rows[] = {{4, 21478168.193, 112868689.207}, {10, 18209344.773, 95691379.586},
                      {32, 18191129.764, 95594454.382}};
  for (const Row& r : rows) {
    const receiver::RawMeasurement* m = nullptr;
    for (int i = 0; i < first.num_meas; ++i)
      if (first.meas[static_cast<std::size_t>(i)].sat == SatId(GnssSystem::kGps, r.prn)) m = &first.meas[static_cast<std::size_t>(i)];
    ASSERT_NE(m, nullptr) << "G" << r.prn;
    EXPECT_NEAR(m->pseudorange_m, r.c1c_m, 0.001) << "G" << r.prn;
    EXPECT_NEAR(m->carrier_phase_cycles, r.l1c_cycles, 0.001) << "G" << r.prn;
  }
}

}  // namespace decoder_real_test
}  // namespace gnssemu::protocol::rtcm
