// SPDX-License-Identifier: Apache-2.0
// [receiver] and its sub-tables: the receiver's own settings and the
// world's error processes and oscillator. Ranges: the core's.
#include <array>
#include <limits>

#include "config/keys/config_keys.hpp"
#include "config/setup/device_setup.hpp"

namespace gnssemu::config::detail {

namespace {

using receiver::AcquisitionConfig;
using receiver::NavFilterConfig;
using receiver::OperationalLimits;
using receiver::ReceiverConfig;
using receiver::SolverConfig;
using world::ClockConfig;
using world::ErrorModelConfig;
using world::GaussMarkovConfig;
using world::WorldConfig;
using Gm = world::GaussMarkovRanges;
using Gradient = ErrorModelConfig::Gradient;

constexpr Choice<world::ThermalModel> kThermalModels[] = {{"dll", world::ThermalModel::kDll},
                                                          {"fixed", world::ThermalModel::kFixed}};
constexpr Choice<atmosphere::IonoCorrection> kIonoCorrections[] = {
    {"klobuchar", atmosphere::IonoCorrection::kKlobuchar}, {"none", atmosphere::IonoCorrection::kNone}};
constexpr Choice<atmosphere::TropoCorrection> kTropoCorrections[] = {
    {"saastamoinen", atmosphere::TropoCorrection::kSaastamoinenNiell},
    {"zhd_niell", atmosphere::TropoCorrection::kZhdNiell},
    {"saastamoinen_cosz", atmosphere::TropoCorrection::kSaastamoinenCosZ},
    {"none", atmosphere::TropoCorrection::kNone}};

constexpr Choice<protocol::ubx::Generation> kGenerations[] = {{"m8", protocol::ubx::Generation::kM8},
                                                               {"m9", protocol::ubx::Generation::kM9},
                                                               {"f9p", protocol::ubx::Generation::kF9P}};
constexpr Choice<receiver::NavFilterType> kFilterTypes[] = {{"kalman", receiver::NavFilterType::kKalman},
                                                           {"none", receiver::NavFilterType::kNone}};
constexpr Choice<receiver::StartMode> kStartModes[] = {
    {"hot", receiver::StartMode::kHot}, {"warm", receiver::StartMode::kWarm}, {"cold", receiver::StartMode::kCold}};
constexpr Choice<receiver::CoastReport> kCoastReports[] = {{"no_fix", receiver::CoastReport::kNoFix},
                                                           {"dead_reckoning", receiver::CoastReport::kDeadReckoning}};
// The core's names, in dynModel order.
constexpr auto kDynamicModels = [] {
  std::array<Choice<receiver::DynamicModel>, receiver::kDynamicModelNames.size()> c{};
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = {receiver::kDynamicModelNames[i].name, receiver::kDynamicModelNames[i].model};
  return c;
}();

// --- [receiver.errors.*] ---------------------------------------------------

constexpr Field<GaussMarkovConfig> kOrbitClockFields[] = {
    number<&GaussMarkovConfig::sigma_m>("sigma_m", Gm::sigma_m, "steady-state 1 sigma; 0 disables"),
    number<&GaussMarkovConfig::tau_s>("tau_s", Gm::tau_s, "correlation time"),
};
constexpr Section<GaussMarkovConfig> kOrbitClock{kOrbitClockFields};

constexpr Field<GaussMarkovConfig> kMultipathFields[] = {
    number<&GaussMarkovConfig::sigma_m>("sigma_m", Gm::sigma_m, "1 sigma at the zenith; 0 disables"),
    number<&GaussMarkovConfig::tau_s>("tau_s", Gm::tau_s, "correlation time"),
};
constexpr Section<GaussMarkovConfig> kMultipath{kMultipathFields};

constexpr Field<Gradient> kGradientFields[] = {
    number<&Gradient::north_m>("north_m", world::ErrorModelRanges::gradient_north_m, "mean north component"),
    number<&Gradient::east_m>("east_m", world::ErrorModelRanges::gradient_east_m, "mean east component"),
    number<&Gradient::north_diurnal_m>("north_diurnal_m", world::ErrorModelRanges::gradient_north_diurnal_m,
                                       "amplitude of the daily cycle of the north component"),
    number<&Gradient::north_peak_h>("north_peak_h", world::ErrorModelRanges::gradient_north_peak_h,
                                    "local time of its maximum"),
    number<&Gradient::east_diurnal_m>("east_diurnal_m", world::ErrorModelRanges::gradient_east_diurnal_m,
                                      "amplitude of the daily cycle of the east component"),
    number<&Gradient::east_peak_h>("east_peak_h", world::ErrorModelRanges::gradient_east_peak_h,
                                   "local time of its maximum"),
    number<&Gradient::process, &GaussMarkovConfig::sigma_m>("sigma_m", Gm::sigma_m,
                                                            "1 sigma of g_N and of g_E; 0 disables"),
    number<&Gradient::process, &GaussMarkovConfig::tau_s>("tau_s", Gm::tau_s, "correlation time"),
};
constexpr Section<Gradient> kGradient{kGradientFields};

using IonoScale = ErrorModelConfig::IonoScale;
constexpr Field<IonoScale> kIonoScaleFields[] = {
    number<&IonoScale::sigma>("sigma", world::ErrorModelRanges::iono_scale_sigma,
                              "steady-state 1 sigma of the relative error (0.2 = 20 %); 0 disables"),
    number<&IonoScale::tau_s>("tau_s", world::ErrorModelRanges::iono_scale_tau_s, "correlation time"),
};
constexpr Section<IonoScale> kIonoScale{kIonoScaleFields};

constexpr Field<ErrorModelConfig> kErrorsFields[] = {
    choice<kThermalModels, &ErrorModelConfig::thermal_model>(
        "thermal_model", "white code noise σ: DLL thermal jitter at each satellite's C/N0 (`[signal.dll]`), or "
                         "`thermal_sigma_m`"),
    number<&ErrorModelConfig::thermal_sigma_m>("thermal_sigma_m", world::ErrorModelRanges::thermal_sigma_m,
                                               "white pseudorange noise, 1 sigma (`thermal_model = \"fixed\"`)"),
    number<&ErrorModelConfig::doppler_sigma_m_s>("doppler_sigma_m_s", world::ErrorModelRanges::doppler_sigma_m_s,
                                                 "white range-rate noise, 1 sigma (`[signal.carrier] doppler_model = \"fixed\"`)"),
    table<kOrbitClock, &ErrorModelConfig::orbit_clock>("orbit_clock", "first-order Gauss-Markov"),
    table<kMultipath, &ErrorModelConfig::multipath>("multipath",
                                                    "unit Gauss-Markov x sigma_m / sin(el); sigma_m 0 = off"),
    table<kGradient, &ErrorModelConfig::gradient>(
        "gradient", "delay += G_N cos(az) + G_E sin(az); G_N = north_m + north_diurnal_m cos(2 pi (LT - north_peak_h) "
                    "/ 24 h) + g_N (E alike); g: Gauss-Markov"),
    table<kIonoScale, &ErrorModelConfig::iono_scale>(
        "iono_scale", "what the broadcast ionosphere gets wrong for the whole sky at once: every ionospheric delay "
                      "× (1 + sigma·x(t)), x a unit Gauss-Markov process; fitted by `gnssemu calibrate`"),
};
constexpr Section<ErrorModelConfig> kErrors{kErrorsFields};

// --- [receiver.clock] ------------------------------------------------------

constexpr Field<ClockConfig> kClockFields[] = {
    number<&ClockConfig::bias_s>("bias_s", world::ClockRanges::bias_s, "initial clock bias"),
    number<&ClockConfig::drift_s_s>("drift_s_s", world::ClockRanges::drift_s_s,
                                    "initial drift (10 ppm covers any TCXO)"),
    number<&ClockConfig::drift_noise_s_s_sqrt_s>("drift_noise_s_s_sqrt_s", world::ClockRanges::drift_noise_s_s_sqrt_s,
                                                 "drift random-walk density"),
    number<&ClockConfig::jump_threshold_s>("jump_threshold_s", world::ClockRanges::jump_threshold_s,
                                           "when \\|bias\\| exceeds this, the clock steps by whole multiples of it "
                                           "(millisecond jumps); 0 disables"),
};
constexpr Section<ClockConfig> kClock{kClockFields};

// --- [receiver.solver], [receiver.corrections] -----------------------------

using Sr = receiver::SolverRanges;
constexpr Choice<receiver::WeightModel> kWeightModels[] = {{"elevation_cn0", receiver::WeightModel::kElevationCn0},
                                                           {"rtklib", receiver::WeightModel::kRtklib}};
constexpr Field<SolverConfig> kSolverFields[] = {
    either<kWeightModels, &SolverConfig::weights>(
        "weights", "pseudorange variance model: a² + b²/sin²(el) + c²·10^(−C/N0/10) (elevation as RTKLIB, C/N0 as "
                   "Kuusniemi et al. 2004); or RTKLIB rnx2rtkp's single point: a² + b²/sin(el) + the broadcast "
                   "URA's variance + `code_bias_sigma_m`² (docs/models.md)"),
    number<&SolverConfig::sigma_a_m>("sigma_a_m", Sr::sigma_a_m,
                                     "pseudorange weight model σ² = a² + b²/sin²(el) + c²·10^(−C/N0/10)"),
    number<&SolverConfig::sigma_b_m>("sigma_b_m", Sr::sigma_b_m, "(a and b may not both be 0)"),
    rule<SolverConfig, receiver::check_weights>(),
    number<&SolverConfig::sigma_c_m_sqrt_hz>("sigma_c_m_sqrt_hz", Sr::sigma_c_m_sqrt_hz,
                                             "C/N0 term of the weights; 0: elevation only"),
    number<&SolverConfig::code_bias_sigma_m>("code_bias_sigma_m", Sr::code_bias_sigma_m,
                                             "`weights = \"rtklib\"`: 1 sigma of the receiver's unknown code bias "
                                             "(RTKLIB ERR_CBIAS 0.3 m)"),
    number<&SolverConfig::iono_model_fraction>(
        "iono_model_fraction", Sr::iono_model_fraction,
        "adds (f·I_Klobuchar)² to σ² when the receiver corrects the ionosphere (RTKLIB ERR_BRDCI = 0.5); 0: left out"),
    number<&SolverConfig::tropo_model_sigma_m>("tropo_model_sigma_m", Sr::tropo_model_sigma_m,
                                               "adds (s / (sin el + 0.1))² to σ² when the receiver corrects the "
                                               "troposphere (RTKLIB ERR_SAAS = 0.3 m); 0: left out"),
    number<&SolverConfig::sigma_range_rate_m_s>("sigma_range_rate_m_s", Sr::sigma_range_rate_m_s,
                                                "Doppler range-rate 1 sigma"),
    number<&SolverConfig::height_hold_sigma_m>("height_hold_sigma_m", Sr::height_hold_sigma_m,
                                               "1 sigma of the held height in 2D fixes"),
    number<&SolverConfig::residual_test_pfa>(
        "residual_test_pfa", Sr::residual_test_pfa,
        "false-alarm probability of the chi-square test on post-fit residuals (fails → the worst satellite is "
        "excluded and the epoch re-solved while ≥ 5 remain and at most `max_exclusions` are out, else no fix; "
        "docs/models.md); below 0.5, where the threshold would fall below the median; 0 disables"),
    integer<&SolverConfig::max_exclusions>(
        "max_exclusions", Sr::max_exclusions,
        "satellites fault exclusion may remove per epoch: 1 = RAIM's single-fault assumption (DO-229, RTKLIB "
        "`raim_fde`); more keeps fixes in canyons with several NLOS satellites but also keeps wrong fixes when every "
        "satellite is biased (an ionospheric storm); 0 = detection only"),
    integer<&SolverConfig::max_iterations>("max_iterations", Sr::max_iterations, "Gauss–Newton iterations at most"),
};
constexpr Section<SolverConfig> kSolver{kSolverFields, [](const SolverConfig& s) { receiver::validate(s); }};

constexpr Field<SolverConfig> kCorrectionsFields[] = {
    choice<kIonoCorrections, &SolverConfig::iono>(
        "ionosphere", "broadcast Klobuchar at L1 with the nav header's ION ALPHA/BETA (RINEX 2) or GPSA/GPSB "
                      "(RINEX 3); a file without them: RTKLIB's default coefficients"),
    choice<kTropoCorrections, &SolverConfig::tropo>(
        "troposphere", "Saastamoinen ZHD + ZWD of the standard atmosphere (RH 0.7) × Niell; or 2.31·e^(−1.2e-4 h) × "
                       "Niell hydrostatic; or the Saastamoinen zenith delays × 1/sin(el) as RTKLIB's `tropmodel` (to "
                       "compare with rnx2rtkp)"),
};
constexpr Section<SolverConfig> kCorrections{kCorrectionsFields};

// --- [receiver.nav], [receiver.acquisition], [receiver.limits] -------------

using Nr = receiver::NavFilterRanges;
constexpr Field<NavFilterConfig> kNavFields[] = {
    choice<kDynamicModels, &NavFilterConfig::dynamic_model>(
        "dyn_model", "CFG-NAV5 dynModel: the platform the navigation filter assumes (its process noise) and its "
                     "sanity limits of altitude and speed, beyond which there is no fix (u-blox's dynamic platform "
                     "table, docs/models.md \"Navigation filter\"); a host's CFG-NAV5 changes it at run time"),
    number<&NavFilterConfig::static_hold_speed_m_s>(
        "static_hold_thresh_m_s", Nr::static_hold_speed_m_s,
        "CFG-NAV5 staticHoldThresh (cm/s on the wire): below this speed the position is frozen and the velocity "
        "reported 0, until the speed exceeds 1.5 × it; 0 off (the M8's default)"),
    number<&NavFilterConfig::static_hold_max_dist_m>(
        "static_hold_max_dist_m", Nr::static_hold_max_dist_m,
        "CFG-NAV5 staticHoldMaxDist: static hold also ends once the filter's position is this far from the held "
        "one; 0: speed only"),
    number<&NavFilterConfig::smoothing_window_s>(
        "smoothing_window_s", Nr::smoothing_window_s,
        "carrier smoothing of code (Hatch filter, restarted at a slip or loss of lock); 0: raw code, as an M8 "
        "navigates (its NAV-SAT never flags a smoothed pseudorange)"),
    number<&NavFilterConfig::coast_limit_s>(
        "coast_limit_s", Nr::coast_limit_s,
        "with fewer than 3 usable satellites the filter extrapolates this long (growing hAcc), then there is no "
        "fix"),
    choice<kCoastReports, &NavFilterConfig::coast_report>(
        "coast_report", "how the outputs flag the extrapolated solution: `no_fix` (NAV-PVT fixType 0 with the "
                        "extrapolated position, NMEA invalid; u-blox's receivers without sensors) or "
                        "`dead_reckoning` (fixType 1, GGA quality 6, mode E; as its ADR/UDR modules)"),
    number<&NavFilterConfig::position_noise_m2_s>(
        "position_noise_m2_s", Nr::position_noise_m2_s,
        "random-walk position noise of the filter: how fast it follows slowly drifting pseudorange errors; sets "
        "the static epoch-to-epoch step (0.02: 0.15 m at 1 Hz, docs/validation.md)"),
    number<&NavFilterConfig::clock_h0_s>("clock_h0_s", Nr::clock_h0_s,
                                         "the filter's oscillator model: white frequency noise h0 (TCXO)"),
    number<&NavFilterConfig::clock_h_minus2_per_s>("clock_h_minus2_per_s", Nr::clock_h_minus2_per_s,
                                                   "random-walk frequency noise h−2 of that model"),
    number<&NavFilterConfig::innovation_gate_sigma>("innovation_gate_sigma", Nr::innovation_gate_sigma,
                                                    "a measurement whose innovation exceeds this many σ is not used"),
    number<&NavFilterConfig::reinit_margin_m>(
        "reinit_margin_m", Nr::reinit_margin_m,
        "a snapshot fix this far beyond 5 σ of the filter's prediction restarts the filter (the antenna moved)"),
};
constexpr Section<NavFilterConfig> kNav{kNavFields};

using Ar = receiver::AcquisitionRanges;
constexpr Field<AcquisitionConfig> kAcquisitionFields[] = {
    choice<kStartModes, &AcquisitionConfig::start>(
        "start", "what the receiver knows at daemon start and in batch, as CFG-RST navBbrMask keeps it: hot "
                 "everything (first fix after about 1 s), warm no ephemerides, cold nothing (about 30 s; MAX-M8 "
                 "data sheet: 29 s GPS)"),
    boolean<&AcquisitionConfig::modelled>(
        "modelled", "false: a satellite is tracked and used as soon as its C/N0 reaches `signal.acquire_dbhz` (no "
                    "search, no ephemeris download, `start` has no effect)"),
    number<&AcquisitionConfig::cold_search_s>("cold_search_s", Ar::cold_search_s,
                                              "mean search time of one satellite without aiding (whole Doppler "
                                              "range), at strong signal"),
    number<&AcquisitionConfig::aided_search_s>("aided_search_s", Ar::aided_search_s,
                                               "the same, aided by time, position and almanac or ephemeris"),
    number<&AcquisitionConfig::reacq_search_s>("reacq_search_s", Ar::reacq_search_s,
                                               "the same, for a satellite lost less than `reacq_window_s` ago"),
    number<&AcquisitionConfig::reacq_window_s>("reacq_window_s", Ar::reacq_window_s,
                                               "how long a lost satellite counts as a reacquisition"),
    number<&AcquisitionConfig::strong_cn0_dbhz>(
        "strong_cn0_dbhz", Ar::strong_cn0_dbhz,
        "below this C/N0 a search takes 10^((strong − C/N0)/10) times longer (dwell ∝ 1/(C/N0))"),
    number<&AcquisitionConfig::search_spread>("search_spread", Ar::search_spread,
                                              "search times drawn uniformly in [1 − s, 1 + s] × the mean"),
    number<&AcquisitionConfig::cold_acquire_dbhz>(
        "cold_acquire_dbhz", Ar::cold_acquire_dbhz,
        "C/N0 an unaided search needs at least, besides `signal.acquire_dbhz` (MAX-M8 data sheet cold-start "
        "sensitivity −148 dBm)"),
    number<&AcquisitionConfig::reacq_margin_db>(
        "reacq_margin_db", Ar::reacq_margin_db,
        "a reacquisition succeeds this far below `signal.acquire_dbhz` (data sheet: −160 vs −157 dBm)"),
    number<&AcquisitionConfig::aided_doppler_window_hz>(
        "aided_doppler_window_hz", Ar::aided_doppler_window_hz,
        "half-width of an aided search about the Doppler predicted from the last fix; a receiver carried farther "
        "(≳ 150 km) falls back to the unaided search"),
    number<&AcquisitionConfig::bit_sync_s>("bit_sync_s", Ar::bit_sync_s,
                                           "from acquisition to data bit synchronisation"),
    number<&AcquisitionConfig::almanac_download_s>("almanac_download_s", Ar::almanac_download_s,
                                                   "tracking time to collect the almanac (25 pages × 30 s)"),
    number<&AcquisitionConfig::ephemeris_validity_s>("ephemeris_validity_s", Ar::ephemeris_validity_s,
                                                     "how long a decoded ephemeris is used (4-h fit interval)"),
};
constexpr Section<AcquisitionConfig> kAcquisition{kAcquisitionFields};

using Lr = receiver::OperationalLimitRanges;
constexpr Field<OperationalLimits> kLimitsFields[] = {
    number<&OperationalLimits::max_altitude_m>(
        "max_altitude_m", Lr::max_altitude_m,
        "above this height above mean sea level there is no fix (MAX-M8 data sheet operational limit 50 000 m)"),
    number<&OperationalLimits::max_speed_m_s>("max_speed_m_s", Lr::max_speed_m_s,
                                              "above this 3D speed there is no fix (data sheet: 500 m/s)"),
};
constexpr Section<OperationalLimits> kLimits{kLimitsFields};

// --- [receiver.spoof_detection] -------------------------------------------

using receiver::SpoofDetectionConfig;
using Sd = receiver::SpoofDetectionRanges;
constexpr Field<SpoofDetectionConfig> kSpoofDetectionFields[] = {
    boolean<&SpoofDetectionConfig::enabled>("enabled", "false: NAV-STATUS spoofDetState 0 (deactivated)"),
    number<&SpoofDetectionConfig::cn0_jump_db>("cn0_jump_db", Sd::cn0_jump_db,
                                               "C/N0 rise of one satellite between epochs that counts as a jump"),
    integer<&SpoofDetectionConfig::cn0_jump_sats>("cn0_jump_sats", Sd::cn0_jump_sats,
                                                  "satellites that must jump in the same epoch"),
    number<&SpoofDetectionConfig::clock_jump_m>("clock_jump_m", Sd::clock_jump_m,
                                                "clock bias change beyond the drift prediction that counts as a jump"),
    number<&SpoofDetectionConfig::uniform_std_db>(
        "uniform_std_db", Sd::uniform_std_db,
        "C/N0 spread below which the sky looks like one transmitter (satellites spanning >= 30 deg elevation)"),
    integer<&SpoofDetectionConfig::uniform_min_sats>("uniform_min_sats", Sd::uniform_min_sats,
                                                     "tracked satellites the uniformity test needs"),
    number<&SpoofDetectionConfig::system_disagreement_m>(
        "system_disagreement_m", Sd::system_disagreement_m,
        "distance between the positions the used GPS satellites and the other systems' point to, beyond which "
        "they disagree (a GPS-only spoofer; 5 used satellites each side); one side excluded wholesale by the "
        "residual test counts too; 0 off"),
    number<&SpoofDetectionConfig::hold_s>("hold_s", Sd::hold_s, "an indication is reported this long"),
};
constexpr Section<SpoofDetectionConfig> kSpoofDetection{
    kSpoofDetectionFields, [](const SpoofDetectionConfig& c) { receiver::validate(c); }};

// --- [receiver] ------------------------------------------------------------

// Any 64-bit seed is valid; TOML integers stop at 2^63 - 1.
constexpr Field<Config> seed_field() {
  Field<Config> row = integer<&Config::world, &WorldConfig::seed>(
      "seed", 0, std::numeric_limits<int64_t>::max(),
      "seed of every random process; same seed and inputs, same output. The top level's is also the sky's "
      "(satellite orbit/clock residuals, atmosphere); a `[[vehicle.receiver]]` seed changes only that "
      "receiver's noise, multipath, carrier and clock");
  row.write = [](TomlWriter& w, const Field<Config>& f, const Config& c) {
    if (c.world.seed > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
      throw Error("receiver.seed " + std::to_string(c.world.seed) + " does not fit a TOML integer (max 2^63 - 1)");
    }
    w.key(f.key, std::to_string(c.world.seed), f.note);
  };
  return row;
}

// A profile sets the defaults of the keys read after it ([receiver.*],
// [atmosphere], [signal]); keys the file gives override it.
void read_profile(TableReader& t, const Field<Config>& f, Config& c) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  const std::string name = t.string(f.key, std::nullopt);
  pipeline::ReceiverProfile p{};
  try {
    p = pipeline::receiver_profile(name);
  } catch (const Error&) {
    t.fail(*n, t.full_name(f.key) + ": '" + name + "' is not one of \"ublox_m8\", \"geodetic\"");
  }
  const pipeline::PipelineConfig pc = pipeline::apply_profile({c.world, c.receiver}, p, c.origin.lat_rad);
  c.world = pc.world;
  c.receiver = pc.receiver;
  c.profile = p;
}

void write_profile(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (c.profile) w.key(f.key, string_text(pipeline::profile_name(*c.profile)), f.note);
}

constexpr Field<Config> profile_field() {
  Field<Config> row = custom<Config>(
      "profile", "", "`\"ublox_m8\"`, `\"geodetic\"`",
      "the fitted error model of one kind of receiver as the defaults of every key after it (docs/models.md "
      "\"Receiver profiles\"): the sky's orbit/clock, ionosphere and gradient processes pooled from five real "
      "station-days, and the device's antenna and code loop — `ublox_m8` a u-blox M8 with a patch antenna, "
      "`geodetic` a station receiver with a choke ring. Keys the file gives override it. Unset: the "
      "unfitted defaults below",
      read_profile, write_profile);
  row.doc_default = "unset";
  return row;
}

void read_state_file(TableReader& t, const Field<Config>& f, Config& c) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) return;
  const std::string given = t.string(f.key, std::nullopt);
  if (given.empty()) t.fail(*n, t.full_name(f.key) + ": must not be empty (leave it out: no state file)");
  c.state_file = resolve_path(given, t.base_dir());
}

