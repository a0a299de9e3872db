// SPDX-License-Identifier: Apache-2.0
// RXM-RAWX around a jammer episode, as the daemon sends it (pipeline with a
// fault stage, then the RAWX encoder): before, every satellite with
// trkStat prValid|cpValid|halfCyc and a growing locktime; while the jammer
// holds C/N0 under the tracking threshold, no entries; after, each back with
// locktime 0 and halfCyc clear (a new lock), halfCyc again once the next
// subframe preamble passed (docs/raw-output.md "Faults and the carrier").
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/faults/fault_event.hpp"
#include "core/faults/interference.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/protocol/ubx/wire/ubx_rxm.hpp"

namespace gnssemu::rawx_fault_lock_test {
namespace {

struct Entry {
  int prn = 0;
  int locktime_ms = 0;
  int trk_stat = 0;
};

// GPS entries of one encoded RAWX (frame: 6 header bytes, then the payload).
std::vector<Entry> gps_entries(const receiver::RawEpoch& raw) {
  std::string out;
  std::vector<Entry> v;
  if (protocol::ubx::rxm_rawx(raw, protocol::ubx::Generation::kM8, out) == 0) return v;
  const std::size_t p = 6;
  const int n = static_cast<unsigned char>(out[p + 11]);
  for (int i = 0; i < n; ++i) {
    const std::size_t b = p + protocol::ubx::kRawxHeaderBytes + protocol::ubx::kRawxMeasBytes * static_cast<std::size_t>(i);
    if (out[b + 20] != 0) continue;
    std::uint16_t lock = 0;
    std::memcpy(&lock, out.data() + b + 24, sizeof lock);
    v.push_back({static_cast<unsigned char>(out[b + 21]), lock, static_cast<unsigned char>(out[b + 30])});
  }
  return v;
}

TEST(RawxFaultLock, JammerEpisodeClearsAndRestartsLocktimeAndHalfCycle) {
  static const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  pipeline::Pipeline rx(store, pipeline::PipelineConfig{});
  // 50 dB over the nominal signal, wideband: ~25 dB off every C/A C/N0, under the 25 dB-Hz floor.
  faults::FaultEvent jam = faults::FaultEvent::of(faults::FaultType::kJammer, 70.0, 30.0, 0);
  jam.put(faults::Param::kJsDb, 50.0);
  rx.set_faults(std::vector<faults::FaultEvent>{jam});
  world::Truth truth;
  truth.pos_m = geo::ecef_from_lla(Lla{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0});
  truth.valid = true;
  const time::GpsTime t0 = store.first_valid() + 8.0 * 3600.0;
  const auto step = [&](int s) {
    truth.t = t0 + static_cast<double>(s);
    rx.step(truth.t, truth);
    return gps_entries(rx.receiver().raw());
  };
  std::vector<Entry> before;
  for (int s = 0; s < 70; ++s) before = step(s);
  ASSERT_GE(before.size(), 5u);
  for (const Entry& e : before) {
    // prValid, cpValid, halfCyc; subHalfCyc (0x08) where the loop locked on the inverted sign.
    EXPECT_EQ(e.trk_stat & 0x07, 0x07) << e.prn;
    EXPECT_GT(e.locktime_ms, 30000) << e.prn;
  }
  for (int s = 70; s < 100; ++s) EXPECT_TRUE(step(s).empty()) << s;
  std::vector<int> back_at(before.size(), -1), resolved_at(before.size(), -1);
  for (int s = 100; s < 130; ++s) {
    const std::vector<Entry> now = step(s);
    for (std::size_t i = 0; i < before.size(); ++i) {
      for (const Entry& e : now) {
        if (e.prn != before[i].prn) continue;
        if (back_at[i] < 0) {
          back_at[i] = s;
          EXPECT_EQ(e.locktime_ms, 0) << e.prn;
          EXPECT_EQ(e.trk_stat, 0x03) << e.prn;  // prValid, cpValid; half cycle not yet known
        } else {
          EXPECT_EQ(e.locktime_ms, (s - back_at[i]) * 1000) << e.prn;
          if (resolved_at[i] < 0 && (e.trk_stat & 0x07) == 0x07) resolved_at[i] = s;
        }
      }
    }
  }
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_GE(back_at[i], 100) << before[i].prn;
    // The next 6 s subframe preamble resolves the half cycle.
    EXPECT_GT(resolved_at[i], back_at[i]) << before[i].prn;
    EXPECT_LE(resolved_at[i], back_at[i] + 7) << before[i].prn;
  }
}

}  // namespace
}  // namespace gnssemu::rawx_fault_lock_test
