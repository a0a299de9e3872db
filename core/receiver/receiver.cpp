// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/receiver.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/common/error.hpp"
#include "core/geo/geoid.hpp"
#include "core/signal/dll_jitter.hpp"
#include "core/world/measurement/carrier.hpp"
#include "core/world/random.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::receiver {

namespace {

// Accuracy reported without a fix (u-blox reports huge hAcc; NMEA GST prints it).
constexpr double kNoFixAccuracy_m = 9999.0;
constexpr double kNoFixSpeedAccuracy_m_s = 999.0;
constexpr double kNoFixTimeAccuracy_s = 1.0;
// A tracked satellite always reports a positive C/N0 (0 means "not tracked"
// in GSV / NAV-SAT), dB-Hz.
constexpr double kMinReportedCn0_dbhz = 1.0;
// A gap longer than this between two smoothing updates restarts the smoothing, s.
constexpr double kMaxSmoothingGap_s = 2.0;
// A step of the receiver's clock between epochs beyond this is its own
// millisecond clock adjustment (RAWX recStat clkReset), s: drift moves it by
// microseconds per epoch.
constexpr double kClockResetStep_s = 0.5e-3;
// The second signal, aided by the first's loops: C/N0 it is found at below
// the unaided acquisition threshold, dB, and its pull-in time, s (carrier
// aiding spares the search: a few loop time constants).
constexpr double kAidingGain_db = 3.0;
constexpr double kAidedPullIn_s = 1.0;
// Preamble of a navigation data frame (GPS LNAV TLM: 8 bits at 50 bit/s), s.
constexpr double kPreamble_s = 0.16;

/// Period of the data frame whose preamble tells a Costas loop's sign, s:
/// GPS/QZSS LNAV subframe 6 s (IS-GPS-200 §20.3.2), BeiDou D1 subframe 6 s
/// (BDS ICD B1I §5.2.3), GLONASS string 2 s (GLONASS ICD §3.3.2.6), Galileo
/// I/NAV page part 2 s (OS SIS ICD §4.3.2), SBAS message 1 s (RTCA DO-229).
double data_frame_s(GnssSystem sys) noexcept {
  switch (sys) {
    case GnssSystem::kGlonass:
    case GnssSystem::kGalileo: return 2.0;
    case GnssSystem::kSbas: return 1.0;
    default: return 6.0;
  }
}

/// A data signal's half-cycle ambiguity is resolved once a whole frame
/// preamble fell within its lock: the lock (lock_s, s) began before the last
/// frame start (frames on the GPS time grid, tow_s) and the preamble has passed.
bool half_cycle_resolved(SignalId sig, double lock_s, double tow_s) noexcept {
  const SignalInfo& info = signal_info(sig);
  if (info.pilot) return true;
  const double frame_s = data_frame_s(info.system);
  double since_s = std::fmod(tow_s - kPreamble_s, frame_s);
  if (since_s < 0.0) since_s += frame_s;
  return lock_s >= since_s + kPreamble_s;
}

/// The loop's own 1-sigma estimates at C/N0 cn0_dbhz (RAWX prStdev, cpStdev,
/// doStdev) from the tracking-noise formulas the world's loops follow with
/// their default settings: DLL thermal jitter (signal/dll_jitter.hpp, Kaplan
/// & Hegarty §8.8), PLL thermal jitter plus oscillator phase noise and FLL
/// frequency jitter (world/carrier.hpp).
void loop_sigmas(double cn0_dbhz, double wavelength_m, RawMeasurement& m) noexcept {
  static constexpr signal::DllParams kDll{};
  static constexpr world::CarrierConfig kLoops{};
  m.pseudorange_sigma_m = signal::dll_thermal_sigma_m(cn0_dbhz, kDll);
  const double pll_rad = world::pll_jitter_rad(cn0_dbhz, kLoops.pll_bandwidth_hz, kLoops.integration_s);
  m.carrier_sigma_cycles = std::hypot(pll_rad, kLoops.oscillator_sigma_rad) / (2.0 * kPi);
  m.doppler_sigma_hz = world::fll_range_rate_sigma_m_s(cn0_dbhz, kLoops, wavelength_m) / wavelength_m;
}

static_assert(static_cast<int>(AntennaStatus::kShort) == static_cast<int>(world::AntennaState::kShort) &&
              static_cast<int>(AntennaStatus::kOpen) == static_cast<int>(world::AntennaState::kOpen));

const ReceiverConfig& validated(const ReceiverConfig& c) {
  validate(c);
  return c;
}

}  // namespace

