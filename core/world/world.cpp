// SPDX-License-Identifier: Apache-2.0
#include "core/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "core/geo/geodesy.hpp"
#include "core/signal/dll_jitter.hpp"
#include "core/signal/system_signal.hpp"
#include "core/world/measurement/error_processes.hpp"

namespace gnssemu::world {

namespace {

// C/N0 shape when the signal stage is off: nominal at zenith, about -8 dB at 5 degrees.
constexpr double kCn0ElevationLoss_db = 10.0;
// Cached atmospheric terms are dropped when the receiver moves this much
// vertically or in total (m): a 5 m height change moves the 5-degree tropo
// delay by ~1.5 cm; 5 km moves a pierce point by < 1 % of its scale.
constexpr double kCacheMaxHeightChange_m = 5.0;
constexpr double kCacheMaxMove_m = 5000.0;
// Elevation floor of the multipath 1 / sin(el) scaling (ErrorModelConfig doc), rad.

const WorldConfig& validated(const WorldConfig& c) {
  validate(c);
  return c;
}

}  // namespace

World::World(const orbit::EphemerisStore& store, const WorldConfig& config)
    : config_(validated(config)),
      own_sky_(store, config_.systems, sky_errors_config(config_)),
      noise_(MeasurementNoise::of(config_)),
      rng_(config.seed),
      clock_(config.clock),
      atmosphere_(config.atmosphere),
      cache_(config.atmosphere.cache_refresh_s, config.atmosphere.cache_mode),
      link_(config.signal.link) {
  obs_.signal_modelled = config.signal.enabled;
}

void World::attach_scene(const SceneSetup& setup) {
  if (setup.scene == nullptr) {
    propagator_.reset();
    scene_frame_.reset();
  } else {
    propagator_ = std::make_unique<scene::Propagator>(*setup.scene, setup.search);
    scene_frame_ = std::make_unique<geo::LocalFrame>(setup.origin);
  }
  scene_path_.fill(scene::SatPath{});
}

void World::set_klobuchar_shape(const orbit::KlobucharParams& p) {
  atmosphere_.set_klobuchar_shape(p);
  cache_.clear();
}

void World::advance(const SharedSky& sky, const time::GpsTime& t) noexcept {
  // The satellites the store holds (it may be replaced between epochs, as
  // the daemon re-dates it).
  if (sats_of_ != &sky || sats_revision_ != sky.revision()) {
    n_sats_ = 0;
    for (const SatId sat : sky.sats())
      if (config_.systems.has(sat.system)) sats_[static_cast<std::size_t>(n_sats_++)] = sat;
    sats_of_ = &sky;
    sats_revision_ = sky.revision();
  }
  // The regional processes of the sky, at this world's sigmas.
  const SkyErrors& e = sky.errors();
  iono_factor_ = atmosphere_.iono_on() ? 1.0 + config_.errors.iono_scale.sigma * e.value(SkyProcess::kIonoScale) : 1.0;
  zwd_pert_m_ = atmosphere_.tropo_on() ? config_.atmosphere.zwd_perturbation.sigma_m * e.value(SkyProcess::kZwd) : 0.0;
  if (!started_) {
    started_ = true;
  } else {
    double dt_s = t - t_prev_;
    if (!std::isfinite(dt_s) || dt_s < 0.0) dt_s = 0.0;  // time going back: hold the processes
    dt_s_ = dt_s;
    clock_.advance(dt_s, rng_.normal(kClockStream, epoch_, Purpose::kClockDrift));
  }
  t_prev_ = t;
}

double World::multipath_m(int band, SatId sat, uint64_t stream, const time::GpsTime& t, uint64_t epoch,
                          double el_rad) noexcept {
  const ErrorModelConfig& c = config_.errors;
  if (!(c.multipath.sigma_m > 0.0)) return 0.0;
  const GaussMarkovConfig unit{1.0, c.multipath.tau_s};
  const std::size_t k = static_cast<std::size_t>(sat.index());
  const auto b = static_cast<std::size_t>(band);
  double& x = multipath_unit_[b][k];
  if (!multipath_started_[b][k]) {
    x = gauss_markov_init(unit, rng_.normal(stream, epoch, Purpose::kMultipathInit));
    multipath_started_[b][k] = true;
  } else {
    const double dt_s = t - multipath_t_[b][k];
    if (std::isfinite(dt_s) && dt_s > 0.0)
      x = gauss_markov_step(x, dt_s, unit, rng_.normal(stream, epoch, Purpose::kMultipathStep));
  }
  multipath_t_[b][k] = t;
  return c.multipath.sigma_m / multipath_sin_el(el_rad) * x;
}

void World::gradient_now(const SharedSky& sky, const time::GpsTime& t, double lon_rad) noexcept {
  const ErrorModelConfig::Gradient& g = config_.errors.gradient;
  const double sigma_m = g.process.sigma_m;
  gradient_now_m_ = {g.north_m + sigma_m * sky.errors().value(SkyProcess::kGradientNorth),
                     g.east_m + sigma_m * sky.errors().value(SkyProcess::kGradientEast)};
  if (g.north_diurnal_m == 0.0 && g.east_diurnal_m == 0.0) return;
  // Local time as in the Klobuchar model (IS-GPS-200 20.3.3.5.2.5): GPS time
  // plus 43200 s per semicircle of longitude; 2 pi per day.
  const double lt_rad = 2.0 * kPi * (t.tow_s() / kSecondsPerDay) + lon_rad;
  const double h_to_rad = 2.0 * kPi / 24.0;
  gradient_now_m_[0] += g.north_diurnal_m * std::cos(lt_rad - g.north_peak_h * h_to_rad);
  gradient_now_m_[1] += g.east_diurnal_m * std::cos(lt_rad - g.east_peak_h * h_to_rad);
}

// Stage 1 (sky): every satellite with an ephemeris above the horizon; those
// above the mask are listed in above_.
void World::sky_stage(const SharedSky& sky, const time::GpsTime& t, const Truth& truth, const Lla& rx_lla,
                      double mask_rad) noexcept {
  n_above_ = 0;
  const RxPlace rx = RxPlace::of(truth.pos_m, rx_lla);
  for (int i = 0; i < n_sats_ && n_in_sky_ < kMaxSatsInView; ++i) {
    const SatId sat = sats_[static_cast<std::size_t>(i)];
    if (!tracked_.has(sat.system)) continue;
    const orbit::Ephemeris* eph = sky.state(sat).eph;
    if (eph == nullptr) continue;
    const std::size_t k = static_cast<std::size_t>(sat.index());
    SkySat s;
    if (!sky_sat(sky, *eph, t, rx, truth.vel_m_s, s, light_time_guess(sky_[k], t))) continue;
    sky_[k] = s;
    eph_[k] = eph;
    scene_path_[k] = scene::SatPath{};
    in_sky_[static_cast<std::size_t>(n_in_sky_++)] = sat;
    if (s.el_rad >= mask_rad) above_[static_cast<std::size_t>(n_above_++)] = sat;
  }
}

// Stage 3 (propagation): the configured atmosphere along each line of sight
// above the mask. Slow terms come through the per-satellite cache; the
// Gauss–Markov perturbations are added every epoch.
void World::propagation_stage(const SharedSky& sky, const time::GpsTime& t, const Lla& rx_lla, const Ecef& rx_pos_m) noexcept {
  for (int i = 0; i < n_above_; ++i) path_[static_cast<std::size_t>(above_[i].index())] = PathEffects{};
  if (!atmosphere_.any_on()) return;
  // Cached terms belong to a place: moving far enough (height matters most,
  // the 5-degree tropo delay changes ~3 mm per metre) starts the cache over.
  if (!cache_pos_valid_ || std::fabs(rx_lla.height_m - cache_height_m_) > kCacheMaxHeightChange_m ||
      (rx_pos_m - cache_pos_m_).norm() > kCacheMaxMove_m) {
    cache_.clear();
    cache_pos_valid_ = true;
    cache_pos_m_ = rx_pos_m;
    cache_height_m_ = rx_lla.height_m;
  }
  const double tow_s = t.tow_s();
  const double doy = atmosphere_.tropo_on() ? t.fractional_day_of_year() : 1.0;
  const double iono_sigma_tecu = config_.atmosphere.ionosphere.perturbation.sigma;
  for (int i = 0; i < n_above_; ++i) {
    const SatId sat = above_[i];
    const std::size_t k = static_cast<std::size_t>(sat.index());
    const SkySat& s = sky_[k];
    const SlowTerms v =
        cache_.get(sat, t, [&] {
          ++atmosphere_evaluations_;
          return atmosphere_.slow_terms(rx_lla, s.az_rad, s.el_rad, tow_s, doy);
        });
    PathEffects& e = path_[k];
    if (atmosphere_.iono_on()) {
      // Computed at the configured frequency; the delay scales as 1 / f^2.
      const double f_ratio = config_.atmosphere.ionosphere.freq_hz / orbit::carrier_hz(*eph_[k]);
      const double tecu = iono_sigma_tecu * sky.errors().value(SkyProcess::kIono, sat);
      e.iono_m = std::max(v[kIonoM] * iono_factor_ + tecu * v[kIonoMPerTecu], 0.0) * (f_ratio * f_ratio);
    }
    if (atmosphere_.tropo_on()) e.tropo_m = std::max(v[kTropoM] + zwd_pert_m_ * v[kNmfWet], 0.0);
    e.delay_m = e.iono_m + e.tropo_m;
    e.loss_db = v[kAttenDb];
  }
}

// Stage 3b (propagation, buildings): direct, reflected only (extra path
// length and reflection loss join the atmosphere's), or not received.
void World::scene_stage(const Ecef& rx_pos_m) noexcept {
  if (!propagator_) return;
  for (int i = 0; i < n_above_; ++i) {
    const SkySat& s = sky_[static_cast<std::size_t>(above_[i].index())];
    scene_query_[i] =
        scene::SatQuery{above_[i].index(), scene_frame_->vector_to_enu((s.pos_m - rx_pos_m) / s.range_m)};
  }
  const auto n = static_cast<std::size_t>(n_above_);
  propagator_->compute(scene_frame_->to_enu(rx_pos_m), std::span<const scene::SatQuery>(scene_query_.data(), n),
                       std::span<scene::SatPath>(scene_out_.data(), n));
  for (int i = 0; i < n_above_; ++i) {
    const scene::SatPath& sp = scene_out_[i];
    const std::size_t k = static_cast<std::size_t>(above_[i].index());
    scene_path_[k] = sp;
    PathEffects& e = path_[k];
    if (sp.kind == scene::PathKind::kNone) {
      e.received = false;
    } else if (sp.kind == scene::PathKind::kNlos) {
      e.delay_m += sp.extra_delay_m;
      e.loss_db += sp.loss_db;
    }
  }
}

// Stage 4 (signal): C/N0 of every satellite above the mask from the link
// budget (0 when nothing is received), or the fixed elevation curve when the
// signal stage is off.
void World::signal_stage() noexcept {
  for (int i = 0; i < n_above_; ++i) {
    const std::size_t k = static_cast<std::size_t>(above_[i].index());
    const SkySat& s = sky_[k];
    const PathEffects& e = path_[k];
    const GnssSystem sys = above_[i].system;
    double cn0 = 0.0;
    if (!config_.signal.enabled) {
      const double one_m_sin = 1.0 - std::sin(s.el_rad);
      const signal::SystemSignal& ss = signal::system_signal(sys);
      cn0 = config_.nominal_cn0_dbhz - kCn0ElevationLoss_db * one_m_sin * one_m_sin - scene_path_[k].loss_db;
      if (ss.power_offset_db != 0.0 || ss.slope_offset_db != 0.0)
        cn0 += ss.power_offset_db + ss.slope_offset_db * one_m_sin;
    } else if (e.received) {
      cn0 = link_.cn0_dbhz(s.range_m, s.el_rad, e.loss_db, sys, orbit::carrier_hz(*eph_[k]));
    }
    cn0_dbhz_[k] = cn0;
  }
}

// Stage 5 (observables): every satellite in view (SatId order) with its path
// truth; pseudorange and Doppler of every received one.
void World::observables_stage(const SharedSky& sky, const time::GpsTime& t, uint64_t epoch, double mask_rad) noexcept {
  const double rx_clock_s = clock_.bias_s();
  const double rx_drift_s_s = clock_.drift_s_s();
  obs_.t_rx_local = t + rx_clock_s;
  for (int i = 0; i < n_in_sky_; ++i) {
    const SatId sat = in_sky_[static_cast<std::size_t>(i)];
    const std::size_t k = static_cast<std::size_t>(sat.index());
    const uint64_t stream = sat_stream(sat);
    const SkySat& s = sky_[k];
    SatObservable& o = obs_.sats[static_cast<std::size_t>(obs_.num_sats++)];
    o = SatObservable{};
    o.sat = sat;
    o.eph = eph_[k];
    o.az_rad = s.az_rad;
    o.el_rad = s.el_rad;
    o.above_mask = s.el_rad >= mask_rad;
    if (!o.above_mask) continue;
    const scene::SatPath& sp = scene_path_[k];
    o.blocked = sp.kind == scene::PathKind::kNone;
    o.nlos = sp.kind == scene::PathKind::kNlos;
    o.bounces = o.nlos ? sp.bounces : 0;
    o.nlos_delay_m = o.nlos ? sp.extra_delay_m : 0.0;
    o.received = path_[k].received;
    o.cn0_dbhz = cn0_dbhz_[k];
    if (!o.received) continue;
    const orbit::Ephemeris* eph = o.eph;
    const double cn0 = o.cn0_dbhz;
    const double thermal_m = noise_.code_sigma_m(cn0) * rng_.normal(stream, epoch, Purpose::kThermal);
    const double multipath = multipath_m(0, sat, stream, t, epoch, s.el_rad);
    const double orbit_clock_m = orbit_clock_process(config_.errors.orbit_clock, sat.system).sigma_m *
                                 sky.errors().value(SkyProcess::kOrbitClock, sat);
    const double gradient_m = gradient_now_m_[0] * std::cos(s.az_rad) + gradient_now_m_[1] * std::sin(s.az_rad);
    o.carrier_hz = orbit::carrier_hz(*eph);
    o.wavelength_m = kSpeedOfLight_m_s / o.carrier_hz;
    const double rr_noise_m_s =
        noise_.range_rate_sigma_m_s(cn0, o.wavelength_m) * rng_.normal(stream, epoch, Purpose::kDoppler);
    // The satellite's actual L1 clock = broadcast (dt_sv - TGD) + residual.
    const double pr_m = s.range_m + kSpeedOfLight_m_s * (rx_clock_s - (s.clk_bias_s - eph->tgd_s)) +
                        orbit_clock_m + path_[k].delay_m + thermal_m + multipath + gradient_m;
    const double rr_m_s = s.range_rate_m_s + kSpeedOfLight_m_s * (rx_drift_s_s - s.clk_drift_s_s) + rr_noise_m_s;
    o.pseudorange_m = pr_m;
    o.doppler_hz = -rr_m_s / o.wavelength_m;
    carrier_observable(o, s, epoch, rx_clock_s, orbit_clock_m, gradient_m, multipath);
    if (sbas_service_ != nullptr && sbas_corrects(sat.system)) sbas_estimates(o, t, epoch, orbit_clock_m, path_[k].iono_m);
    if (config_.bands > 1) second_signal(o, s, t, epoch, rx_clock_s, rx_drift_s_s, orbit_clock_m, gradient_m);
  }
  for (int b = 0; b < config_.bands; ++b) {
    const auto ub = static_cast<std::size_t>(b);
    for (int i = 0; i < n_sats_; ++i) {
      const std::size_t k = static_cast<std::size_t>(sats_[static_cast<std::size_t>(i)].index());
      if (!carrier_seen_[ub][k]) carrier_[ub][k].continuous = false;
    }
  }
}

void World::sbas_estimates(SatObservable& o, const time::GpsTime& t, uint64_t epoch, double orbit_clock_m,
                           double iono_m) noexcept {
  // Correlation time of the residuals: an estimate (docs/models.md "SBAS"):
  // the network's estimates are renewed every few minutes (long-term and
  // ionospheric messages, RTCA DO-229 Table A-8) and wander over a pass.
  constexpr GaussMarkovConfig kUnit{1.0, 600.0};
  const std::size_t k = static_cast<std::size_t>(o.sat.index());
  const uint64_t stream = sat_stream(o.sat);
  double& oc = sbas_unit_[0][k];
  double& io = sbas_unit_[1][k];
  if (!sbas_started_[k]) {
    oc = gauss_markov_init(kUnit, rng_.normal(stream, epoch, Purpose::kSbasOrbitClockInit));
    io = gauss_markov_init(kUnit, rng_.normal(stream, epoch, Purpose::kSbasIonoInit));
    sbas_started_[k] = true;
  } else {
    const double dt_s = t - sbas_t_[k];
    if (std::isfinite(dt_s) && dt_s > 0.0) {
      oc = gauss_markov_step(oc, dt_s, kUnit, rng_.normal(stream, epoch, Purpose::kSbasOrbitClockStep));
      io = gauss_markov_step(io, dt_s, kUnit, rng_.normal(stream, epoch, Purpose::kSbasIonoStep));
    }
  }
  sbas_t_[k] = t;
  const SbasService& s = *sbas_service_;
  const double f_ratio = kL1Freq_hz / o.carrier_hz;
  o.sbas_valid = true;
  o.sbas_orbit_clock_m = orbit_clock_m - s.sisre_m * oc;
  o.sbas_iono_m = iono_m + s.iono_vertical_m * sbas_obliquity(o.el_rad) * f_ratio * f_ratio * io;
}

double World::carrier_offset_cycles(CarrierTrack& c, uint64_t stream, uint64_t epoch, bool restart, double sigma_rad,
                                    bool pilot, bool nlos) noexcept {
  const CarrierConfig& cc = config_.carrier;
  restart = restart || !c.continuous;
  double slip_cycles = 0.0;
  if (!restart) {
    if (nlos != c.nlos) {
      restart = true;  // a different path: the loop re-locks on it
    } else if (rng_.uniform(stream, epoch, Purpose::kCycleSlip, 0) <
               cycle_slip_probability(sigma_rad, cc.pll_bandwidth_hz, dt_s_)) {
      // A Costas loop slips by half a cycle, a pilot's pure PLL by a whole one.
      const double size = pilot ? 1.0 : 0.5;
      slip_cycles = rng_.uniform(stream, epoch, Purpose::kCycleSlip, 1) < 0.5 ? -size : size;
    }
  }
  if (restart) {
    // A new lock starts from an arbitrary whole number of cycles; a Costas
    // loop locks on either data sign, so half a cycle off as often as not
    // (until the frame preamble tells the receiver which).
    c.offset_cycles = std::floor(2.0e5 * rng_.uniform(stream, epoch, Purpose::kCarrierAmbiguity, 0)) - 1.0e5;
    c.half_cycle = !pilot && rng_.uniform(stream, epoch, Purpose::kLockHalfCycle, 0) < 0.5;
    if (c.half_cycle) c.offset_cycles += 0.5;
    ++c.discontinuities;
  } else if (slip_cycles != 0.0) {
    c.offset_cycles += slip_cycles;
    c.half_cycle = c.half_cycle != (std::fabs(slip_cycles) < 1.0);
    ++c.discontinuities;
  }
  c.continuous = true;
  c.nlos = nlos;
  return c.offset_cycles;
}

// The second signal: the first's geometry, clocks, troposphere and path, its
// own carrier, ionosphere (1 / f^2), group delays, C/N0, noise, multipath and lock.
void World::second_signal(SatObservable& o, const SkySat& s, const time::GpsTime& t, uint64_t epoch,
                          double rx_clock_s, double rx_drift_s_s, double orbit_clock_m, double gradient_m) noexcept {
  const std::optional<SignalId> sig = signal_of(o.sat.system, 1);
  if (!sig) return;
  const std::size_t k = static_cast<std::size_t>(o.sat.index());
  const uint64_t stream = band_stream(o.sat, 1);
  const orbit::Ephemeris& eph = *o.eph;
  SecondSignal& b = o.band1;
  b.received = true;
  b.cn0_dbhz = std::max(o.cn0_dbhz + band1_power_offset_db(o.sat.system), 0.0);
  b.carrier_hz = signal_carrier_hz(*sig, eph.glo_channel);
  b.wavelength_m = kSpeedOfLight_m_s / b.carrier_hz;
  const double f_ratio = o.carrier_hz / b.carrier_hz;
  const double gamma = f_ratio * f_ratio;
  const PathEffects& e = path_[k];
  const double iono_m = e.iono_m * gamma;
  const double common_m = s.range_m + kSpeedOfLight_m_s * (rx_clock_s - (s.clk_bias_s - band1_group_delay_s(eph, gamma))) +
                          orbit_clock_m + (e.delay_m - e.iono_m) + gradient_m;
  const double thermal_m = noise_.code_sigma_m(b.cn0_dbhz) * rng_.normal(stream, epoch, Purpose::kThermal);
  const double multipath = multipath_m(1, o.sat, stream, t, epoch, s.el_rad);
  b.pseudorange_m = common_m + iono_m + thermal_m + multipath + config_.receiver_ifb_m;
  const double rr_noise_m_s =
      noise_.range_rate_sigma_m_s(b.cn0_dbhz, b.wavelength_m) * rng_.normal(stream, epoch, Purpose::kDoppler);
  b.doppler_hz = -(s.range_rate_m_s + kSpeedOfLight_m_s * (rx_drift_s_s - s.clk_drift_s_s) + rr_noise_m_s) / b.wavelength_m;
  const CarrierConfig& cc = config_.carrier;
  if (!cc.enabled) return;
  CarrierTrack& c = carrier_[1][k];
  carrier_seen_[1][k] = true;
  const double sigma_rad =
      std::hypot(pll_jitter_rad(b.cn0_dbhz, cc.pll_bandwidth_hz, cc.integration_s), cc.oscillator_sigma_rad);
  const double offset = carrier_offset_cycles(c, stream, epoch, o.lock_break, sigma_rad, signal_info(*sig).pilot, o.nlos);
  b.carrier_discontinuities = c.discontinuities;
  b.carrier_half_cycle = c.half_cycle;
  const double phase_noise_m =
      sigma_rad / (2.0 * kPi) * b.wavelength_m * rng_.normal(stream, epoch, Purpose::kCarrierNoise);
  const double carrier_m = common_m - iono_m + phase_noise_m + carrier_multipath_m(multipath, b.wavelength_m);
  b.carrier_valid = true;
  b.carrier_phase_cycles = carrier_m / b.wavelength_m + offset;
}

// The carrier range has the code's delays except the ionosphere's, which
// advances the phase by as much as it delays the code; code multipath and
// thermal code noise are not in it, the NLOS path length is.
void World::carrier_observable(SatObservable& o, const SkySat& s, uint64_t epoch, double rx_clock_s,
                               double orbit_clock_m, double gradient_m, double multipath_m) noexcept {
  const std::size_t k = static_cast<std::size_t>(o.sat.index());
  const uint64_t stream = sat_stream(o.sat);
  CarrierTrack& c = carrier_[0][k];
  carrier_seen_[0][k] = true;
  const CarrierConfig& cc = config_.carrier;
  // No carrier tracking: no phase, so no lock breaks or slips to model.
  if (!cc.enabled) return;
  // Lock break: the range moved by more than its rate explains.
  if (c.continuous && dt_s_ > 0.0) {
    const double explained_m = 0.5 * (c.range_rate_m_s + s.range_rate_m_s) * dt_s_;
    o.lock_break = std::fabs(s.range_m - c.range_m - explained_m) > cc.lock_break_m;
  }
  const double sigma_rad =
      std::hypot(pll_jitter_rad(o.cn0_dbhz, cc.pll_bandwidth_hz, cc.integration_s), cc.oscillator_sigma_rad);
  const std::optional<SignalId> sig = signal_of(o.sat.system, 0);
  const bool pilot = sig && signal_info(*sig).pilot;
  const double offset = carrier_offset_cycles(c, stream, epoch, o.lock_break, sigma_rad, pilot, o.nlos);
  c.range_m = s.range_m;
  c.range_rate_m_s = s.range_rate_m_s;
  o.carrier_discontinuities = c.discontinuities;
  o.carrier_half_cycle = c.half_cycle;
  const PathEffects& e = path_[k];
  const double phase_noise_m =
      sigma_rad / (2.0 * kPi) * o.wavelength_m * rng_.normal(stream, epoch, Purpose::kCarrierNoise);
  const double carrier_m = s.range_m + kSpeedOfLight_m_s * (rx_clock_s - (s.clk_bias_s - o.eph->tgd_s)) +
                           orbit_clock_m + e.delay_m - 2.0 * e.iono_m + gradient_m + phase_noise_m +
                           carrier_multipath_m(multipath_m, o.wavelength_m);
  o.carrier_valid = true;
  o.carrier_phase_cycles = carrier_m / o.wavelength_m + offset;
}

const Observables& World::step(const time::GpsTime& t, const Truth& truth, double mask_rad) noexcept {
  own_sky_.update(t, std::span<const Ecef>(&truth.pos_m, 1), tracked_);
  return step(own_sky_, truth, mask_rad);
}

const Observables& World::step(const SharedSky& sky, const Truth& truth, double mask_rad) noexcept {
  const time::GpsTime t = sky.t();
  advance(sky, t);
  const uint64_t epoch = epoch_++;
  obs_.sky = &sky;

  obs_.t = t;
  // The world's noise floor, as MON-HW reports it; with the signal stage off
  // the C/N0 curve is fixed, so the receiver sees a quiet sky.
  obs_.noise_rise_db = config_.signal.enabled ? config_.signal.link.environment_noise_rise_db : kQuietNoiseRise_db;
  obs_.clock_bias_s = clock_.bias_s();
  obs_.clock_drift_s_s = clock_.drift_s_s();
  obs_.num_sats = 0;
  n_in_sky_ = 0;
  n_above_ = 0;
  for (auto& seen : carrier_seen_) seen.fill(false);
  obs_.antenna_connected = truth.valid && truth.pos_m.finite() && truth.vel_m_s.finite();
  if (!obs_.antenna_connected) {
    for (auto& band : carrier_)
      for (CarrierTrack& c : band) c.continuous = false;
    return obs_;
  }

  const Lla rx_lla = geo::lla_from_ecef(truth.pos_m);
  sbas_service_ = sbas_service_at(rx_lla);
  gradient_now(sky, t, rx_lla.lon_rad);
  sky_stage(sky, t, truth, rx_lla, mask_rad);
  propagation_stage(sky, t, rx_lla, truth.pos_m);
  scene_stage(truth.pos_m);
  signal_stage();
  observables_stage(sky, t, epoch, mask_rad);
  return obs_;
}

}  // namespace gnssemu::world
