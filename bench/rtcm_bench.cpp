// SPDX-License-Identifier: Apache-2.0
// rtcm_bench: the base station's RTCM 3 observation stream at its heaviest:
// MSM7 (and MSM4) for 40 satellites on 2 signals (12 GPS, 8 GLONASS, 10
// Galileo, 10 BeiDou) at 10 Hz, plus 1005 every 10 s. Bytes per second
// against a UART's budget (115200 baud 8N1 = 11520 bytes/s; a real base then
// drops epochs or needs a faster line), encode time per epoch and heap
// allocations per epoch. Prints figures.
//   rtcm_bench [epochs]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/common/constants.hpp"
#include "core/protocol/rtcm/rtcm_msm.hpp"
#include "core/protocol/rtcm/rtcm_station.hpp"
#include "tests/support/alloc_counter.hpp"

namespace {

using namespace gnssemu;
namespace rtcm = protocol::rtcm;

receiver::RawEpoch busy_epoch() {
  receiver::RawEpoch e;
  e.t_rx = time::GpsTime(2296, 302400.0);
  e.time_valid = true;
  const std::pair<GnssSystem, int> kSky[] = {
      {GnssSystem::kGps, 12}, {GnssSystem::kGlonass, 8}, {GnssSystem::kGalileo, 10}, {GnssSystem::kBeiDou, 10}};
  for (const auto& [sys, count] : kSky) {
    for (int n = 1; n <= count; ++n) {
      for (int band = 0; band < kNumBands; ++band) {
        receiver::RawMeasurement& m = e.meas[static_cast<std::size_t>(e.num_meas++)];
        m.sat = SatId(sys, n + 2);
        m.signal = *signal_of(sys, band);
        m.glonass_channel = sys == GnssSystem::kGlonass ? n - 4 : 0;
        m.pseudorange_m = 2.0e7 + 1.7e5 * n + 1.3 * band;
        m.carrier_phase_cycles = m.pseudorange_m / (kSpeedOfLight_m_s / signal_carrier_hz(m.signal, m.glonass_channel));
        m.doppler_hz = 250.0 * n - 1500.0;
        m.cn0_dbhz = 35.0 + n;
        m.lock_time_s = 60.0;
        m.pseudorange_valid = m.carrier_valid = m.half_cycle_resolved = true;
      }
    }
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  const int epochs = argc > 1 ? std::atoi(argv[1]) : 20000;
  constexpr double kRateHz = 10.0;
  constexpr double kUartBytesPerS = 115200.0 / 10.0;  // 8N1: 10 bits a byte
  std::printf("rtcm_bench: 40 satellites x 2 signals, %g Hz, %d epochs, 1005 every 10 s\n", kRateHz, epochs);
  for (const rtcm::MsmKind kind : {rtcm::MsmKind::kMsm7, rtcm::MsmKind::kMsm4}) {
    receiver::RawEpoch e = busy_epoch();
    rtcm::MsmEncoder enc(1, kind);
    rtcm::StationInfo st;
    st.arp_ecef_m = Ecef(4201000.0, 168000.0, 4780000.0);
    std::string out;
    out.reserve(16384);
    std::size_t bytes = 0;
    int messages = 0;
    enc.append_epoch(e, SystemSet::all(), out);  // warm-up
    const long allocs_before = support::allocation_count();
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < epochs; ++k) {
      out.clear();
      e.t_rx += 1.0 / kRateHz;
      for (int i = 0; i < e.num_meas; ++i) {
        e.meas[static_cast<std::size_t>(i)].lock_time_s += 1.0 / kRateHz;
        e.meas[static_cast<std::size_t>(i)].pseudorange_m += 0.01;
      }
      if (k % 100 == 0) rtcm::append_station(st, false, out);
      messages += enc.append_epoch(e, SystemSet::all(), out).messages;
      bytes += out.size();
    }
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const long allocs = support::allocation_count() - allocs_before;
    const double bytes_per_s = static_cast<double>(bytes) / epochs * kRateHz;
    std::printf("  MSM%d: %.0f bytes/epoch in %.1f messages, %.0f bytes/s = %.0f %% of 115200 baud (%s); "
                "encode %.2f us/epoch; %ld allocations\n",
                static_cast<int>(kind), static_cast<double>(bytes) / epochs, static_cast<double>(messages) / epochs,
                bytes_per_s, 100.0 * bytes_per_s / kUartBytesPerS,
                bytes_per_s <= kUartBytesPerS ? "fits" : "does NOT fit: a base drops epochs or needs 230400 baud",
                wall_s / epochs * 1e6, allocs);
  }
  return 0;
}
