#include "core/receiver/receiver.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/geo/geoid.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::receiver {

namespace {

// Accuracy reported without a fix (u-blox reports huge hAcc; NMEA GST prints it).
constexpr double kNoFixAccuracy_m = 9999.0;
constexpr double kNoFixSpeedAccuracy_m_s = 999.0;
constexpr double kNoFixTimeAccuracy_s = 1.0;
// C/N0 shape when the signal stage is off: nominal at zenith, about -8 dB at 5 degrees.
constexpr double kCn0ElevationLoss_db = 10.0;
// A tracked satellite always reports a positive C/N0 (0 means "not tracked"
// in GSV / NAV-SAT), dB-Hz.
constexpr double kMinReportedCn0_dbhz = 1.0;
// Cached atmospheric terms are dropped when the receiver moves this much
// vertically or in total (m): a 5 m height change moves the 5-degree tropo
// delay by ~1.5 cm; 5 km moves a pierce point by < 1 % of its scale.
constexpr double kCacheMaxHeightChange_m = 5.0;
constexpr double kCacheMaxMove_m = 5000.0;
// Elevation floor of the multipath 1 / sin(el) scaling (ReceiverConfig doc), rad.
constexpr double kMultipathMinEl_rad = 5.0 * kDegToRad;

void check(bool ok, const std::string& what) {
  if (!ok) throw Error("receiver config: " + what);
}

void validate(const ReceiverConfig& c) {
  check(c.elevation_mask_rad >= 0.0 && c.elevation_mask_rad < kPi / 2.0,
        "elevation_mask_rad must be in [0, pi/2)");
  const ErrorModelConfig& e = c.errors;
  check(std::isfinite(e.thermal_sigma_m) && e.thermal_sigma_m >= 0.0, "errors.thermal_sigma_m must be >= 0");
  check(std::isfinite(e.orbit_clock.sigma_m) && e.orbit_clock.sigma_m >= 0.0,
        "errors.orbit_clock.sigma_m must be >= 0");
  check(std::isfinite(e.orbit_clock.tau_s) && e.orbit_clock.tau_s > 0.0, "errors.orbit_clock.tau_s must be > 0");
  check(std::isfinite(e.multipath.sigma_m) && e.multipath.sigma_m >= 0.0, "errors.multipath.sigma_m must be >= 0");
  check(std::isfinite(e.multipath.tau_s) && e.multipath.tau_s > 0.0, "errors.multipath.tau_s must be > 0");
  check(std::isfinite(e.gradient.north_m) && std::isfinite(e.gradient.east_m),
        "errors.gradient.north_m / east_m must be finite");
  check(std::isfinite(e.gradient.north_diurnal_m) && e.gradient.north_diurnal_m >= 0.0 &&
            std::isfinite(e.gradient.east_diurnal_m) && e.gradient.east_diurnal_m >= 0.0,
        "errors.gradient.north_diurnal_m / east_diurnal_m must be >= 0");
  check(e.gradient.north_peak_h >= 0.0 && e.gradient.north_peak_h < 24.0 && e.gradient.east_peak_h >= 0.0 &&
            e.gradient.east_peak_h < 24.0,
        "errors.gradient.north_peak_h / east_peak_h must be in [0, 24) h");
  check(std::isfinite(e.gradient.process.sigma_m) && e.gradient.process.sigma_m >= 0.0,
        "errors.gradient.sigma_m must be >= 0");
  check(std::isfinite(e.gradient.process.tau_s) && e.gradient.process.tau_s > 0.0,
        "errors.gradient.tau_s must be > 0");
  check(std::isfinite(e.doppler_sigma_m_s) && e.doppler_sigma_m_s >= 0.0, "errors.doppler_sigma_m_s must be >= 0");
  const ClockConfig& k = c.clock;
  check(std::isfinite(k.bias_s) && std::fabs(k.bias_s) < 1.0, "clock.bias_s must be finite and below 1 s");
  check(std::isfinite(k.drift_s_s) && std::fabs(k.drift_s_s) < 1e-3, "clock.drift_s_s must be below 1e-3");
  check(std::isfinite(k.drift_noise_s_s_sqrt_s) && k.drift_noise_s_s_sqrt_s >= 0.0,
        "clock.drift_noise_s_s_sqrt_s must be >= 0");
  check(std::isfinite(k.jump_threshold_s) && k.jump_threshold_s >= 0.0 && k.jump_threshold_s < 1.0,
        "clock.jump_threshold_s must be in [0, 1)");
  check(std::isfinite(c.nominal_cn0_dbhz) && c.nominal_cn0_dbhz > 0.0, "nominal_cn0_dbhz must be > 0");
  check(std::isfinite(c.max_pdop) && c.max_pdop > 0.0, "max_pdop must be > 0");
  check(c.max_channels >= 1 && c.max_channels <= kMaxGpsPrn, "max_channels must be in [1, 32]");
  const SolverConfig& s = c.solver;
  check(std::isfinite(s.sigma_a_m) && std::isfinite(s.sigma_b_m) && s.sigma_a_m >= 0.0 && s.sigma_b_m >= 0.0 &&
            s.sigma_a_m + s.sigma_b_m > 0.0,
        "solver.sigma_a_m / sigma_b_m must be >= 0 and not both 0");
  check(std::isfinite(s.sigma_range_rate_m_s) && s.sigma_range_rate_m_s > 0.0,
        "solver.sigma_range_rate_m_s must be > 0");
  check(std::isfinite(s.height_hold_sigma_m) && s.height_hold_sigma_m > 0.0,
        "solver.height_hold_sigma_m must be > 0");
  check(s.residual_test_pfa >= 0.0 && s.residual_test_pfa < 0.5, "solver.residual_test_pfa must be in [0, 0.5)");
  check(s.max_exclusions >= 0 && s.max_exclusions <= kMaxGpsPrn, "solver.max_exclusions must be in [0, 32]");
  check(s.max_iterations >= 1 && s.max_iterations <= 100, "solver.max_iterations must be in [1, 100]");
  check(std::isfinite(s.sigma_c_m_sqrt_hz) && s.sigma_c_m_sqrt_hz >= 0.0, "solver.sigma_c_m_sqrt_hz must be >= 0");
  const AtmosphereConfig& a = c.atmosphere;
  check(std::isfinite(a.zwd_perturbation.sigma_m) && a.zwd_perturbation.sigma_m >= 0.0,
        "atmosphere.zwd_perturbation.sigma_m must be >= 0");
  check(std::isfinite(a.zwd_perturbation.tau_s) && a.zwd_perturbation.tau_s > 0.0,
        "atmosphere.zwd_perturbation.tau_s must be > 0");
  signal::validate(c.signal.tracking);
  signal::validate(c.signal.dll);
}

const ReceiverConfig& validated(const ReceiverConfig& c) {
  validate(c);
  return c;
}

}  // namespace