Receiver::Receiver(const ReceiverConfig& config, std::uint64_t seed)
    : config_(validated(config)),
      acq_(config.acquisition, config.tracking, seed),
      spoof_(config.spoof_detection),
      solver_(config.solver, config.max_pdop),
      nav_(config.filter, config.solver) {
  seed_ = seed;
  no_fix_epoch();
}

void Receiver::set_klobuchar(const orbit::KlobucharParams& p) {
  for (double v : p.alpha)
    if (!std::isfinite(v)) throw Error("receiver config: Klobuchar alpha must be finite");
  for (double v : p.beta)
    if (!std::isfinite(v)) throw Error("receiver config: Klobuchar beta must be finite");
  solver_.set_klobuchar(p);
}

void Receiver::restart(const StartState& keep) noexcept {
  acq_.restart(keep);
  sbas_.reset();
  nav_.reset();
  rtk_.reset();
  for (HatchFilter& h : hatch_) h.reset();
  smoothed_last_.fill(false);
  raw_.num_meas = 0;
  clear_locks();
  if (!keep.position) {
    have_fix_ = false;
    have_3d_ = false;
  }
  no_fix_epoch();
}

void Receiver::clear_locks() noexcept {
  for (auto& band : lock_time_s_) band.fill(0.0);
  band1_tracked_.fill(false);
  band1_pull_in_s_.fill(0.0);
}

void Receiver::set_dynamic_model(DynamicModel m) noexcept {
  config_.filter.dynamic_model = m;
  nav_.set_dynamic_model(m);
}

void Receiver::set_static_hold(double speed_m_s, double max_dist_m) noexcept {
  config_.filter.static_hold_speed_m_s = speed_m_s;
  config_.filter.static_hold_max_dist_m = max_dist_m;
  nav_.set_static_hold(speed_m_s, max_dist_m);
}

void Receiver::no_fix_epoch() noexcept {
  fix_.type = FixType::kNone;
  fix_.dop = Dop{};
  fix_.vel_m_s = Ecef{};
  fix_.vel_enu_m_s = Enu{};
  fix_.speed_m_s = fix_.course_rad = fix_.climb_m_s = 0.0;
  fix_.num_used = 0;
  fix_.sigma_uere_m = 0.0;
  fix_.range_rms_m = 0.0;
  fix_.sigma_e_m = fix_.sigma_n_m = fix_.sigma_u_m = kNoFixAccuracy_m;
  fix_.cov_en_m2 = 0.0;
  fix_.h_acc_m = fix_.v_acc_m = kNoFixAccuracy_m;
  fix_.speed_acc_m_s = kNoFixSpeedAccuracy_m_s;
  fix_.time_acc_s = kNoFixTimeAccuracy_s;
  for (int i = 0; i < fix_.num_sats; ++i) {
    fix_.sats[i].used = false;
    fix_.sats[i].excluded = false;
    fix_.sats[i].residual_m = 0.0;
  }
}

void Receiver::tracking_stage(const time::GpsTime& t, const world::Observables& obs, double dt_s) noexcept {
  AidingState aiding;
  if (have_fix_) aiding = AidingState{true, last_pos_m_, last_vel_m_s_, last_drift_m_s_};
  acq_.step(t, dt_s, obs, aiding);
  tracked_.fill(false);
  int n_tracked = 0;
  std::array<SatId, kMaxSatsInView> tracked_sat{};
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    if (!o.above_mask || !systems_.has(o.sat.system)) continue;
    el_rad_[static_cast<std::size_t>(o.sat.index())] = o.el_rad;
    if (acq_.tracked(o.sat)) tracked_sat[static_cast<std::size_t>(n_tracked++)] = o.sat;
  }
  // Channels go to the highest satellites, within each system's budget and the total.
  std::sort(tracked_sat.begin(), tracked_sat.begin() + n_tracked, [this](SatId a, SatId b) {
    const double ea = el_rad_[static_cast<std::size_t>(a.index())], eb = el_rad_[static_cast<std::size_t>(b.index())];
    return ea != eb ? ea > eb : a < b;
  });
  std::array<int, kNumSystems> per_system{};
  int kept = 0;
  for (int i = 0; i < n_tracked; ++i) {
    const SatId sat = tracked_sat[static_cast<std::size_t>(i)];
    int& used = per_system[static_cast<std::size_t>(sat.system)];
    if (kept >= config_.max_channels || used >= channels_[static_cast<std::size_t>(sat.system)]) {
      acq_.drop(sat);
      continue;
    }
    ++used;
    tracked_sat[static_cast<std::size_t>(kept++)] = sat;
  }
  n_tracked = kept;
  usable_.fill(false);
  for (int i = 0; i < n_tracked; ++i) {
    const SatId sat = tracked_sat[static_cast<std::size_t>(i)];
    tracked_[static_cast<std::size_t>(sat.index())] = true;
    usable_[static_cast<std::size_t>(sat.index())] = acq_.usable(sat);
  }
}

