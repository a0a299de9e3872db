// SPDX-License-Identifier: Apache-2.0
#pragma once
// Raw measurements: what the receiver's tracking loops report per satellite
// and signal at one epoch, on its own clock — the content of UBX RXM-RAWX,
// a RINEX 3 observation epoch and an RTCM 3 MSM (shared/reference/rtk-raw.md
// §1.1, §1.2, §2.4). Plain data, filled by Receiver::step; the protocol
// encoders only scale it.
#include <array>
#include <cstdint>

#include "core/common/gnss_signals.hpp"
#include "core/common/sat_id.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::receiver {

/// Most measurements in one epoch: every satellite in view on both bands.
inline constexpr int kMaxRawMeasurements = kMaxSatsInView * kNumBands;

/// One satellite's signal as the loops track it.
struct RawMeasurement {
  SatId sat;
  SignalId signal = SignalId::kGpsL1CA;
  int glonass_channel = 0;            ///< FDMA channel k (-7..6); 0 for other systems
  double pseudorange_m = 0.0;         ///< code pseudorange on the receiver's clock, m (RAWX prMes)
  /// Accumulated carrier phase, cycles of the signal's carrier, same sign as
  /// the pseudorange; an arbitrary integer per lock, plus half a cycle while
  /// a Costas loop on the inverted data sign is unresolved (RAWX cpMes).
  double carrier_phase_cycles = 0.0;
  double doppler_hz = 0.0;            ///< Hz, positive when approaching (RAWX doMes)
  double cn0_dbhz = 0.0;              ///< dB-Hz
  /// Time the carrier has been tracked without a discontinuity, s (>= 0;
  /// 0 at a new lock or a slip: RAWX locktime, RINEX LLI, MSM DF402).
  double lock_time_s = 0.0;
  double pseudorange_sigma_m = 0.0;   ///< 1-sigma code noise the loop estimates, m
  double carrier_sigma_cycles = 0.0;  ///< 1-sigma phase noise, cycles
  double doppler_sigma_hz = 0.0;      ///< 1-sigma Doppler noise, Hz
  bool pseudorange_valid = false;     ///< trkStat prValid
  bool carrier_valid = false;         ///< trkStat cpValid: the phase is continuous since lock_time_s began
  /// The half-cycle ambiguity of the Costas loop is resolved (the data
  /// preamble found): trkStat halfCyc; false sets RINEX LLI bit 1.
  bool half_cycle_resolved = false;
  /// Half a cycle was subtracted from the phase when it was resolved (trkStat subHalfCyc).
  bool half_cycle_subtracted = false;
};

/// Every measurement of one epoch.
struct RawEpoch {
  /// Receive time of the measurements on the receiver's clock (RAWX rcvTow and
  /// week; RINEX epoch): true GPS time plus the receiver's clock bias.
  time::GpsTime t_rx;
  bool time_valid = false;            ///< the receiver knows GPS time (else nothing is reported)
  int leap_seconds = 18;              ///< GPS - UTC, s
  bool leap_seconds_valid = false;    ///< RAWX recStat leapSec
  bool clock_reset = false;           ///< the receiver stepped its clock since the last epoch (RAWX clkReset)
  std::array<RawMeasurement, kMaxRawMeasurements> meas{};  ///< first num_meas valid, SatId then band order
  int num_meas = 0;
};

}  // namespace gnssemu::receiver