Receiver::Receiver(const orbit::EphemerisStore& store, const ReceiverConfig& config)
    : store_(store),
      config_(validated(config)),
      rng_(config.seed),
      clock_(config.clock),
      atmosphere_(config.atmosphere),
      cache_(config.atmosphere.cache_refresh_s, config.atmosphere.cache_mode),
      link_(config.signal.link),
      solver_(config.solver, config.max_pdop) {
  no_fix_epoch();
}

void Receiver::attach_scene(const scene::Scene& scene, const Lla& origin, const scene::SearchConfig& search) {
  propagator_ = std::make_unique<scene::Propagator>(scene, search);
  scene_frame_ = std::make_unique<geo::LocalFrame>(origin);
  scene_path_.fill(scene::SatPath{});
}

void Receiver::set_klobuchar(const orbit::KlobucharParams& p) {
  for (double v : p.alpha) check(std::isfinite(v), "Klobuchar alpha must be finite");
  for (double v : p.beta) check(std::isfinite(v), "Klobuchar beta must be finite");
  solver_.set_klobuchar(p);
  atmosphere_.set_klobuchar_shape(p);
  cache_.clear();
}

void Receiver::advance_world(const time::GpsTime& t) noexcept {
  const GaussMarkovConfig& gm = config_.errors.orbit_clock;
  const bool iono_gm = atmosphere_.iono_on() && config_.atmosphere.ionosphere.perturbation.sigma > 0.0;
  const GaussMarkovConfig iono_cfg{config_.atmosphere.ionosphere.perturbation.sigma,
                                   config_.atmosphere.ionosphere.perturbation.tau_s};
  const bool zwd_gm = atmosphere_.tropo_on() && config_.atmosphere.zwd_perturbation.sigma_m > 0.0;
  const GaussMarkovConfig& zwd_cfg = config_.atmosphere.zwd_perturbation;
  const bool mp = config_.errors.multipath.sigma_m > 0.0;
  const GaussMarkovConfig mp_unit{1.0, config_.errors.multipath.tau_s};
  const GaussMarkovConfig& grad = config_.errors.gradient.process;
  const bool grad_gm = grad.sigma_m > 0.0;
  if (!started_) {
    if (grad_gm)
      for (int c = 0; c < 2; ++c)
        gradient_m_[c] = gauss_markov_init(grad, rng_.normal(kGradientStream + c, 0, Purpose::kGradientInit));
    if (mp)
      for (int p = 1; p <= kMaxGpsPrn; ++p)
        multipath_unit_[p - 1] = gauss_markov_init(mp_unit, rng_.normal(p, 0, Purpose::kMultipathInit));
    for (int p = 1; p <= kMaxGpsPrn; ++p)
      orbit_clock_m_[p - 1] = gauss_markov_init(gm, rng_.normal(p, 0, Purpose::kGaussMarkovInit));
    if (iono_gm)
      for (int p = 1; p <= kMaxGpsPrn; ++p)
        iono_tecu_[p - 1] = gauss_markov_init(iono_cfg, rng_.normal(p, 0, Purpose::kIonoInit));
    if (zwd_gm) zwd_pert_m_ = gauss_markov_init(zwd_cfg, rng_.normal(kClockStream, 0, Purpose::kTropoInit));
    started_ = true;
    dt_s_ = 0.0;
  } else {
    double dt_s = t - t_prev_;
    if (!std::isfinite(dt_s) || dt_s < 0.0) dt_s = 0.0;  // time going back: hold the processes
    dt_s_ = dt_s;
    for (int p = 1; p <= kMaxGpsPrn; ++p)
      orbit_clock_m_[p - 1] =
          gauss_markov_step(orbit_clock_m_[p - 1], dt_s, gm, rng_.normal(p, epoch_, Purpose::kGaussMarkovStep));
    if (iono_gm && dt_s > 0.0)
      for (int p = 1; p <= kMaxGpsPrn; ++p)
        iono_tecu_[p - 1] =
            gauss_markov_step(iono_tecu_[p - 1], dt_s, iono_cfg, rng_.normal(p, epoch_, Purpose::kIonoStep));
    if (grad_gm && dt_s > 0.0)
      for (int c = 0; c < 2; ++c)
        gradient_m_[c] = gauss_markov_step(gradient_m_[c], dt_s, grad,
                                           rng_.normal(kGradientStream + c, epoch_, Purpose::kGradientStep));
    if (mp && dt_s > 0.0)
      for (int p = 1; p <= kMaxGpsPrn; ++p)
        multipath_unit_[p - 1] = gauss_markov_step(multipath_unit_[p - 1], dt_s, mp_unit,
                                                   rng_.normal(p, epoch_, Purpose::kMultipathStep));
    if (zwd_gm && dt_s > 0.0)
      zwd_pert_m_ = gauss_markov_step(zwd_pert_m_, dt_s, zwd_cfg, rng_.normal(kClockStream, epoch_, Purpose::kTropoStep));
    clock_.advance(dt_s, rng_.normal(kClockStream, epoch_, Purpose::kClockDrift));
  }
  t_prev_ = t;
}