void Receiver::measurement_stage(const world::Observables& obs, double dt_s) noexcept {
  in_.t_rx_local = obs.t_rx_local;
  in_.sky = obs.sky;
  in_.doy = in_.t_rx_local.fractional_day_of_year();
  in_.num_meas = 0;
  const bool smooth = config_.filter.type == NavFilterType::kKalman && config_.filter.smoothing_window_s > 0.0;
  std::array<bool, kNumSats> smoothed_now{};
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    const SatId p = o.sat;
    if (!systems_.has(p.system)) continue;
    const std::size_t k = static_cast<std::size_t>(p.index());
    SatInfo& si = fix_.sats[fix_.num_sats++];
    si = SatInfo{};
    si.sat = p;
    si.az_rad = o.az_rad;
    si.el_rad = o.el_rad;
    si.healthy = o.eph != nullptr && o.eph->health == 0;  // a broadcast "unhealthy" is tracked, not used
    si.above_mask = o.above_mask;
    if (si.above_mask) ++fix_.num_visible;
    si.blocked = o.blocked;
    si.nlos = o.nlos;
    si.bounces = o.bounces;
    si.nlos_delay_m = o.nlos_delay_m;
    si.glonass_channel = o.eph != nullptr ? o.eph->glo_channel : 0;  // freqId of NAV-SAT/NAV-SIG
    si.ephemeris = acq_.has_ephemeris(p);
    if (!tracked_[k]) continue;
    si.tracked = true;
    si.cn0_dbhz = std::max(o.cn0_dbhz, kMinReportedCn0_dbhz);
    si.pseudorange_m = o.pseudorange_m;
    si.doppler_hz = o.doppler_hz;
    ++fix_.num_tracked;
    if (!usable_[k] || !si.healthy) continue;
    double pr_m = si.pseudorange_m;
    if (smooth && o.carrier_valid) {
      const bool restart = !smoothed_last_[k] || acq_.new_lock(p) ||
                           o.carrier_discontinuities != discontinuities_[k] || dt_s > kMaxSmoothingGap_s;
      pr_m = hatch_[k].update(o.pseudorange_m, o.carrier_phase_cycles * o.wavelength_m, dt_s,
                              config_.filter.smoothing_window_s, restart);
      discontinuities_[k] = o.carrier_discontinuities;
      smoothed_now[k] = true;
      si.smoothed = hatch_[k].epochs() > 1.0;
    }
    Measurement& m = in_.meas[in_.num_meas];
    m.eph = o.eph;
    m.pseudorange_m = pr_m;
    m.doppler_hz = si.doppler_hz;
    m.wavelength_m = o.wavelength_m;
    m.cn0_dbhz = si.cn0_dbhz;
    m.iono_given = false;
    m.iono_m = 0.0;
    meas_sat_[static_cast<std::size_t>(in_.num_meas++)] = p;
  }
  smoothed_last_ = smoothed_now;
  if (in_.num_meas > max_solution_sats_) cap_measurements();
}

