// SPDX-License-Identifier: Apache-2.0
#include "core/faults/fault_stage.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/common/error.hpp"
#include "core/common/gnss_signals.hpp"
#include "core/faults/interference.hpp"
#include "core/geo/geodesy.hpp"
#include "core/signal/system_signal.hpp"

namespace gnssemu::faults {

namespace {

// Salt of the stage's own random streams, so its draws never repeat the world's.
constexpr std::uint64_t kSeedSalt = 0x6661756C74730001ULL;  // "faults"
// C/N0 at which a signal no longer reaches the correlators at all, dB-Hz.
constexpr double kNoSignal_dbhz = 0.0;

void check(const FaultEvent& e) {
  if (const auto problem = check_event(e)) {
    throw Error("scenario", e.line, std::string(type_name(e.type)) + " event: " + *problem);
  }
}

// Unit line of sight in ENU from azimuth / elevation.
Enu los_enu(double az_rad, double el_rad) noexcept {
  const double ce = std::cos(el_rad);
  return Enu(std::sin(az_rad) * ce, std::cos(az_rad) * ce, std::sin(el_rad));
}

bool in_sector(double az_deg, double from_deg, double to_deg) noexcept {
  if (from_deg <= to_deg) return az_deg >= from_deg && az_deg <= to_deg;
  return az_deg >= from_deg || az_deg <= to_deg;  // wraps through north
}

}  // namespace

FaultStage::FaultStage(const FaultContext& context, std::span<const FaultEvent> events) {
  set_context(context);
  events_.reserve(kMaxEvents);
  status_.reserve(kMaxEvents);
  spoof_.reserve(kMaxEvents);
  inject(events);
}

void FaultStage::set_context(const FaultContext& context) {
  signal::validate(context.link);
  world::validate(context.noise);
  ctx_ = context;
  rng_ = world::CounterRng(world::CounterRng::mix(context.seed ^ kSeedSalt));
  n0_dbw_hz_ = signal::thermal_noise_density_dbw_hz(ctx_.link.noise_temperature_k) + ctx_.link.noise_figure_db +
               ctx_.link.environment_noise_rise_db;
}

void FaultStage::inject(std::span<const FaultEvent> events) {
  if (events_.size() + events.size() > kMaxEvents) {
    throw Error("scenario: at most " + std::to_string(kMaxEvents) + " events are held; " +
                std::to_string(events_.size()) + " are, " + std::to_string(events.size()) + " more given");
  }
  for (const FaultEvent& e : events) check(e);
  for (const FaultEvent& e : events) {
    FaultEvent shifted = e;
    shifted.start_s += elapsed_s_;
    events_.push_back(shifted);
    spoof_.push_back(SpoofState{});
    status_.push_back(FaultStatus{});
  }
  for (std::size_t i = 0; i < events_.size(); ++i) status_[i].event = &events_[i];
}

void FaultStage::clear() noexcept {
  // Spoofers end here as at their own end: the loops they moved let go.
  for (const SpoofState& sp : spoof_) {
    if (!sp.started || !moved(sp)) continue;
    for (std::size_t p = 0; p < released_.size(); ++p) released_[p] = released_[p] || sp.captured[p];
    releasing_ = true;
  }
  // Satellite offsets vanish with their events: a step the loops see next epoch.
  for (const Shift& sh : shift_) releasing_ = releasing_ || sh.prev_m != 0.0;
  events_.clear();
  spoof_.clear();
  status_.clear();
}

std::span<const FaultStatus> FaultStage::status() noexcept {
  for (std::size_t i = 0; i < events_.size(); ++i) {
    status_[i].event = &events_[i];
    status_[i].elapsed_s = elapsed_s_ - events_[i].start_s;
    status_[i].active = events_[i].active_at(elapsed_s_);
  }
  return status_;
}

int FaultStage::active_count() const noexcept {
  int n = 0;
  for (const FaultEvent& e : events_) n += e.active_at(elapsed_s_) ? 1 : 0;
  return n;
}

void FaultStage::degrade(world::SatObservable& o, double cn0_dbhz) noexcept {
  if (!o.received || !(cn0_dbhz < o.cn0_dbhz)) return;
  if (!(cn0_dbhz > kNoSignal_dbhz)) {
    o.received = false;
    o.cn0_dbhz = 0.0;
    return;
  }
  // The world drew its noise at the old C/N0: add the difference in variance
  // (none where the configured model does not depend on C/N0).
  const world::MeasurementNoise& n = ctx_.noise;
  const auto extra_sigma = [&](auto sigma) {
    const double s0 = sigma(o.cn0_dbhz), s1 = sigma(cn0_dbhz);
    return std::sqrt(std::max(s1 * s1 - s0 * s0, 0.0));
  };
  const std::uint64_t stream = world::sat_stream(o.sat);
  const double extra_m = extra_sigma([&](double c) { return n.code_sigma_m(c); });
  if (extra_m > 0.0) o.pseudorange_m += extra_m * rng_.normal(stream, epoch_, world::Purpose::kThermal);
  const double extra_rr = extra_sigma([&](double c) { return n.range_rate_sigma_m_s(c, o.wavelength_m); });
  if (extra_rr > 0.0) o.doppler_hz -= extra_rr * rng_.normal(stream, epoch_, world::Purpose::kDoppler) / o.wavelength_m;
  if (o.carrier_valid) {
    const std::optional<SignalId> sig = signal_of(o.sat.system, 0);
    degrade_carrier(o.carrier_phase_cycles, slips_[static_cast<std::size_t>(o.sat.index())][0], o.cn0_dbhz, cn0_dbhz,
                    sig && signal_info(*sig).pilot, stream);
  }
  o.cn0_dbhz = cn0_dbhz;
}

void FaultStage::degrade_band1(world::SatObservable& o, double cn0_dbhz) noexcept {
  // Its C/N0 and carrier loop; its code and Doppler noise stay the world's.
  world::SecondSignal& b = o.band1;
  if (!b.received || !(cn0_dbhz < b.cn0_dbhz)) return;
  b.received = cn0_dbhz > kNoSignal_dbhz;
  if (b.received && b.carrier_valid) {
    const std::optional<SignalId> sig = signal_of(o.sat.system, 1);
    degrade_carrier(b.carrier_phase_cycles, slips_[static_cast<std::size_t>(o.sat.index())][1], b.cn0_dbhz, cn0_dbhz,
                    sig && signal_info(*sig).pilot, world::band_stream(o.sat, 1));
  }
  b.cn0_dbhz = b.received ? cn0_dbhz : 0.0;
}

void FaultStage::degrade_carrier(double& phase_cycles, CarrierSlips& slips, double cn0_from_dbhz, double cn0_to_dbhz,
                                 bool pilot, std::uint64_t stream) noexcept {
  const world::CarrierConfig& cc = ctx_.noise.carrier;
  if (!cc.enabled) return;
  // Total loop jitter (thermal PLL jitter and the oscillator's), rad.
  const auto sigma_rad = [&](double cn0) {
    return std::hypot(world::pll_jitter_rad(cn0, cc.pll_bandwidth_hz, cc.integration_s), cc.oscillator_sigma_rad);
  };
  const double s0 = sigma_rad(cn0_from_dbhz), s1 = sigma_rad(cn0_to_dbhz);
  // The world drew the phase noise at the old C/N0: add the difference in variance.
  phase_cycles += std::sqrt(std::max(s1 * s1 - s0 * s0, 0.0)) / (2.0 * kPi) *
                  rng_.normal(stream, epoch_, world::Purpose::kCarrierNoise);
  if (!(dt_s_ > 0.0)) return;
  // Slips the weaker signal adds to those the world drew at the old C/N0
  // (Viterbi's mean time to slip, world/carrier.hpp).
  const double p_extra = world::cycle_slip_probability(s1, cc.pll_bandwidth_hz, dt_s_) -
                         world::cycle_slip_probability(s0, cc.pll_bandwidth_hz, dt_s_);
  if (!(p_extra > 0.0) || !(rng_.uniform(stream, epoch_, world::Purpose::kCycleSlip, 0) < p_extra)) return;
  // A Costas loop slips by half a cycle (onto the other data sign), a
  // pilot's pure PLL by a whole one, either way.
  const double size = pilot ? 1.0 : 0.5;
  CarrierSlips& s = current(slips);
  s.cycles += rng_.uniform(stream, epoch_, world::Purpose::kCycleSlip, 1) < 0.5 ? -size : size;
  s.half = s.half != !pilot;
  ++s.count;
  any_slips_ = true;
}

FaultStage::CarrierSlips& FaultStage::current(CarrierSlips& s) const noexcept {
  if (s.last_epoch + 1 < epoch_) s = CarrierSlips{};  // the loop missed an epoch: lost, a new lock since
  s.last_epoch = epoch_;
  return s;
}

void FaultStage::carry_slips(world::Observables& obs) noexcept {
  if (!any_slips_) return;
  bool any = false;
  const auto carry = [&](bool locked, double& phase_cycles, std::uint32_t& discontinuities, bool& half_cycle,
                         CarrierSlips& slips) {
    CarrierSlips& s = current(slips);
    if (!locked) {
      s = CarrierSlips{};
      return;
    }
    phase_cycles += s.cycles;
    discontinuities += s.count;
    half_cycle = half_cycle != s.half;
    any = any || s.count > 0;
  };
  for (int i = 0; i < obs.num_sats; ++i) {
    world::SatObservable& o = obs.sats[i];
    auto& s = slips_[static_cast<std::size_t>(o.sat.index())];
    carry(o.received && o.carrier_valid, o.carrier_phase_cycles, o.carrier_discontinuities, o.carrier_half_cycle, s[0]);
    world::SecondSignal& b = o.band1;
    carry(b.received && b.carrier_valid, b.carrier_phase_cycles, b.carrier_discontinuities, b.carrier_half_cycle, s[1]);
  }
  any_slips_ = any;
}

void FaultStage::shift(world::SatObservable& o, double delta_m, double rate_m_s) noexcept {
  o.pseudorange_m += delta_m;
  o.carrier_phase_cycles += delta_m / o.wavelength_m;
  o.doppler_hz -= rate_m_s / o.wavelength_m;
  world::SecondSignal& b = o.band1;
  if (!b.received) return;
  b.pseudorange_m += delta_m;
  b.carrier_phase_cycles += delta_m / b.wavelength_m;
  b.doppler_hz -= rate_m_s / b.wavelength_m;
}

void FaultStage::break_lock(world::SatObservable& o) noexcept {
  o.lock_break = true;
  ++o.carrier_discontinuities;
  ++o.band1.carrier_discontinuities;
}

void FaultStage::let_go(const std::array<bool, kNumSats>& held, world::Observables& obs) noexcept {
  for (int i = 0; i < obs.num_sats; ++i)
    if (held[static_cast<std::size_t>(obs.sats[i].sat.index())] && obs.sats[i].received) break_lock(obs.sats[i]);
}

void FaultStage::satellite_fault(const FaultEvent& e, double f, double since_s, world::Observables& obs) noexcept {
  const std::optional<SatId> sat = sat_from_param(e.param(Param::kPrn).from);
  if (!sat) return;
  for (int i = 0; i < obs.num_sats; ++i) {
    world::SatObservable& o = obs.sats[i];
    if (o.sat != *sat || o.eph == nullptr) continue;
    // Broadcast faults: the receiver decodes a falsified copy of the set.
    const bool eph_fault = e.has(Param::kEphRadialM) || e.has(Param::kEphAlongM) || e.has(Param::kUnhealthy);
    if (eph_fault) {
      orbit::Ephemeris& c = eph_copy_[static_cast<std::size_t>(sat->index())];
      c = *o.eph;
      const double a_m = c.sqrt_a_sqrtm * c.sqrt_a_sqrtm;
      const double da_m = e.value(Param::kEphRadialM, f);
      if (a_m + da_m > 0.0) c.sqrt_a_sqrtm = std::sqrt(a_m + da_m);
      if (a_m > 0.0) c.m0_rad += e.value(Param::kEphAlongM, f) / a_m;
      if (e.value(Param::kUnhealthy, f) >= 0.5) c.health = 1;
      o.eph = &c;
    }
    // Signal faults: the satellite transmits early or late (code and carrier alike).
    const Ramp& bias = e.param(Param::kBiasM);
    const double bias_rate_m_s =
        e.has(Param::kBiasM) && std::isfinite(e.duration_s) ? (bias.to - bias.from) / e.duration_s : 0.0;
    const double rate_m_s = e.value(Param::kRateMS, f);
    const double offset_m = e.value(Param::kBiasM, f) + rate_m_s * since_s +
                            kSpeedOfLight_m_s * 1e-6 * e.value(Param::kClockJumpUs, f);
    const std::size_t k = static_cast<std::size_t>(sat->index());
    shift_[k].m += offset_m;
    shift_[k].rate_m_s += rate_m_s + bias_rate_m_s;
    if (!o.received) continue;
    shift(o, offset_m, rate_m_s + bias_rate_m_s);
  }
}

void FaultStage::satellite_steps(world::Observables& obs) noexcept {
  // A transmitted signal that jumps by more than its rate explains (a clock
  // step, a bias switched on or off) pulls the code loop off its chip and the
  // PLL off its cycle: the receiver loses lock, as the world's lock_break.
  const double limit_m = ctx_.noise.carrier.lock_break_m;
  for (int i = 0; i < obs.num_sats; ++i) {
    world::SatObservable& o = obs.sats[i];
    const std::size_t k = static_cast<std::size_t>(o.sat.index());
    Shift& sh = shift_[k];
    const double jump_m = sh.m - sh.prev_m - 0.5 * (sh.rate_m_s + sh.prev_rate_m_s) * dt_s_;
    if (epoch_ > 1 && o.received && std::fabs(jump_m) > limit_m) break_lock(o);
    sh.prev_m = sh.m;
    sh.prev_rate_m_s = sh.rate_m_s;
  }
}

void FaultStage::sky_block(const FaultEvent& e, double f, world::Observables& obs) noexcept {
  const double az0 = e.value(Param::kAzFromDeg, f), az1 = e.value(Param::kAzToDeg, f);
  const double el0 = e.value(Param::kElMinDeg, f), el1 = e.value(Param::kElMaxDeg, f);
  const bool full_circle = az0 == 0.0 && az1 == 360.0;
  for (int i = 0; i < obs.num_sats; ++i) {
    world::SatObservable& o = obs.sats[i];
    if (!o.above_mask || !o.received) continue;
    const double az = o.az_rad / kDegToRad, el = o.el_rad / kDegToRad;
    if (!(full_circle || in_sector(az, az0, az1)) || el < el0 || el > el1) continue;
    if (e.has(Param::kLossDb)) {
      degrade_band1(o, o.band1.cn0_dbhz - e.value(Param::kLossDb, f));
      degrade(o, o.cn0_dbhz - e.value(Param::kLossDb, f));
    } else {
      o.received = false;
      o.blocked = true;
      o.cn0_dbhz = 0.0;
    }
  }
}

void FaultStage::outage(const FaultEvent& e, world::Observables& obs) noexcept {
  const auto kind = static_cast<OutageKind>(e.mode);
  if (kind == OutageKind::kOpen) obs.antenna_state = world::AntennaState::kOpen;
  if (kind == OutageKind::kShort) obs.antenna_state = world::AntennaState::kShort;
  for (int i = 0; i < obs.num_sats; ++i) {
    world::SatObservable& o = obs.sats[i];
    if (!o.above_mask) continue;
    o.blocked = o.blocked || kind == OutageKind::kBlockage;
    o.received = false;
    o.cn0_dbhz = 0.0;
  }
}

void FaultStage::spoofer(const FaultEvent& e, SpoofState& s, double f, double dt_s, world::Observables& obs) noexcept {
  const auto mode = static_cast<SpoofMode>(e.mode);
  const double c = kSpeedOfLight_m_s;
  // The false trajectory and clock (ENU offset from the truth).
  const Enu fixed_offset(e.value(Param::kOffsetEastM, f), e.value(Param::kOffsetNorthM, f),
                         e.value(Param::kOffsetUpM, f));
  switch (mode) {
    case SpoofMode::kDrag: {
      const double since_s = s.started ? dt_s : 0.0;
      const double hdg = e.value(Param::kDragHeadingDeg, f) * kDegToRad;
      // Speed grows with the acceleration from the start of the drag.
      const double speed = e.value(Param::kDragSpeedMS, f) + e.value(Param::kDragAccelMS2, f) * s.drag_s;
      s.rate_m_s = Enu(speed * std::sin(hdg), speed * std::cos(hdg), e.value(Param::kDragUpMS, f));
      s.offset_m = Enu(s.offset_m + s.rate_m_s * since_s);
      s.clock_rate_m_s = e.value(Param::kPushRateNsS, f) * 1e-9 * c;
      s.clock_m += s.clock_rate_m_s * since_s;
      s.drag_s += since_s;
      break;
    }
    case SpoofMode::kTimePush: {
      const double since_s = s.started ? dt_s : 0.0;
      s.rate_m_s = Enu{};
      s.clock_rate_m_s = e.value(Param::kPushRateNsS, f) * 1e-9 * c;
      s.clock_m += s.clock_rate_m_s * since_s;
      s.offset_m = fixed_offset;
      break;
    }
    case SpoofMode::kMeacon:
      s.aligned = false;  // the replay arrives late: the loops must let go and reacquire
      s.offset_m = fixed_offset;
      s.rate_m_s = Enu{};
      s.clock_m = e.value(Param::kDelayUs, f) * 1e-6 * c;
      s.clock_rate_m_s = 0.0;
      break;
    case SpoofMode::kTakeover:
      s.aligned = false;
      s.offset_m = fixed_offset;
      s.rate_m_s = Enu{};
      s.clock_m = e.value(Param::kClockJumpUs, f) * 1e-6 * c;
      s.clock_rate_m_s = e.value(Param::kPushRateNsS, f) * 1e-9 * c;
      break;
  }
  s.started = true;
  if (obs.antenna_state != world::AntennaState::kOk) return;
  // One transmitter sends every PRN of the systems it forges at one power:
  // the strongest authentic signal of those plus the advantage. A loop is
  // captured where the spoofed signal beats the authentic one by the capture
  // margin (weak satellites first); other systems' signals stay authentic.
  const SystemSet forged(static_cast<std::uint8_t>(e.value(Param::kSystems, f)));
  const auto forges = [&](const world::SatObservable& o) {
    return o.above_mask && o.received && forged.has(o.sat.system);
  };
  double strongest = 0.0;
  for (int i = 0; i < obs.num_sats; ++i)
    if (forges(obs.sats[i])) strongest = std::max(strongest, obs.sats[i].cn0_dbhz);
  if (!(strongest > 0.0)) return;
  const double level = strongest + e.value(Param::kPowerAdvantageDb, f);
  const double margin = e.value(Param::kCaptureMarginDb, f);
  for (int i = 0; i < obs.num_sats; ++i) {
    world::SatObservable& o = obs.sats[i];
    if (!forges(o)) continue;
    const bool captured = level - o.cn0_dbhz >= margin;
    const std::size_t k = static_cast<std::size_t>(o.sat.index());
    const bool newly = captured && !s.captured[k];
    s.captured[k] = captured;
    if (!captured) continue;
    ++effects_.captured;
    // Ranges as seen from the false position with the false clock: every
    // spoofed pseudorange agrees with one solution (residuals stay quiet).
    const Enu u = los_enu(o.az_rad, o.el_rad);
    shift(o, -u.dot(s.offset_m) + s.clock_m, -u.dot(s.rate_m_s) + s.clock_rate_m_s);
    o.cn0_dbhz = level;
    if (newly && !s.aligned) break_lock(o);
  }
  effects_.spoof_offset_m = s.offset_m;
  effects_.spoof_clock_m = s.clock_m;
}

double FaultStage::jammer_power_w(const FaultEvent& e, double f, const world::Truth& truth, bool* cw) const noexcept {
  const double freq_hz = e.value(Param::kFreqMhz, f) * 1e6;
  *cw = static_cast<JammerKind>(e.mode) != JammerKind::kWideband;
  double j_dbw = 0.0;
  if (e.has(Param::kJsDb)) {
    j_dbw = kNominalSignal_dbw + e.value(Param::kJsDb, f);
  } else {
    double distance_m = e.value(Param::kDistanceM, f);
    double el_rad = 0.0;
    if (e.has(Param::kLatDeg)) {
      const Lla rx = geo::lla_from_ecef(truth.pos_m);
      const Lla jl{e.value(Param::kLatDeg, f) * kDegToRad, e.value(Param::kLonDeg, f) * kDegToRad,
                   e.has(Param::kHeightM) ? e.value(Param::kHeightM, f) : rx.height_m};
      const Ecef jp = geo::ecef_from_lla(jl);
      distance_m = (jp - truth.pos_m).norm();
      el_rad = geo::look_angles(truth.pos_m, rx, jp).el_rad;
    }
    const double gain = e.has(Param::kGainDbi) ? e.value(Param::kGainDbi, f)
                                               : signal::antenna_gain_dbi(ctx_.link.antenna, el_rad);
    j_dbw = jammer_power_dbw(e.value(Param::kEirpDbw, f), distance_m, gain, freq_hz);
  }
  return std::pow(10.0, j_dbw / 10.0);
}

void FaultStage::apply(const time::GpsTime& t, const world::Truth& truth, world::Observables& obs) noexcept {
  double dt_s = 0.0;
  if (!started_) {
    started_ = true;
    t0_ = t;
  } else {
    dt_s = t - t_prev_;
    if (!std::isfinite(dt_s) || dt_s < 0.0) dt_s = 0.0;
  }
  t_prev_ = t;
  dt_s_ = dt_s;
  elapsed_s_ = t - t0_;
  ++epoch_;
  effects_ = FaultEffects{};
  if (events_.empty() && !releasing_) {
    carry_slips(obs);
    return;
  }
  const double now = elapsed_s_;
  // Order of the physics: the satellites transmit (satellite faults), the
  // sky and the antenna pass or stop the signals (sky_block, outage), a
  // ground spoofer adds its own, and interference degrades everything received.
  bool sat_faults = false;
  for (const FaultEvent& e : events_) sat_faults = sat_faults || (e.type == FaultType::kSatellite && e.active_at(now));
  // The shifts are tracked while a satellite fault acts and one epoch after (its end is a step too).
  if (sat_faults || shifted_) {
    for (int i = 0; i < obs.num_sats; ++i) {
      Shift& sh = shift_[static_cast<std::size_t>(obs.sats[i].sat.index())];
      sh.m = sh.rate_m_s = 0.0;
    }
    for (const FaultEvent& e : events_)
      if (e.type == FaultType::kSatellite && e.active_at(now)) satellite_fault(e, e.fraction_at(now), now - e.start_s, obs);
    satellite_steps(obs);
  }
  shifted_ = sat_faults;
  for (const FaultEvent& e : events_)
    if (e.type == FaultType::kSkyBlock && e.active_at(now)) sky_block(e, e.fraction_at(now), obs);
  for (const FaultEvent& e : events_)
    if (e.type == FaultType::kOutage && e.active_at(now)) outage(e, obs);
  if (releasing_) {
    let_go(released_, obs);
    released_ = {};
    releasing_ = false;
  }
  for (std::size_t k = 0; k < events_.size(); ++k) {
    const FaultEvent& e = events_[k];
    if (e.type != FaultType::kSpoofer) continue;
    if (e.active_at(now)) {
      spoofer(e, spoof_[k], e.fraction_at(now), dt_s, obs);
    } else if (spoof_[k].started) {
      // The spoofer stops: the loops it held find no signal where it was
      // (unless it had not moved them) and reacquire the authentic ones.
      if (moved(spoof_[k])) let_go(spoof_[k].captured, obs);
      spoof_[k] = SpoofState{};
    }
  }
  // Each jammer hurts a satellite by the part of its spectrum inside that
  // satellite's main lobe (its system's signal around its own carrier).
  double j_w = 0.0, cw_w = 0.0;
  int n_jam = 0;
  for (const FaultEvent& e : events_) {
    if (e.type != FaultType::kJammer || !e.active_at(now)) continue;
    const double f = e.fraction_at(now);
    const auto kind = static_cast<JammerKind>(e.mode);
    bool cw = false;
    const double p_w = jammer_power_w(e, f, truth, &cw);
    j_w += p_w;
    if (cw) cw_w += p_w;
    jam_[static_cast<std::size_t>(n_jam++)] =
        ActiveJammer{p_w, kind,
                     JammerBand{e.value(Param::kFreqMhz, f) * 1e6,
                                e.has(Param::kBandwidthMhz) ? e.value(Param::kBandwidthMhz, f) * 1e6
                                                            : default_jammer_width_hz(kind)}};
  }
  if (j_w > 0.0) {
    effects_.jammer_dbw = 10.0 * std::log10(j_w);
    effects_.agc_rise_db = agc_rise_db(j_w, n0_dbw_hz_);
    obs.noise_rise_db += effects_.agc_rise_db;
    obs.cw_jam_to_noise += cw_w / (std::pow(10.0, n0_dbw_hz_ / 10.0) * kFrontEndBandwidth_hz);
    for (int i = 0; i < obs.num_sats; ++i) {
      world::SatObservable& o = obs.sats[i];
      if (!o.above_mask || !o.received) continue;
      const SignalBand band{o.carrier_hz, signal::system_signal(o.sat.system).main_lobe_half_width_hz};
      double i0_w_hz = 0.0;
      for (int k = 0; k < n_jam; ++k) {
        const ActiveJammer& a = jam_[static_cast<std::size_t>(k)];
        i0_w_hz += interference_density_w_hz(a.power_w, a.kind, a.band, band);
      }
      degrade(o, effective_cn0_dbhz(o.cn0_dbhz, n0_dbw_hz_, i0_w_hz));
      if (o.band1.received) {
        // The second signal sees the jammers that overlap its own band.
        const SignalBand band1{o.band1.carrier_hz, signal::system_signal(o.sat.system).main_lobe_half_width_hz};
        double i1_w_hz = 0.0;
        for (int k = 0; k < n_jam; ++k) {
          const ActiveJammer& a = jam_[static_cast<std::size_t>(k)];
          i1_w_hz += interference_density_w_hz(a.power_w, a.kind, a.band, band1);
        }
        degrade_band1(o, effective_cn0_dbhz(o.band1.cn0_dbhz, n0_dbw_hz_, i1_w_hz));
      }
    }
  }
  carry_slips(obs);
}

}  // namespace gnssemu::faults