void Receiver::gradient_now(const time::GpsTime& t, double lon_rad) noexcept {
  const ErrorModelConfig::Gradient& g = config_.errors.gradient;
  gradient_now_m_ = {g.north_m + gradient_m_[0], g.east_m + gradient_m_[1]};
  if (g.north_diurnal_m == 0.0 && g.east_diurnal_m == 0.0) return;
  // Local time as in the Klobuchar model (IS-GPS-200 20.3.3.5.2.5): GPS time
  // plus 43200 s per semicircle of longitude; 2 pi per day.
  const double lt_rad = 2.0 * kPi * (t.tow_s() / kSecondsPerDay) + lon_rad;
  const double h_to_rad = 2.0 * kPi / 24.0;
  gradient_now_m_[0] += g.north_diurnal_m * std::cos(lt_rad - g.north_peak_h * h_to_rad);
  gradient_now_m_[1] += g.east_diurnal_m * std::cos(lt_rad - g.east_peak_h * h_to_rad);
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
  fix_.h_acc_m = fix_.v_acc_m = kNoFixAccuracy_m;
  fix_.speed_acc_m_s = kNoFixSpeedAccuracy_m_s;
  fix_.time_acc_s = kNoFixTimeAccuracy_s;
  for (int i = 0; i < fix_.num_sats; ++i) {
    fix_.sats[i].used = false;
    fix_.sats[i].residual_m = 0.0;
  }
}