void Receiver::cap_measurements() noexcept {
  // Which satellites the real chip keeps is not documented: the highest
  // (the least multipath and troposphere) is our estimate.
  std::array<double, kMaxSatsInView> el{};
  const int n = in_.num_meas;
  for (int i = 0; i < n; ++i) el[static_cast<std::size_t>(i)] = el_rad_[static_cast<std::size_t>(meas_sat_[static_cast<std::size_t>(i)].index())];
  std::array<double, kMaxSatsInView> sorted = el;
  std::nth_element(sorted.begin(), sorted.begin() + (n - max_solution_sats_), sorted.begin() + n);
  const double threshold = sorted[static_cast<std::size_t>(n - max_solution_sats_)];
  int above = 0;
  for (int i = 0; i < n; ++i) above += el[static_cast<std::size_t>(i)] > threshold;
  int ties_left = max_solution_sats_ - above;  // equal elevations: the first in SatId order
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    const double e = el[static_cast<std::size_t>(i)];
    if (e < threshold || (e == threshold && ties_left-- <= 0)) continue;
    in_.meas[static_cast<std::size_t>(kept)] = in_.meas[static_cast<std::size_t>(i)];
    meas_sat_[static_cast<std::size_t>(kept++)] = meas_sat_[static_cast<std::size_t>(i)];
  }
  in_.num_meas = kept;
}

void Receiver::raw_stage(const world::Observables& obs, double dt_s) noexcept {
  raw_.t_rx = obs.t_rx_local;
  raw_.time_valid = fix_.time_valid;
  raw_.leap_seconds = fix_.leap_seconds;
  raw_.leap_seconds_valid = fix_.time_valid;
  // The receiver steps its own clock by whole milliseconds: the measurements
  // of this epoch are then on a clock that jumped since the last one.
  const double clock_s = obs.t_rx_local - obs.t;
  raw_.clock_reset = raw_clock_known_ && std::fabs(clock_s - raw_clock_s_) > kClockResetStep_s;
  raw_clock_s_ = clock_s;
  raw_clock_known_ = std::isfinite(clock_s);
  raw_.num_meas = 0;
  const bool two_bands = config_.bands > 1;
  PerBand<bool> locked{};
  std::array<bool, kNumSats> band1_now{}, pulling{};
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    const std::size_t k = static_cast<std::size_t>(o.sat.index());
    if (!systems_.has(o.sat.system) || !tracked_[k]) continue;
    const std::optional<SignalId> sig = signal_of(o.sat.system, 0);
    if (!sig) continue;
    const int glonass_channel = o.eph != nullptr ? o.eph->glo_channel : 0;
    const bool new_lock = acq_.new_lock(o.sat);
    const RawSignal first{*sig, o.pseudorange_m, o.doppler_hz, o.cn0_dbhz, o.wavelength_m, o.carrier_valid,
                          o.carrier_phase_cycles, o.carrier_discontinuities, o.carrier_half_cycle};
    raw_measurement(o.sat, glonass_channel, 0, first, new_lock, dt_s, locked[0][k]);
    if (two_bands && band1_tracked(o, dt_s, band1_now[k], pulling[k])) {
      const world::SecondSignal& b = o.band1;
      const RawSignal second{*signal_of(o.sat.system, 1), b.pseudorange_m, b.doppler_hz, b.cn0_dbhz, b.wavelength_m,
                             b.carrier_valid, b.carrier_phase_cycles, b.carrier_discontinuities,
                             b.carrier_half_cycle};
      raw_measurement(o.sat, glonass_channel, 1, second, new_lock || !band1_tracked_[k], dt_s, locked[1][k]);
    }
  }
  for (int b = 0; b < config_.bands; ++b) {
    const auto ub = static_cast<std::size_t>(b);
    for (std::size_t k = 0; k < kNumSats; ++k)
      if (!locked[ub][k]) lock_time_s_[ub][k] = 0.0;
  }
  if (!two_bands) return;
  band1_tracked_ = band1_now;
  for (std::size_t k = 0; k < kNumSats; ++k)
    if (!pulling[k]) band1_pull_in_s_[k] = 0.0;
}

bool Receiver::band1_tracked(const world::SatObservable& o, double dt_s, bool& now, bool& pulling) noexcept {
  const std::size_t k = static_cast<std::size_t>(o.sat.index());
  const world::SecondSignal& b = o.band1;
  // The first signal's loops aid the second's (code phase, Doppler): it is
  // found at a lower C/N0 (kAidingGain_db) and pulled in within kAidedPullIn_s;
  // it is lost by its own C/N0 alone.
  const double need_dbhz =
      band1_tracked_[k] ? config_.tracking.lose_dbhz : config_.tracking.acquire_dbhz - kAidingGain_db;
  pulling = b.received && b.cn0_dbhz >= need_dbhz;
  if (!pulling) return now = false;
  if (!band1_tracked_[k]) band1_pull_in_s_[k] += dt_s;
  now = band1_tracked_[k] || band1_pull_in_s_[k] >= kAidedPullIn_s;
  return now;
}