void write_state_file(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (!c.state_file.empty()) w.key(f.key, string_text(w.path_text(c.state_file)), f.note);
}

// Unset, a table that names the generation takes that chip's default;
// otherwise the value it inherits stays (a [base] or [[vehicle.receiver]]
// over the top level's).
void read_bands(TableReader& t, const Field<Config>& f, Config& c) {
  if (t.find(f.key) == nullptr) {
    if (t.find("generation") != nullptr) c.receiver.bands = default_bands(c.generation);
    return;
  }
  c.receiver.bands = static_cast<int>(t.integer(f.key, std::nullopt, 1, kNumBands));
  if (c.receiver.bands > default_bands(c.generation)) {
    t.fail(*t.find(f.key), t.full_name(f.key) + " = " + std::to_string(c.receiver.bands) + ": " +
                               single_band_reason(c.generation));
  }
}

void write_bands(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (c.receiver.bands != default_bands(c.generation)) w.key(f.key, std::to_string(c.receiver.bands), f.note);
}

void read_raw_data(TableReader& t, const Field<Config>& f, Config& c) {
  if (t.find(f.key) == nullptr) {
    if (t.find("generation") != nullptr) c.raw_data = default_raw_data(c.generation);
    return;
  }
  c.raw_data = t.boolean(f.key, std::nullopt);
  if (!c.raw_data && default_raw_data(c.generation)) {
    t.fail(*t.find(f.key), t.full_name(f.key) +
                               " = false: every ZED-F9P firmware (HPG) has RXM-RAWX and RXM-SFRBX; leave it out");
  }
}