// Stage 1 (sky): every satellite with an ephemeris above the horizon; returns
// the number above the mask (listed in above_).
int Receiver::sky_stage(const time::GpsTime& t, const Truth& truth, const Lla& rx_lla) noexcept {
  n_above_ = 0;
  for (int p = 1; p <= kMaxGpsPrn; ++p) {
    const orbit::Ephemeris* eph = store_.select(p, t);
    if (eph == nullptr) continue;
    const SkySat s = sky_sat(*eph, t, truth.pos_m, rx_lla, truth.vel_m_s);
    if (!(s.el_rad > 0.0)) continue;
    sky_[p - 1] = s;
    in_sky_[p - 1] = true;
    if (s.el_rad >= config_.elevation_mask_rad) above_[n_above_++] = p;
  }
  return n_above_;
}

// Stage 3 (propagation): the configured atmosphere along each line of sight
// above the mask. Slow terms come through the per-satellite cache; the
// Gauss–Markov perturbations are added every epoch.
void Receiver::propagation_stage(const time::GpsTime& t, const Lla& rx_lla, const Ecef& rx_pos_m) noexcept {
  for (int i = 0; i < n_above_; ++i) path_[above_[i] - 1] = PathEffects{};
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
  for (int i = 0; i < n_above_; ++i) {
    const int p = above_[i];
    const SkySat& s = sky_[p - 1];
    const SlowTerms v =
        cache_.get(p, t, [&] {
          ++atmosphere_evaluations_;
          return atmosphere_.slow_terms(rx_lla, s.az_rad, s.el_rad, tow_s, doy);
        });
    PathEffects& e = path_[p - 1];
    if (atmosphere_.iono_on()) e.iono_m = std::max(v[kIonoM] + iono_tecu_[p - 1] * v[kIonoMPerTecu], 0.0);
    if (atmosphere_.tropo_on()) e.tropo_m = std::max(v[kTropoM] + zwd_pert_m_ * v[kNmfWet], 0.0);
    e.delay_m = e.iono_m + e.tropo_m;
    e.loss_db = v[kAttenDb];
  }
}

// Stage 3b (propagation, buildings): direct, reflected only (extra path
// length and reflection loss join the atmosphere's), or not received.
void Receiver::scene_stage(const Ecef& rx_pos_m) noexcept {
  scene_path_.fill(scene::SatPath{});
  if (!propagator_) return;
  for (int i = 0; i < n_above_; ++i) {
    const SkySat& s = sky_[above_[i] - 1];
    scene_query_[i] = scene::SatQuery{above_[i], scene_frame_->vector_to_enu((s.pos_m - rx_pos_m) / s.range_m)};
  }
  const auto n = static_cast<std::size_t>(n_above_);
  propagator_->compute(scene_frame_->to_enu(rx_pos_m), std::span<const scene::SatQuery>(scene_query_.data(), n),
                       std::span<scene::SatPath>(scene_out_.data(), n));
  for (int i = 0; i < n_above_; ++i) {
    const scene::SatPath& sp = scene_out_[i];
    scene_path_[above_[i] - 1] = sp;
    PathEffects& e = path_[above_[i] - 1];
    if (sp.kind == scene::PathKind::kNone) {
      e.received = false;
    } else if (sp.kind == scene::PathKind::kNlos) {
      e.delay_m += sp.extra_delay_m;
      e.loss_db += sp.loss_db;
    }
  }
}

