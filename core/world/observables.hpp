// SPDX-License-Identifier: Apache-2.0
#pragma once
// Observables: what the world hands the receiver at one epoch (DESIGN.md §1,
// the line between step 6 and step 7): per satellite the geometry, the
// signal's C/N0, code pseudorange and Doppler, plus the path truth the
// receiver passes on for analysis only. Plain data; faults edit it between
// the world and the receiver.
#include <array>
#include <cstdint>

#include "core/common/constants.hpp"
#include "core/common/sat_id.hpp"
#include "core/orbit/ephemeris.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::world {

/// Noise-floor rise of a quiet countryside, dB.
inline constexpr double kQuietNoiseRise_db = 1.0;

/// The antenna as the receiver's supervisor sees it (MON-HW aStatus).
enum class AntennaState : uint8_t { kOk, kShort, kOpen };

/// The second signal of a satellite (gnss_signals.hpp band 1), modelled only
/// for worlds of dual-band receivers: its own C/N0, noise, multipath, group
/// delays and carrier lock; geometry, troposphere, orbit and clock are the
/// L1-band signal's.
struct SecondSignal {
  /// Modelled and received (the system has a second signal, the world
  /// models band 1 and the path reaches the antenna).
  bool received = false;
  double cn0_dbhz = 0.0;                ///< dB-Hz (a fault may lower it alone: a jammer on one band)
  double pseudorange_m = 0.0;           ///< code pseudorange, m
  double carrier_hz = 0.0;              ///< carrier, Hz
  double wavelength_m = 0.0;            ///< its wavelength, m
  double doppler_hz = 0.0;              ///< Hz, positive when approaching
  bool carrier_valid = false;           ///< as SatObservable::carrier_valid, for this band
  double carrier_phase_cycles = 0.0;    ///< cycles of wavelength_m, an arbitrary integer per lock
  std::uint32_t carrier_discontinuities = 0;  ///< this band's new locks and slips so far
  bool carrier_half_cycle = false;      ///< as SatObservable::carrier_half_cycle, for this band
};

/// One satellite above the horizon with a healthy ephemeris.
struct SatObservable {
  SatId sat;                            ///< the satellite
  const orbit::Ephemeris* eph = nullptr;  ///< the broadcast set it transmits (the receiver decodes the same)
  double az_rad = 0.0;                  ///< [0, 2pi), from true north
  double el_rad = 0.0;                  ///< (0, pi/2]
  /// At or above the mask the world was asked to model; below it only the
  /// geometry above is set.
  bool above_mask = false;
  bool received = false;                ///< a signal reaches the antenna
  double cn0_dbhz = 0.0;                ///< carrier-to-noise density at the antenna, dB-Hz (0 when not received)
  double pseudorange_m = 0.0;           ///< code pseudorange with every error, m (when received)
  /// Carrier of the signal, Hz (orbit::carrier_hz of its set), and its
  /// wavelength, m: Doppler and carrier phase are in its units.
  double carrier_hz = kL1Freq_hz;
  double wavelength_m = kL1Wavelength_m;
  double doppler_hz = 0.0;              ///< Doppler of that carrier, Hz, positive when approaching (when received)
  /// The carrier loop is locked (received, with the carrier modelled).
  bool carrier_valid = false;
  /// Accumulated carrier phase, cycles of wavelength_m, with the sign of the pseudorange
  /// (grows with the range); an arbitrary whole number of cycles per lock (and half of one while carrier_half_cycle).
  double carrier_phase_cycles = 0.0;
  /// Carrier discontinuities of this satellite so far (new locks, cycle slips): a
  /// change since the last epoch says the phase is not continuous (as the
  /// loss-of-lock indicator of RINEX), so carrier smoothing must restart.
  /// Counted only while [signal.carrier] is enabled.
  std::uint32_t carrier_discontinuities = 0;
  /// The Costas loop of a data signal holds the inverted data sign, so
  /// carrier_phase_cycles is half a cycle off a whole number; the receiver
  /// learns it from the next frame preamble. Never set for a pilot.
  bool carrier_half_cycle = false;
  /// The range jumped by more than the code loop follows since the last
  /// epoch (a discontinuous truth): the receiver loses lock on it. Only
  /// while [signal.carrier] is enabled (or set by the fault stage).
  bool lock_break = false;
  SecondSignal band1;                   ///< the second frequency (dual-band worlds only)
  /// What the SBAS whose service area holds the antenna broadcasts for this
  /// satellite (its ground network's estimates, each the world's own error
  /// plus the service's residual; world/sbas_service.hpp): set for received
  /// satellites of the systems SBAS L1 corrects. Whether a receiver decodes
  /// them is its own affair (a GEO of that service tracked long enough).
  bool sbas_valid = false;
  double sbas_orbit_clock_m = 0.0;      ///< the satellite's orbit/clock range error in pseudorange_m, m
  double sbas_iono_m = 0.0;             ///< slant ionospheric delay at carrier_hz, m
  // Path truth of the scene stage (analysis only; zero without a scene).
  bool nlos = false;                    ///< received via reflections only
  bool blocked = false;                 ///< no signal path (not received)
  int bounces = 0;                      ///< reflections on the received path
  double nlos_delay_m = 0.0;            ///< extra path length in the pseudorange, m
};

class SharedSky;

struct Observables {
  time::GpsTime t;                      ///< epoch, true GPS receive time
  /// false: no truth (antenna lost); no satellite is listed.
  bool antenna_connected = false;
  /// false: C/N0 follows the fixed elevation curve of a world without a link
  /// budget, and every received signal is strong enough to track.
  bool signal_modelled = true;
  /// Environment noise-floor rise above thermal at the antenna, dB (>= 0).
  double noise_rise_db = kQuietNoiseRise_db;
  /// Antenna supervisor state; not kOk: nothing is received.
  AntennaState antenna_state = AntennaState::kOk;
  /// CW / narrowband interference power over the front end's noise floor
  /// (linear, >= 0; 0: none): what a CW detector sees (MON-HW jamInd).
  double cw_jam_to_noise = 0.0;
  time::GpsTime t_rx_local;             ///< the epoch on the receiver's own (biased) clock
  double clock_bias_s = 0.0;            ///< true receiver clock bias, s (analysis)
  double clock_drift_s_s = 0.0;         ///< true receiver clock drift, s/s (analysis)
  /// The broadcast orbits of the epoch (what a receiver computes from the
  /// ephemerides it decodes; no world truth): its SharedSky::state_at()
  /// spares the receiver evaluating them again. Null: evaluate them.
  const SharedSky* sky = nullptr;
  std::array<SatObservable, kMaxSatsInView> sats{};  ///< first num_sats valid, in SatId order
  int num_sats = 0;
};

}  // namespace gnssemu::world