void Receiver::raw_measurement(SatId sat, int glonass_channel, int band, const RawSignal& sig, bool new_lock,
                               double dt_s, bool& locked) noexcept {
  const std::size_t k = static_cast<std::size_t>(sat.index());
  const auto ub = static_cast<std::size_t>(band);
  RawMeasurement& m = raw_.meas[static_cast<std::size_t>(raw_.num_meas++)];
  m = RawMeasurement{};
  m.sat = sat;
  m.signal = sig.id;
  m.glonass_channel = glonass_channel;
  m.pseudorange_m = sig.pseudorange_m;
  m.doppler_hz = sig.doppler_hz;
  m.cn0_dbhz = std::max(sig.cn0_dbhz, kMinReportedCn0_dbhz);
  m.pseudorange_valid = true;
  loop_sigmas(m.cn0_dbhz, sig.wavelength_m, m);
  if (!sig.carrier_valid) return;
  double& lock_s = lock_time_s_[ub][k];
  const bool continuous = sig.discontinuities == raw_discontinuities_[ub][k] && !new_lock;
  lock_s = continuous ? lock_s + dt_s : 0.0;
  raw_discontinuities_[ub][k] = sig.discontinuities;
  locked = true;
  // A re-acquisition after a loss the world's carrier did not see (C/N0
  // below the loop's threshold, a fault's jammer, outage or spoofer) starts
  // the carrier accumulator over: a new arbitrary whole number of cycles,
  // and a Costas loop may lock on either data sign. The first lock keeps
  // the world's own.
  const bool pilot = signal_info(sig.id).pilot;
  if (new_lock && locks_[ub][k]++ > 0) {
    const world::CounterRng rng(seed_);
    const std::uint64_t stream = world::kAcquisitionStream + world::band_stream(sat, band);
    const double u = rng.uniform(stream, locks_[ub][k], world::Purpose::kRelockAmbiguity, 0);
    relock_cycles_[ub][k] = std::floor(2.0e5 * u) - 1.0e5;
    relock_half_[ub][k] = !pilot && rng.uniform(stream, locks_[ub][k], world::Purpose::kRelockHalfCycle, 0) < 0.5;
  }
  const bool half = sig.half_cycle != relock_half_[ub][k];
  m.carrier_phase_cycles = sig.carrier_phase_cycles + relock_cycles_[ub][k] + (relock_half_[ub][k] ? 0.5 : 0.0);
  m.lock_time_s = lock_s;
  m.carrier_valid = true;
  // A Costas loop's half-cycle ambiguity is resolved by the next frame
  // preamble: an inverted preamble says the loop holds the other sign, and
  // the receiver subtracts the half cycle (RXM-RAWX trkStat halfCyc,
  // subHalfCyc; docs/raw-output.md). A dataless pilot's PLL has none.
  m.half_cycle_resolved = half_cycle_resolved(sig.id, m.lock_time_s, raw_.t_rx.tow_s());
  if (m.half_cycle_resolved && half) {
    m.carrier_phase_cycles -= 0.5;
    m.half_cycle_subtracted = true;
  }
}

