// SPDX-License-Identifier: Apache-2.0
// MSM4/MSM7 from a RawEpoch: message numbers, the multiple-message bit,
// splitting beyond 64 cells, lock indicators (RTCM 10403.3 Tables 3.5-74/76 as
// rtk-raw.md §2.4 states them), values back within the fields' resolution,
// and no allocation per epoch. RTKLIB's own decoding is the integration test
// tests/integration/wire/rtcm_rtklib_integration.py.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"
#include "core/protocol/rtcm/rtcm_msm.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::protocol::rtcm {
namespace {

using receiver::RawEpoch;
using receiver::RawMeasurement;

constexpr double kRangeMs_m = kSpeedOfLight_m_s * 1e-3;

void add(RawEpoch& e, SatId sat, int band, double pr_m) {
  RawMeasurement& m = e.meas[static_cast<std::size_t>(e.num_meas++)];
  m.sat = sat;
  m.signal = *signal_of(sat.system, band);
  m.glonass_channel = sat.system == GnssSystem::kGlonass ? (sat.number % 14) - 7 : 0;
  const double lam = kSpeedOfLight_m_s / signal_carrier_hz(m.signal, m.glonass_channel);
  m.pseudorange_m = pr_m;
  m.carrier_phase_cycles = pr_m / lam + 123456.0 + 0.25;
  m.doppler_hz = -1234.567;
  m.cn0_dbhz = 43.3;
  m.lock_time_s = 100.0;
  m.pseudorange_valid = m.carrier_valid = m.half_cycle_resolved = true;
}

RawEpoch epoch_of(GnssSystem sys, int nsat, int nband) {
  RawEpoch e;
  e.t_rx = time::GpsTime(2300, 345600.5);
  e.time_valid = true;
  for (int n = 1; n <= nsat; ++n)
    for (int b = 0; b < nband; ++b) add(e, SatId(sys, n), b, 2.1e7 + n * 1.0e5 + 0.123 + b * 3.0);
  return e;
}

struct Msm {
  int number = 0;
  bool more = false;
  std::uint32_t epoch = 0;
  int nsat = 0, nsig = 0, ncell = 0;
  std::vector<double> pr_m;  ///< per cell, reconstructed
};

/// Splits frames and decodes the header and the pseudoranges of an MSM.
std::vector<Msm> decode(const std::string& s) {
  std::vector<Msm> out;
  struct Sink : FrameSink {
    std::vector<std::vector<std::uint8_t>> p;
    void on_frame(std::span<const std::uint8_t> b) override { p.emplace_back(b.begin(), b.end()); }
  } sink;
  FrameReader r(sink);
  r.feed({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
  for (const auto& p : sink.p) {
    BitReader b(p);
    Msm m;
    m.number = static_cast<int>(b.u(12));
    b.u(12);
    m.epoch = static_cast<std::uint32_t>(b.u(30));
    m.more = b.u(1) != 0;
    b.u(3 + 7 + 2 + 2 + 1 + 3);
    const std::uint64_t sats = b.u(64);
    const auto sigs = static_cast<std::uint32_t>(b.u(32));
    m.nsat = std::popcount(sats);
    m.nsig = std::popcount(sigs);
    for (int i = 0; i < m.nsat * m.nsig; ++i) m.ncell += static_cast<int>(b.u(1));
    const bool msm7 = m.number % 10 == 7;
    std::vector<double> rough(static_cast<std::size_t>(m.nsat));
    for (auto& r8 : rough) r8 = static_cast<double>(b.u(8));
    if (msm7) b.u(4 * m.nsat);
    for (auto& r10 : rough) r10 += static_cast<double>(b.u(10)) / 1024.0;
    if (msm7) b.u(14 * m.nsat);
    // Every satellite has every signal here: cells in satellite-major order.
    for (int c = 0; c < m.ncell; ++c) {
      const double fine = msm7 ? static_cast<double>(b.s(20)) * std::ldexp(1.0, -29) : static_cast<double>(b.s(15)) * std::ldexp(1.0, -24);
      m.pr_m.push_back((rough[static_cast<std::size_t>(c / m.nsig)] + fine) * kRangeMs_m);
    }
    out.push_back(m);
  }
  return out;
}

TEST(RtcmMsm, LockIndicatorsFollowTheTables) {
  EXPECT_EQ(msm4_lock_indicator(0.0), 0);
  EXPECT_EQ(msm4_lock_indicator(0.031), 0);
  EXPECT_EQ(msm4_lock_indicator(0.032), 1);
  EXPECT_EQ(msm4_lock_indicator(1.0), 5);
  EXPECT_EQ(msm4_lock_indicator(524.287), 14);
  EXPECT_EQ(msm4_lock_indicator(600.0), 15);
  EXPECT_EQ(msm7_lock_indicator(0.050), 50);
  EXPECT_EQ(msm7_lock_indicator(0.100), 82);   // (100 + 64) / 2
  EXPECT_EQ(msm7_lock_indicator(1.0), 190);    // (1000 + 2048) / 16
  EXPECT_EQ(msm7_lock_indicator(70000.0), 704);
  // Decoding DF407 (t = 2^n i - n 2^(n+5)) gives back at most the lock time.
  for (double t : {0.07, 0.9, 3.3, 77.0, 5000.0}) {
    const int i = msm7_lock_indicator(t);
    const int n = i / 32 - 1;
    const double back_ms = n <= 0 ? i : std::ldexp(1.0, n) * i - n * std::ldexp(1.0, n + 5);
    EXPECT_LE(back_ms, t * 1e3 + 1e-9);
    EXPECT_GT(back_ms, t * 1e3 * 0.49);
  }
}

TEST(RtcmMsm, MessageNumbersAndSatelliteIds) {
  EXPECT_EQ(msm_message_number(GnssSystem::kGps, MsmKind::kMsm4), 1074);
  EXPECT_EQ(msm_message_number(GnssSystem::kGlonass, MsmKind::kMsm7), 1087);
  EXPECT_EQ(msm_message_number(GnssSystem::kGalileo, MsmKind::kMsm7), 1097);
  EXPECT_EQ(msm_message_number(GnssSystem::kQzss, MsmKind::kMsm4), 1114);
  EXPECT_EQ(msm_message_number(GnssSystem::kBeiDou, MsmKind::kMsm7), 1127);
  EXPECT_EQ(msm_satellite_id(SatId(GnssSystem::kQzss, 1)), 1);   // PRN 193
  EXPECT_EQ(msm_satellite_id(SatId(GnssSystem::kSbas, 20)), 1);  // PRN 120
  EXPECT_EQ(msm_satellite_id(SatId(GnssSystem::kBeiDou, 60)), 60);
}

TEST(RtcmMsm, PseudorangesBackWithinFieldResolution) {
  for (MsmKind kind : {MsmKind::kMsm4, MsmKind::kMsm7}) {
    MsmEncoder enc(7, kind);
    const RawEpoch e = epoch_of(GnssSystem::kGps, 8, 2);
    std::string out;
    enc.append_epoch(e, SystemSet::all(), out);
    const auto msgs = decode(out);
    ASSERT_EQ(msgs.size(), 1u);
    EXPECT_FALSE(msgs[0].more);
    EXPECT_EQ(msgs[0].epoch, 345600500u);
    ASSERT_EQ(msgs[0].ncell, 16);
    const double res_m = kRangeMs_m * std::ldexp(1.0, kind == MsmKind::kMsm7 ? -29 : -24);
    for (int c = 0; c < 16; ++c)
      EXPECT_NEAR(msgs[0].pr_m[static_cast<std::size_t>(c)], e.meas[static_cast<std::size_t>(c)].pseudorange_m, res_m / 2 + 1e-9);
  }
}

TEST(RtcmMsm, SplitsBeyond64CellsAndSetsTheMultipleMessageBit) {
  RawEpoch e = epoch_of(GnssSystem::kBeiDou, 40, 2);  // 80 cells: two BeiDou messages
  RawEpoch gps = epoch_of(GnssSystem::kGps, 3, 1);
  // GPS first, in SatId order.
  RawEpoch both = gps;
  for (int i = 0; i < e.num_meas; ++i) both.meas[static_cast<std::size_t>(both.num_meas++)] = e.meas[static_cast<std::size_t>(i)];
  MsmEncoder enc(1, MsmKind::kMsm7);
  std::string out;
  const MsmEpochStats st = enc.append_epoch(both, SystemSet::all(), out);
  EXPECT_EQ(st.messages, 3);
  EXPECT_EQ(st.cells, 83);
  const auto msgs = decode(out);
  ASSERT_EQ(msgs.size(), 3u);
  EXPECT_EQ(msgs[0].number, 1077);
  EXPECT_EQ(msgs[1].number, 1127);
  EXPECT_EQ(msgs[2].number, 1127);
  EXPECT_TRUE(msgs[0].more);
  EXPECT_TRUE(msgs[1].more);
  EXPECT_FALSE(msgs[2].more);
  EXPECT_EQ(msgs[1].nsat + msgs[2].nsat, 40);
  EXPECT_LE(msgs[1].nsat * msgs[1].nsig, 64);
  EXPECT_EQ(msgs[1].epoch, 345586500u);  // BDT = GPST - 14 s
  // Only the systems asked for.
  std::string gps_only;
  EXPECT_EQ(enc.append_epoch(both, SystemSet::only(GnssSystem::kGps), gps_only).messages, 1);
}

TEST(RtcmMsm, GlonassEpochIsDayOfWeekAndMoscowTimeOfDay) {
  RawEpoch e = epoch_of(GnssSystem::kGlonass, 2, 1);
  e.leap_seconds = 18;
  MsmEncoder enc(1, MsmKind::kMsm4);
  std::string out;
  enc.append_epoch(e, SystemSet::all(), out);
  const auto msgs = decode(out);
  ASSERT_EQ(msgs.size(), 1u);
  // GPS tow 345600.5 = Thursday 00:00:00.5; UTC 23:59:42.5 Wed; +3 h = Thu 02:59:42.5.
  EXPECT_EQ(msgs[0].epoch >> 27, 4u);
  EXPECT_EQ(msgs[0].epoch & ((1u << 27) - 1), 10782500u);
}

TEST(RtcmMsm, EpochDoesNotAllocate) {
  RawEpoch e = epoch_of(GnssSystem::kBeiDou, 40, 2);
  MsmEncoder enc(1, MsmKind::kMsm7);
  std::string out;
  out.reserve(8192);
  enc.append_epoch(e, SystemSet::all(), out);
  out.clear();
  const long before = support::allocation_count();
  for (int i = 0; i < 10; ++i) {
    e.t_rx += 0.1;
    enc.append_epoch(e, SystemSet::all(), out);
    out.clear();
  }
  EXPECT_EQ(support::allocation_count(), before);
}

TEST(RtcmMsm, InvalidTimeSendsNothing) {
  RawEpoch e = epoch_of(GnssSystem::kGps, 4, 1);
  e.time_valid = false;
  MsmEncoder enc(1, MsmKind::kMsm4);
  std::string out;
  EXPECT_EQ(enc.append_epoch(e, SystemSet::all(), out).messages, 0);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace gnssemu::protocol::rtcm
