// SPDX-License-Identifier: Apache-2.0
#pragma once
// Multiple Signal Messages 4 and 7 (RTCM 10403.3 §3.5.6; field table in
// shared/reference/rtk-raw.md §2.3-2.5) from a receiver's RawEpoch: one
// message per system (1074/1077 GPS, 1084/1087 GLONASS, 1094/1097 Galileo,
// 1104/1107 SBAS, 1114/1117 QZSS, 1124/1127 BeiDou), split into several when
// satellites x signals exceed the 64-bit cell mask, the multiple-message bit
// set on every message of the epoch but the last.
//
// The encoder keeps, per satellite and band, the whole-cycle offset it takes
// off the carrier phase so that the phase-range stays within the +-1171 m
// the fine phase-range field holds around the rough range; a new offset is a
// new lock for the decoder, so the lock time restarts there (what RTKLIB's
// encoder does, rtk-raw.md §2.4). The epoch time has whole milliseconds, so
// the observables are moved along their Doppler from the receive time to the
// millisecond it is rounded to.
#include <array>
#include <cstdint>
#include <string>

#include "core/common/gnss_signals.hpp"
#include "core/common/sat_id.hpp"
#include "core/receiver/raw_measurements.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::protocol::rtcm {

enum class MsmKind : std::uint8_t { kMsm4 = 4, kMsm7 = 7 };

/// Message number of an MSM of sys (1074, 1127, ...); 0 for a system without MSMs.
int msm_message_number(GnssSystem sys, MsmKind kind) noexcept;

/// RTCM MSM satellite id (1 = the satellite mask's MSB) of sat: GPS, Galileo,
/// BeiDou PRN; GLONASS slot; QZSS PRN - 192; SBAS PRN - 119.
int msm_satellite_id(SatId sat) noexcept;

/// DF402 (4 bits) and DF407 (10 bits) lock-time indicators of a lock time, s
/// (RTCM 10403.3 Tables 3.5-74 and 3.5-76).
int msm4_lock_indicator(double lock_s) noexcept;
int msm7_lock_indicator(double lock_s) noexcept;

/// What one epoch's MSMs came to.
struct MsmEpochStats {
  int messages = 0;      ///< frames appended
  int cells = 0;         ///< signals encoded
  int dropped_cells = 0; ///< signals that did not fit a field (reported as invalid)
};

class MsmEncoder {
public:
  /// station_id: DF003, 0..4095.
  MsmEncoder(int station_id, MsmKind kind) noexcept : station_id_(station_id), kind_(kind) {}

  /// Appends the MSMs of the systems in systems for one epoch (nothing when
  /// the epoch's time is not valid). Never throws once out has capacity; no
  /// allocation of its own.
  MsmEpochStats append_epoch(const receiver::RawEpoch& epoch, SystemSet systems, std::string& out);

  MsmKind kind() const noexcept { return kind_; }
  int station_id() const noexcept { return station_id_; }

private:
  /// Per satellite and band: the phase offset in use and the lock it belongs to.
  struct PhaseState {
    double offset_cycles = 0.0;
    double prev_lock_s = 0.0;
    time::GpsTime reset_at;  ///< the epoch a new offset was taken while the receiver kept lock
    bool active = false;
    bool reset = false;
  };
  struct Cell;
  struct Sat;
  void encode_message(GnssSystem sys, const receiver::RawEpoch& epoch, const Sat* sats, int nsat,
                      const std::array<int, 32>& sig_ids, int nsig, bool more, std::string& out,
                      MsmEpochStats& stats);

  int station_id_;
  MsmKind kind_;
  std::array<PhaseState, kNumSats * kNumBands> phase_{};
};

}  // namespace gnssemu::protocol::rtcm