const Fix& Receiver::step(const time::GpsTime& t, const world::Observables& obs) noexcept {
  double dt_s = 0.0;
  if (started_) {
    dt_s = t - t_prev_;
    if (!std::isfinite(dt_s) || dt_s < 0.0) dt_s = 0.0;  // time going back: no lock time gained
  }
  started_ = true;
  t_prev_ = t;

  fix_.t = t;
  fix_.noise_rise_db = obs.noise_rise_db;
  fix_.cw_jam_to_noise = obs.cw_jam_to_noise;
  fix_.antenna_status = static_cast<AntennaStatus>(obs.antenna_state);
  fix_.leap_seconds = leap_override_ ? leap_s_ : time::leap_seconds_at(t);
  fix_.in_leap_second = !leap_override_ && time::in_inserted_leap_second(t);  // a fixed count never steps
  fix_.num_sats = fix_.num_visible = fix_.num_tracked = 0;
  // Without modelled acquisition time is known once there is an antenna (as
  // before the acquisition model); with it, from the real-time clock or the
  // first decoded time of week.
  const bool modelled = config_.acquisition.modelled;

  if (!obs.antenna_connected) {
    acq_.lose_all(dt_s);
    smoothed_last_.fill(false);
    raw_.num_meas = 0;
    clear_locks();
    fix_.time_valid = modelled ? acq_.time_known() : fix_.time_valid;
    no_fix_epoch();
    if (config_.filter.type == NavFilterType::kKalman) {
      // Nothing to measure: the filter coasts for its limit, then the fix is lost.
      in_.num_meas = 0;
      snap_ = SolverOutput{};
      nav_.step(dt_s, in_, snap_, solver_, out_);
      if (out_.type != FixType::kNone) fill_solution();
    }
    fix_.spoof_det_state = spoof_.update(fix_);
    sbas_.step(dt_s, {}, have_fix_ ? &last_lla_ : nullptr);
    rtk_.step(raw_, obs, corrections_, fix_);
    return fix_;
  }

  tracking_stage(t, obs, dt_s);
  fix_.time_valid = modelled ? acq_.time_known() : true;
  measurement_stage(obs, dt_s);
  sbas_stage(obs, dt_s);
  raw_stage(obs, dt_s);

  // Its own corrections and solution, warm-started from the last fix.
  in_.have_prior = have_fix_;
  if (have_fix_) {
    double dt_fix_s = t - last_fix_t_;
    if (!std::isfinite(dt_fix_s) || std::fabs(dt_fix_s) > 600.0) dt_fix_s = 0.0;
    in_.prior_pos_m = Ecef(last_pos_m_ + last_vel_m_s_ * dt_fix_s);
    in_.prior_clock_m = last_clock_m_ + last_drift_m_s_ * dt_fix_s;
  }
  in_.have_held_height = have_3d_;
  in_.held_pos_m = held_pos_m_;
  in_.held_height_m = held_height_m_;
  if (config_.filter.type == NavFilterType::kKalman) {
    solver_.solve(in_, snap_);
    nav_.step(dt_s, in_, snap_, solver_, out_);
  } else {
    solver_.solve(in_, out_);
  }
  fill_solution();
  fix_.spoof_det_state = spoof_.update(fix_);
  rtk_.step(raw_, obs, corrections_, fix_);
  sbas_fix_flags();
  return fix_;
}

void Receiver::sbas_stage(const world::Observables& obs, double dt_s) noexcept {
  meas_sbas_.fill(false);
  meas_sbas_iono_.fill(false);
  sbas_.step(dt_s, std::span<const SatInfo>(fix_.sats.data(), static_cast<std::size_t>(fix_.num_sats)),
             have_fix_ ? &last_lla_ : nullptr);
  if (!config_.sbas || !sbas_.orbit_clock()) return;
  // Both lists are in SatId order.
  int j = 0;
  for (int i = 0; i < in_.num_meas; ++i) {
    const SatId sat = meas_sat_[static_cast<std::size_t>(i)];
    while (j < obs.num_sats && obs.sats[j].sat < sat) ++j;
    if (j >= obs.num_sats || obs.sats[j].sat != sat) continue;
    const world::SatObservable& o = obs.sats[j];
    if (!o.sbas_valid || !world::sbas_corrects(sat.system)) continue;
    Measurement& m = in_.meas[static_cast<std::size_t>(i)];
    m.pseudorange_m -= o.sbas_orbit_clock_m;
    meas_sbas_[static_cast<std::size_t>(i)] = true;
    if (sbas_.iono()) {
      m.iono_given = true;
      m.iono_m = o.sbas_iono_m;
      meas_sbas_iono_[static_cast<std::size_t>(i)] = true;
    }
  }
}

void Receiver::sbas_fix_flags() noexcept {
  if (fix_.diff_soln || !is_gnss_fix(fix_.type)) return;
  for (int i = 0; i < fix_.num_sats; ++i) {
    if (!fix_.sats[i].used || !fix_.sats[i].sbas_corr) continue;
    // The real NEO-M9N prints station 0000 and no age for an SBAS fix.
    fix_.diff_soln = true;
    fix_.sbas_soln = true;
    fix_.ref_station_id = 0;
    fix_.corr_age_s = -1.0;
    return;
  }
}

