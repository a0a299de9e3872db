// SPDX-License-Identifier: Apache-2.0
#pragma once
// Acquisition and reacquisition: per satellite channel a search, then
// tracking with lose hysteresis, then the broadcast ephemeris download; and
// what the receiver knows (time, position, almanac, ephemerides), which
// decides how fast and at what C/N0 a search succeeds. The u-blox M8 figures
// this is set to (MAX-M8 data sheet UBX-15031506, GPS): cold start 29 s, hot
// start 1 s, acquisition sensitivity cold -148 dBm, hot -157 dBm,
// reacquisition -160 dBm (docs/models.md "Acquisition"). Deterministic for a
// seed; no allocation.
#include <array>
#include <cstdint>

#include "core/common/constants.hpp"
#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/signal/tracking.hpp"
#include "core/time/gps_time.hpp"
#include "core/world/observables.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace gnssemu::receiver {

/// What the receiver still knows at a (re)start: the battery-backed data a
/// CFG-RST navBbrMask keeps.
struct StartState {
  bool ephemeris = true;  ///< broadcast ephemerides it decoded
  bool almanac = true;
  bool position = true;   ///< its last position
  bool time = true;       ///< GPS time (real-time clock)
};

/// Start modes of a u-blox (CFG-RST navBbrMask 0x0000 / 0x0001 / 0xFFFF).
enum class StartMode : std::uint8_t {
  kHot,   ///< everything kept
  kWarm,  ///< ephemerides cleared
  kCold,  ///< nothing kept
};

/// The StartState of a start mode.
constexpr StartState start_state(StartMode m) noexcept {
  switch (m) {
    case StartMode::kHot: return {true, true, true, true};
    case StartMode::kWarm: return {false, true, true, true};
    case StartMode::kCold: break;
  }
  return {false, false, false, false};
}

struct AcquisitionConfig {
  /// false: a satellite is tracked and used as soon as its C/N0 reaches the
  /// acquisition threshold (no search time, no ephemeris download).
  bool modelled = true;
  StartMode start = StartMode::kHot;  ///< state at power-on
  /// Mean search time of one satellite at strong signal, s (> 0): without
  /// aiding (no time, position or orbit of it: the whole Doppler range), aided
  /// (time, position, almanac or ephemeris), and reacquisition (lost for less
  /// than reacq_window_s: its own recent prediction).
  double cold_search_s = 1.5;
  double aided_search_s = 0.5;
  double reacq_search_s = 0.3;
  double reacq_window_s = 60.0;       ///< s (>= 0)
  /// At and above this C/N0 searches take their base time; below it the
  /// dwell grows as 10^((strong - C/N0) / 10), dB-Hz.
  double strong_cn0_dbhz = 40.0;
  double search_spread = 0.3;         ///< search times uniform in [1 - s, 1 + s] x mean, [0, 1)
  /// C/N0 an unaided search needs at least, dB-Hz (it also needs
  /// tracking.acquire_dbhz): the data sheet's cold-start sensitivity,
  /// -148 dBm, at -174 dBm/Hz thermal noise and a 3-dB front end. The default
  /// acquire_dbhz (30) is above it, so there only the search time differs;
  /// a receiver set to the M8's own thresholds (hot -157 dBm = 14 dB-Hz)
  /// cold-starts only on the stronger satellites.
  double cold_acquire_dbhz = 23.0;
  /// A reacquisition succeeds this much below tracking.acquire_dbhz, dB
  /// (data sheet: -160 vs -157 dBm).
  double reacq_margin_db = 3.0;
  /// Half-width of an aided search around the Doppler predicted from the
  /// receiver's own position, velocity and clock drift, Hz (> 0); a signal
  /// outside (the receiver was moved far) is found by the unaided search.
  double aided_doppler_window_hz = 500.0;
  double bit_sync_s = 1.0;            ///< from acquisition to data bit synchronisation, s (>= 0)
  double almanac_download_s = 750.0;  ///< tracking time to collect the almanac (25 pages x 30 s), s (>= 0)
  double ephemeris_validity_s = 14400.0;  ///< how long a decoded ephemeris is used, s (> 0; 4 h fit)
};

/// Valid values of AcquisitionConfig's numbers.
struct AcquisitionRanges {
  static constexpr Range cold_search_s{0.0, 600.0, "s", true};
  static constexpr Range aided_search_s{0.0, 600.0, "s", true};
  static constexpr Range reacq_search_s{0.0, 600.0, "s", true};
  static constexpr Range reacq_window_s{0.0, 86400.0, "s"};
  static constexpr Range strong_cn0_dbhz{0.0, 60.0, "dB-Hz"};
  static constexpr Range search_spread{0.0, 1.0, "", false, true};
  static constexpr Range cold_acquire_dbhz{0.0, 60.0, "dB-Hz"};
  static constexpr Range reacq_margin_db{0.0, 30.0, "dB"};
  static constexpr Range aided_doppler_window_hz{0.0, 10000.0, "Hz", true};
  static constexpr Range bit_sync_s{0.0, 60.0, "s"};
  static constexpr Range almanac_download_s{0.0, 86400.0, "s"};
  static constexpr Range ephemeris_validity_s{0.0, 86400.0, "s", true};
};