// Stage 4 (signal): C/N0 from the link budget, acquisition / loss with
// hysteresis, then the channel limit (highest elevations first).
void Receiver::signal_stage() noexcept {
  tracked_.fill(false);
  std::array<bool, kMaxGpsPrn> above{};
  for (int i = 0; i < n_above_; ++i) above[above_[i] - 1] = true;
  for (int p = 1; p <= kMaxGpsPrn; ++p) {
    if (!above[p - 1]) {
      tracking_[p - 1].reset();
      cn0_dbhz_[p - 1] = 0.0;
    }
  }
  int n_tracked = 0;
  std::array<int, kMaxGpsPrn> tracked_prn{};
  for (int i = 0; i < n_above_; ++i) {
    const int p = above_[i];
    const SkySat& s = sky_[p - 1];
    const PathEffects& e = path_[p - 1];
    bool ok = false;
    double cn0 = 0.0;
    if (!config_.signal.enabled) {
      const double one_m_sin = 1.0 - std::sin(s.el_rad);
      cn0 = config_.nominal_cn0_dbhz - kCn0ElevationLoss_db * one_m_sin * one_m_sin - scene_path_[p - 1].loss_db;
      ok = e.received;
    } else if (e.received) {
      cn0 = link_.cn0_dbhz(s.range_m, s.el_rad, e.loss_db);
      ok = tracking_[p - 1].update(cn0, dt_s_, config_.signal.tracking);
    } else {
      tracking_[p - 1].reset();
    }
    cn0_dbhz_[p - 1] = cn0;
    if (ok) tracked_prn[n_tracked++] = p;
  }
  if (n_tracked > config_.max_channels) {
    std::sort(tracked_prn.begin(), tracked_prn.begin() + n_tracked, [this](int a, int b) {
      const double ea = sky_[a - 1].el_rad, eb = sky_[b - 1].el_rad;
      return ea != eb ? ea > eb : a < b;
    });
    for (int i = config_.max_channels; i < n_tracked; ++i) tracking_[tracked_prn[i] - 1].reset();
    n_tracked = config_.max_channels;
  }
  for (int i = 0; i < n_tracked; ++i) tracked_[tracked_prn[i] - 1] = true;
}

// Stage 5 (observables): pseudorange and Doppler of the tracked satellites,
// listed with every satellite in view in fix_.sats (PRN order).
void Receiver::observables_stage(const time::GpsTime& t, uint64_t epoch) noexcept {
  const double rx_clock_s = clock_.bias_s();
  const double rx_drift_s_s = clock_.drift_s_s();
  const bool dll = config_.errors.thermal_model == ThermalModel::kDll;
  in_.t_rx_local = t + rx_clock_s;
  in_.doy = in_.t_rx_local.fractional_day_of_year();
  in_.num_meas = 0;
  for (int p = 1; p <= kMaxGpsPrn; ++p) {
    if (!in_sky_[p - 1]) continue;
    const SkySat& s = sky_[p - 1];
    SatInfo& si = fix_.sats[fix_.num_sats++];
    si = SatInfo{};
    si.prn = p;
    si.az_rad = s.az_rad;
    si.el_rad = s.el_rad;
    si.healthy = true;
    si.above_mask = s.el_rad >= config_.elevation_mask_rad;
    if (si.above_mask) ++fix_.num_visible;
    const scene::SatPath& sp = scene_path_[p - 1];
    si.blocked = si.above_mask && sp.kind == scene::PathKind::kNone;
    si.nlos = si.above_mask && sp.kind == scene::PathKind::kNlos;
    si.bounces = si.nlos ? sp.bounces : 0;
    si.nlos_delay_m = si.nlos ? sp.extra_delay_m : 0.0;
    if (!tracked_[p - 1]) continue;
    const orbit::Ephemeris* eph = store_.select(p, t);
    const double cn0 = cn0_dbhz_[p - 1];
    const double sigma_m = dll ? signal::dll_thermal_sigma_m(cn0, config_.signal.dll) : config_.errors.thermal_sigma_m;
    const double thermal_m = sigma_m * rng_.normal(p, epoch, Purpose::kThermal);
    const double multipath_m =
        config_.errors.multipath.sigma_m > 0.0
            ? config_.errors.multipath.sigma_m / std::sin(std::max(s.el_rad, kMultipathMinEl_rad)) * multipath_unit_[p - 1]
            : 0.0;
    const double gradient_m = gradient_now_m_[0] * std::cos(s.az_rad) + gradient_now_m_[1] * std::sin(s.az_rad);
    const double rr_noise_m_s = config_.errors.doppler_sigma_m_s * rng_.normal(p, epoch, Purpose::kDoppler);
    // The satellite's actual L1 clock = broadcast (dt_sv - TGD) + residual.
    const double pr_m = s.range_m + kSpeedOfLight_m_s * (rx_clock_s - (s.clk_bias_s - eph->tgd_s)) +
                        orbit_clock_m_[p - 1] + path_[p - 1].delay_m + thermal_m + multipath_m + gradient_m;
    const double rr_m_s = s.range_rate_m_s + kSpeedOfLight_m_s * (rx_drift_s_s - s.clk_drift_s_s) + rr_noise_m_s;
    si.tracked = true;
    si.cn0_dbhz = std::max(cn0, kMinReportedCn0_dbhz);
    si.pseudorange_m = pr_m;
    si.doppler_hz = -rr_m_s / kL1Wavelength_m;
    ++fix_.num_tracked;
    Measurement& m = in_.meas[in_.num_meas];
    m.eph = eph;
    m.pseudorange_m = si.pseudorange_m;
    m.doppler_hz = si.doppler_hz;
    m.cn0_dbhz = si.cn0_dbhz;
    meas_prn_[in_.num_meas++] = p;
  }
}