bool Receiver::within_limits() const noexcept {
  const DynamicModelParams& dm = dynamic_model_params(config_.filter.dynamic_model);
  const double alt_msl_m = fix_.lla.height_m - fix_.geoid_sep_m;
  const double speed_3d = std::hypot(fix_.speed_m_s, fix_.climb_m_s);
  const OperationalLimits& lim = config_.limits;
  if (!(alt_msl_m <= lim.max_altitude_m) || !(speed_3d <= lim.max_speed_m_s)) return false;
  if (!(alt_msl_m <= dm.max_altitude_m)) return false;
  if (dm.check_velocity && (!(fix_.speed_m_s <= dm.max_h_speed_m_s) || !(std::fabs(fix_.climb_m_s) <= dm.max_v_speed_m_s)))
    return false;
  return true;
}

void Receiver::fill_solution() noexcept {
  if (out_.type == FixType::kNone) {
    no_fix_epoch();
    return;
  }
  Fix& f = fix_;
  f.type = out_.type;
  f.pos_m = out_.pos_m;
  f.lla = out_.lla;
  f.geoid_sep_m = geo::geoid_separation_m(f.lla.lat_rad, f.lla.lon_rad);
  f.vel_m_s = out_.vel_m_s;
  f.vel_enu_m_s = out_.vel_enu_m_s;
  f.speed_m_s = std::hypot(out_.vel_enu_m_s.x, out_.vel_enu_m_s.y);
  double course = std::atan2(out_.vel_enu_m_s.x, out_.vel_enu_m_s.y);
  if (course < 0.0) course += 2.0 * kPi;
  if (course >= 2.0 * kPi) course = 0.0;
  f.course_rad = course;
  f.climb_m_s = out_.vel_enu_m_s.z;
  f.clock_bias_s = out_.clock_m / kSpeedOfLight_m_s;
  f.clock_drift_s_s = out_.drift_m_s / kSpeedOfLight_m_s;
  if (!within_limits()) {
    no_fix_epoch();
    return;
  }
  f.dop = out_.dop;
  f.num_used = out_.num_used;
  f.sigma_uere_m = out_.sigma_uere_m;
  f.range_rms_m = out_.range_rms_m;
  const auto& q = out_.cov_pos;
  const auto& qv = out_.cov_vel;
  f.sigma_e_m = std::sqrt(q[0][0]);
  f.sigma_n_m = std::sqrt(q[1][1]);
  f.sigma_u_m = std::sqrt(q[2][2]);
  f.cov_en_m2 = q[0][1];
  f.h_acc_m = std::sqrt(q[0][0] + q[1][1]);
  f.v_acc_m = f.sigma_u_m;
  f.speed_acc_m_s = std::sqrt(qv[0][0] + qv[1][1] + qv[2][2]);
  f.time_acc_s = std::sqrt(q[3][3]) / kSpeedOfLight_m_s;
  // Measurements were taken in SatId order, as were fix_.sats.
  int k = 0;
  for (int i = 0; i < f.num_sats && k < in_.num_meas; ++i) {
    SatInfo& si = f.sats[i];
    if (si.sat != meas_sat_[static_cast<std::size_t>(k)]) continue;
    si.used = f.type != FixType::kDeadReckoning && !out_.excluded[k];  // excluded: tracked, not used
    si.excluded = out_.excluded[k];
    si.sbas_corr = meas_sbas_[static_cast<std::size_t>(k)];
    si.sbas_iono = meas_sbas_iono_[static_cast<std::size_t>(k)];
    si.residual_m = out_.residual_m[k++];
  }

  have_fix_ = true;
  last_fix_t_ = f.t;
  last_pos_m_ = f.pos_m;
  last_lla_ = f.lla;
  last_vel_m_s_ = f.vel_m_s;
  last_clock_m_ = out_.clock_m;
  last_drift_m_s_ = out_.drift_m_s;
  acq_.on_fix();
  if (f.type == FixType::k3D) {
    have_3d_ = true;
    held_pos_m_ = f.pos_m;
    held_height_m_ = f.lla.height_m;
  }
}

}  // namespace gnssemu::receiver