/// Throws gnssemu::Error for a value out of its range.
void validate(const AcquisitionConfig& c);

/// Seconds from phase_s (GPS time of week modulo 30 s, [0, 30)) until words
/// 3-10 of subframes 1, 2 and 3 of the 30-s frame (clock and ephemeris,
/// IS-GPS-200 §20.3.2; each 0.6-s word with its own parity) have each been
/// received whole: 16.8..30.6 s, about 27 s on average.
double ephemeris_wait_s(double phase_s) noexcept;

/// The receiver's estimate it aids searches with (from its last fix).
struct AidingState {
  bool valid = false;
  Ecef pos_m;                ///< ECEF, m
  Ecef vel_m_s;              ///< ECEF, m/s
  double drift_m_s = 0.0;    ///< c x clock drift, m/s
};

class Acquisition {
public:
  /// thresholds: the tracking thresholds (acquire / lose); seed: search-time draws.
  Acquisition(const AcquisitionConfig& config, const signal::TrackingThresholds& thresholds,
              std::uint64_t seed) noexcept;

  /// Restart (power-on, CFG-RST): every channel idle; keeps what keep says.
  void restart(const StartState& keep) noexcept;

  /// One epoch at GPS time t, dt_s after the previous one (s, >= 0), with the
  /// world's observables and the receiver's aiding estimate.
  void step(const time::GpsTime& t, double dt_s, const world::Observables& obs, const AidingState& aiding) noexcept;
  /// The antenna is gone: every channel loses lock (time still advances).
  void lose_all(double dt_s) noexcept;
  /// A fix: the receiver knows time and position from now on.
  void on_fix() noexcept { time_known_ = position_known_ = true; }
  /// Drop the lock of sat (the channel limit): it is searched again later.
  void drop(SatId sat) noexcept;

  /// sat (valid()) is tracked: code lock, a pseudorange.
  bool tracked(SatId sat) const noexcept { return ch_[idx(sat)].state == State::kTracking; }
  /// sat is tracked and its ephemeris is decoded: it can be used.
  bool usable(SatId sat) const noexcept { return tracked(sat) && has_ephemeris(sat); }
  /// The receiver has a decoded ephemeris of sat (always without modelled acquisition).
  bool has_ephemeris(SatId sat) const noexcept { return !cfg_.modelled || ch_[idx(sat)].eph_until_s > now_s_; }
  /// sat became tracked at this epoch.
  bool new_lock(SatId sat) const noexcept { return ch_[idx(sat)].new_lock; }
  /// Searches begun so far (for tests and logs).
  std::uint64_t searches() const noexcept { return searches_; }
  bool time_known() const noexcept { return time_known_; }
  bool position_known() const noexcept { return position_known_; }
  bool almanac_known() const noexcept { return almanac_known_; }
  /// Receiver time since power-on, s.
  double now_s() const noexcept { return now_s_; }

private:
  enum class State : std::uint8_t { kIdle, kSearching, kTracking };
  enum class Search : std::uint8_t { kCold, kAided, kReacq };
  struct Channel {
    State state = State::kIdle;
    Search search = Search::kCold;
    double search_left_s = 0.0;
    bool tracked_before = false;
    double lost_at_s = 0.0;           ///< receiver time of the last loss
    double eph_ready_s = 0.0;         ///< download complete at (receiver time), while tracking
    double eph_until_s = -1.0;        ///< decoded ephemeris usable until (receiver time)
    double time_at_s = 0.0;           ///< the first hand-over word (GPS time) decoded at (receiver time)
    bool downloading = false;
    bool new_lock = false;
  };

  static std::size_t idx(SatId sat) noexcept { return static_cast<std::size_t>(sat.index()); }
  Search classify(SatId sat) const noexcept;
  double threshold_dbhz(Search s) const noexcept;
  double search_time_s(SatId sat, Search s, double cn0_dbhz) noexcept;
  /// The aided search of o would find it: its Doppler is within the window
  /// around the prediction from aiding (true without aiding).
  /// sky: the epoch's broadcast orbits (null: o.eph evaluated in full).
  bool within_aided_window(const time::GpsTime& t, const world::SatObservable& o, const AidingState& aiding,
                           const world::SharedSky* sky) const noexcept;
  void lose(Channel& c) noexcept;
  void step_instant(double dt_s, const world::Observables& obs) noexcept;

  AcquisitionConfig cfg_;
  signal::TrackingThresholds thr_;
  std::uint64_t seed_;
  std::array<Channel, kNumSats> ch_{};  ///< per satellite (SatId::index())
  std::array<signal::TrackingState, kNumSats> instant_{};  ///< hysteresis of the unmodelled mode
  bool time_known_ = true, position_known_ = true, almanac_known_ = true;
  double almanac_tracking_s_ = 0.0;  ///< tracking time towards the almanac download
  double now_s_ = 0.0;
  std::uint64_t searches_ = 0;
};

}  // namespace gnssemu::receiver