void write_raw_data(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (c.raw_data != default_raw_data(c.generation)) w.key(f.key, c.raw_data ? "true" : "false", f.note);
}

void read_constellations(TableReader& t, const Field<Config>& f, Config& c) {
  if (t.find(f.key) == nullptr) return;  // parse_config_text gives the chip's set
  const std::string name = t.full_name(f.key);
  SystemSet set;
  t.string_array(f.key, "an array of strings", "RINEX system letters (strings)",
                 [&](const toml::node& e, const std::string& s) {
                   const auto sys = s.size() == 1 ? system_from_letter(s[0]) : std::nullopt;
                   if (!sys) t.fail(e, name + ": unknown system '" + s + "' (known: G R E C J S)");
                   if (set.has(*sys)) t.fail(e, name + ": '" + s + "' listed twice");
                   set = set.with(*sys);
                 });
  if (set.empty()) t.fail(*t.find(f.key), name + ": at least one system");
  c.world.systems = set;
}

void write_constellations(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (c.world.systems == chip_systems(c)) return;
  std::vector<std::string_view> letters;
  for (const SatNumbering& n : kSatNumbering)  // the table's own letters, in its order
    if (c.world.systems.has(n.system)) letters.emplace_back(&n.letter, 1);
  w.key(f.key, strings_text(letters), f.note);
}