const Fix& Receiver::step(const time::GpsTime& t, const Truth& truth) noexcept {
  advance_world(t);
  const uint64_t epoch = epoch_++;

  fix_.t = t;
  // The world's noise floor, as MON-HW reports it; with the signal stage off
  // the C/N0 curve is fixed, so the receiver sees a quiet sky.
  fix_.noise_rise_db = config_.signal.enabled ? config_.signal.link.environment_noise_rise_db : Fix{}.noise_rise_db;
  fix_.leap_seconds = leap_override_ ? leap_s_ : time::leap_seconds_at(t);
  fix_.in_leap_second = !leap_override_ && time::in_inserted_leap_second(t);  // a fixed count never steps
  fix_.num_sats = fix_.num_visible = fix_.num_tracked = 0;
  in_sky_.fill(false);

  if (!truth.valid || !truth.pos_m.finite() || !truth.vel_m_s.finite()) {
    fix_.time_valid = time_valid_;
    for (signal::TrackingState& s : tracking_) s.reset();  // antenna lost: lock lost
    no_fix_epoch();
    return fix_;
  }
  time_valid_ = true;
  fix_.time_valid = true;

  const Lla rx_lla = geo::lla_from_ecef(truth.pos_m);
  gradient_now(t, rx_lla.lon_rad);
  sky_stage(t, truth, rx_lla);
  propagation_stage(t, rx_lla, truth.pos_m);
  scene_stage(truth.pos_m);
  signal_stage();
  observables_stage(t, epoch);

  // Stage 7 (receiver): its own corrections and solution.
  in_.have_prior = have_fix_;
  if (have_fix_) {
    double dt_s = t - last_fix_t_;
    if (!std::isfinite(dt_s) || std::fabs(dt_s) > 600.0) dt_s = 0.0;
    in_.prior_pos_m = Ecef(last_pos_m_ + last_vel_m_s_ * dt_s);
    in_.prior_clock_m = last_clock_m_ + last_drift_m_s_ * dt_s;
  }
  in_.have_held_height = have_3d_;
  in_.held_pos_m = held_pos_m_;
  in_.held_height_m = held_height_m_;
  solver_.solve(in_, out_);
  fill_solution();
  return fix_;
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
  f.dop = out_.dop;
  f.num_used = out_.num_used;
  f.sigma_uere_m = out_.sigma_uere_m;
  f.range_rms_m = out_.range_rms_m;
  const auto& q = out_.cov_pos;
  const auto& qv = out_.cov_vel;
  f.sigma_e_m = std::sqrt(q[0][0]);
  f.sigma_n_m = std::sqrt(q[1][1]);
  f.sigma_u_m = std::sqrt(q[2][2]);
  f.h_acc_m = std::sqrt(q[0][0] + q[1][1]);
  f.v_acc_m = f.sigma_u_m;
  f.speed_acc_m_s = std::sqrt(qv[0][0] + qv[1][1] + qv[2][2]);
  f.time_acc_s = std::sqrt(q[3][3]) / kSpeedOfLight_m_s;
  // Measurements were taken in PRN order, as were fix_.sats.
  int k = 0;
  for (int i = 0; i < f.num_sats && k < in_.num_meas; ++i) {
    SatInfo& si = f.sats[i];
    if (si.prn != meas_prn_[k]) continue;
    si.used = !out_.excluded[k];  // excluded by the residual test: tracked, not used
    si.residual_m = out_.residual_m[k++];
  }

  have_fix_ = true;
  last_fix_t_ = f.t;
  last_pos_m_ = f.pos_m;
  last_vel_m_s_ = f.vel_m_s;
  last_clock_m_ = out_.clock_m;
  last_drift_m_s_ = out_.drift_m_s;
  if (f.type == FixType::k3D) {
    have_3d_ = true;
    held_pos_m_ = f.pos_m;
    held_height_m_ = f.lla.height_m;
  }
}

}  // namespace gnssemu::receiver