using Rr = receiver::ReceiverRanges;
constexpr Field<Config> kReceiverFields[] = {
    profile_field(),
    number<&Config::rate_hz>("rate_hz", Range{1.0, 10.0, "Hz"},
                             "navigation epoch rate (u-blox M8 GPS-only maximum 10 Hz)"),
    angle<&Config::receiver, &ReceiverConfig::elevation_mask_rad>("elevation_mask_deg", Rr::elevation_mask_deg,
                                                                  "satellites below are not used"),
    seed_field(),
    number<&Config::world, &WorldConfig::nominal_cn0_dbhz>(
        "nominal_cn0_dbhz", world::WorldRanges::nominal_cn0_dbhz,
        "zenith C/N0 when `[signal] enabled = false` (then C/N0 = nominal − 10·(1 − sin el)²)"),
    number<&Config::receiver, &ReceiverConfig::max_pdop>("max_pdop", Rr::max_pdop,
                                                         "above this PDOP the fix is reported as none"),
    integer<&Config::receiver, &ReceiverConfig::max_channels>("max_channels", Rr::max_channels,
                                                              "satellites tracked at most, every system together (highest first; 32 = the M8's and M9's "
                                                              "CFG-GNSS numTrkChHw); CFG-GNSS maxTrkCh limits each system within it"),
    choice<kGenerations, &Config::generation>(
        "generation", "the u-blox chip every output presents (docs/ubx.md \"Generations\"): `m8` a NEO-M8N "
                      "(protocol 18, legacy CFG messages only, MON-HW), `m9` a NEO-M9N (protocol 32.01: CFG-VALSET/"
                      "VALGET/VALDEL beside the legacy CFG messages, MON-RF, SEC-SIG; no NAV-SVINFO), `f9p` a ZED-F9P (HPG 1.32, protocol 27.31: L1/L2, "
                      "the high-precision and RTK messages NAV-HPPOSLLH/HPPOSECEF/RELPOSNED, CFG-NAVHPG/TMODE/UART2 keys)"),
    custom<Config>("bands", "", "1 or 2",
                   "signals tracked per satellite: 1 the L1-band signal (GPS/QZSS L1 C/A, GLONASS L1OF, Galileo "
                   "E1C, BeiDou B1I, SBAS L1); 2 also the second frequency (GPS/QZSS L2CL, GLONASS L2OF, Galileo "
                   "E5bQ, BeiDou B2I) in RXM-RAWX, RINEX and RTCM MSM, with its own ionosphere, group delays, C/N0, "
                   "noise and lock (docs/models.md \"Second frequency\"). The position fix uses the L1 band. 2 only "
                   "with `generation = \"f9p\"`: the NEO-M8N and NEO-M9N track L1 only (an error there)",
                   read_bands, write_bands)
        .default_doc("the generation's: 1 for `m8` and `m9`, 2 for `f9p`"),
    custom<Config>("raw_data", "bool", "—",
                   "the chip's firmware has raw data output, as an M8T/M8P-class timing or the F9P's high-precision "
                   "firmware (docs/raw-output.md \"Availability\"): RXM-RAWX and RXM-SFRBX go out where a port or a "
                   "host enables them; false (a NEO-M8N's or NEO-M9N's standard firmware): they stay silent. Every "
                   "ZED-F9P firmware has them: false with `f9p` is an error",
                   read_raw_data, write_raw_data)
        .default_doc("the generation's: false for `m8` and `m9`, true for `f9p`"),
    boolean<&Config::receiver, &ReceiverConfig::sbas>(
        "sbas", "SBAS corrections, as a u-blox's factory CFG-SBAS (usage diffCorr; a host's CFG-SBAS or "
                "CFG-SBAS-USE_DIFFCORR changes it): once a GEO of the service whose area holds the receiver is "
                "decoded for 120 s, GPS satellites get its orbit/clock corrections (after 300 s its ionosphere) "
                "and the fix is differential (GGA quality 2, NAV-PVT diffSoln; docs/models.md \"SBAS\"). false: "
                "SBAS GEOs are tracked and ranged only"),
    custom<Config>("constellations", "", "RINEX letters `G` GPS, `R` GLONASS, `E` Galileo, `C` BeiDou, `J` QZSS, "
                   "`S` SBAS; at least one, no repeats",
                   "the systems in the receiver's sky: satellites of the other systems in the nav data are not "
                   "modelled (docs/models.md \"Every system's broadcast orbits\"). The chip tracks those of them "
                   "its CFG-GNSS / CFG-SIGNAL enables (factory: `m8` G R J S, `m9` all; a host may change it)",
                   read_constellations, write_constellations)
        .default_doc("every system the chip can track: G R E C J S"),
    custom<Config>("state_file", "path", "a file the daemon may write (relative: to the config file's folder)",
                   "the emulated chip's saved configuration across gnssemud restarts, as a real module's "
                   "flash/BBR (docs/ubx.md \"Saved configuration\"): written when a host saves (CFG-CFG save or "
                   "clear, CFG-VALSET/VALDEL to BBR or Flash), loaded at start. Unset: every start is factory-fresh",
                   read_state_file, write_state_file)
        .default_doc("unset"),
    either<kFilterTypes, &Config::receiver, &ReceiverConfig::filter, &NavFilterConfig::type>(
        "filter", "`kalman`: the navigation filter of a u-blox M8 (position, velocity, clock; `[receiver.nav]`); "
                  "`none`: a snapshot least-squares fix on raw code every epoch"),
    table<kErrors, &Config::world, &WorldConfig::errors>("errors"),
    table<kClock, &Config::world, &WorldConfig::clock>("clock"),
    table<kSolver, &Config::receiver, &ReceiverConfig::solver>("solver", "what the receiver's own solver assumes"),
    table<kCorrections, &Config::receiver, &ReceiverConfig::solver>(
        "corrections", "what the receiver subtracts (broadcast models)"),
    table<kNav, &Config::receiver, &ReceiverConfig::filter>("nav", "navigation filter (CFG-NAV5)"),
    table<kAcquisition, &Config::receiver, &ReceiverConfig::acquisition>("acquisition",
                                                                         "search, reacquisition, ephemeris download"),
    table<kLimits, &Config::receiver, &ReceiverConfig::limits>("limits", "operational limits"),
    table<kSpoofDetection, &Config::receiver, &ReceiverConfig::spoof_detection>(
        "spoof_detection", "the receiver's spoofing indicators (NAV-STATUS spoofDetState, docs/faults.md)"),
};

}  // namespace

constexpr Section<Config> kReceiverKeys{kReceiverFields, [](const Config& c) { receiver::validate(c.receiver); }};

}  // namespace gnssemu::config::detail
