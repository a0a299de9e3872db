// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/tracking/acquisition.hpp"

#include <algorithm>
#include <cmath>

#include "core/orbit/ephemeris.hpp"
#include "core/world/random.hpp"

namespace gnssemu::receiver {

namespace {

// GPS navigation message (IS-GPS-200 §20.3.2): 6-s subframes, 30-s frames;
// subframes 1-3 carry clock and ephemeris.
constexpr double kSubframe_s = 6.0;
constexpr double kFrame_s = 30.0;
constexpr double kWord_s = 0.6;
constexpr int kWordsPerSubframe = 10;
// Words 1-2 of a subframe (TLM, HOW with the time of week), s.
constexpr double kHowWords_s = 2.0 * kWord_s;
// Nominal signal flight time for the Doppler prediction of an aided search, s.
constexpr double kNominalFlight_s = 0.075;

}  // namespace

void validate(const AcquisitionConfig& c) {
  using R = AcquisitionRanges;
  check_ranges("acquisition config",
               {{c.cold_search_s, R::cold_search_s, "cold_search_s"},
                {c.aided_search_s, R::aided_search_s, "aided_search_s"},
                {c.reacq_search_s, R::reacq_search_s, "reacq_search_s"},
                {c.reacq_window_s, R::reacq_window_s, "reacq_window_s"},
                {c.strong_cn0_dbhz, R::strong_cn0_dbhz, "strong_cn0_dbhz"},
                {c.search_spread, R::search_spread, "search_spread"},
                {c.cold_acquire_dbhz, R::cold_acquire_dbhz, "cold_acquire_dbhz"},
                {c.reacq_margin_db, R::reacq_margin_db, "reacq_margin_db"},
                {c.aided_doppler_window_hz, R::aided_doppler_window_hz, "aided_doppler_window_hz"},
                {c.bit_sync_s, R::bit_sync_s, "bit_sync_s"},
                {c.almanac_download_s, R::almanac_download_s, "almanac_download_s"},
                {c.ephemeris_validity_s, R::ephemeris_validity_s, "ephemeris_validity_s"}});
}

double ephemeris_wait_s(double phase_s) noexcept {
  double phi = std::fmod(phase_s, kFrame_s);
  if (!(phi >= 0.0)) phi = phi < 0.0 ? phi + kFrame_s : 0.0;
  // Each 30-bit word carries its own parity, so a word is kept once received
  // whole: words 3-10 of subframes 1-3 (after TLM and HOW) are needed; one
  // under way or past is taken from the next frame.
  double done_s = 0.0;
  for (int sf = 0; sf < 3; ++sf)
    for (int w = 2; w < kWordsPerSubframe; ++w) {
      const double start_s = sf * kSubframe_s + w * kWord_s;
      done_s = std::max(done_s, (start_s >= phi ? start_s : start_s + kFrame_s) + kWord_s);
    }
  return done_s - phi;
}

Acquisition::Acquisition(const AcquisitionConfig& config, const signal::TrackingThresholds& thresholds,
                         std::uint64_t seed) noexcept
    : cfg_(config), thr_(thresholds), seed_(seed) {
  restart(start_state(config.start));
  if (start_state(config.start).ephemeris)
    for (Channel& c : ch_) c.eph_until_s = cfg_.ephemeris_validity_s;
}

void Acquisition::restart(const StartState& keep) noexcept {
  for (Channel& c : ch_) {
    const double eph_until = keep.ephemeris ? c.eph_until_s : -1.0;
    c = Channel{};
    c.eph_until_s = eph_until;
    c.lost_at_s = now_s_;
  }
  for (signal::TrackingState& s : instant_) s.reset();
  time_known_ = keep.time;
  position_known_ = keep.position;
  almanac_known_ = keep.almanac;
  almanac_tracking_s_ = 0.0;
}

Acquisition::Search Acquisition::classify(SatId sat) const noexcept {
  const Channel& c = ch_[idx(sat)];
  if (!time_known_ || !position_known_) return Search::kCold;
  if (c.tracked_before && now_s_ - c.lost_at_s <= cfg_.reacq_window_s) return Search::kReacq;
  if (almanac_known_ || c.eph_until_s > now_s_) return Search::kAided;
  return Search::kCold;
}

double Acquisition::threshold_dbhz(Search s) const noexcept {
  switch (s) {
    case Search::kCold: return std::max(thr_.acquire_dbhz, cfg_.cold_acquire_dbhz);
    case Search::kReacq: return std::max(thr_.acquire_dbhz - cfg_.reacq_margin_db, thr_.lose_dbhz);
    case Search::kAided: break;
  }
  return thr_.acquire_dbhz;
}

double Acquisition::search_time_s(SatId sat, Search s, double cn0_dbhz) noexcept {
  const double base = s == Search::kCold ? cfg_.cold_search_s : s == Search::kAided ? cfg_.aided_search_s : cfg_.reacq_search_s;
  // Below a strong signal the dwell per search cell grows with 1 / (C/N0).
  const double weak = std::pow(10.0, std::max(cfg_.strong_cn0_dbhz - cn0_dbhz, 0.0) / 10.0);
  const world::CounterRng rng(seed_);
  const double u = rng.uniform(world::kAcquisitionStream + world::sat_stream(sat), searches_++,
                               world::Purpose::kAcquisition, 0);
  return base * weak * (1.0 + cfg_.search_spread * (2.0 * u - 1.0));
}

bool Acquisition::within_aided_window(const time::GpsTime& t, const world::SatObservable& o,
                                      const AidingState& aiding, const world::SharedSky* sky) const noexcept {
  if (!aiding.valid || o.eph == nullptr) return true;
  const orbit::SatState st = sky != nullptr ? sky->state_at(*o.eph, t - kNominalFlight_s)
                                             : orbit::sat_state(*o.eph, t - kNominalFlight_s);
  const Vec3 d = st.pos_m - aiding.pos_m;
  const double r = d.norm();
  if (!(r > 0.0)) return true;
  const Vec3 los = d / r;
  const double predicted_rr =
      los.dot(st.vel_m_s - aiding.vel_m_s) + aiding.drift_m_s - kSpeedOfLight_m_s * st.clk_drift_s_s;
  const double measured_rr = -o.wavelength_m * o.doppler_hz;
  return std::fabs(measured_rr - predicted_rr) / o.wavelength_m <= cfg_.aided_doppler_window_hz;
}

void Acquisition::lose(Channel& c) noexcept {
  c.state = State::kIdle;
  c.lost_at_s = now_s_;
  c.downloading = false;
}

void Acquisition::drop(SatId sat) noexcept {
  Channel& c = ch_[idx(sat)];
  instant_[idx(sat)].reset();
  if (c.state == State::kTracking) lose(c);
}

void Acquisition::lose_all(double dt_s) noexcept {
  now_s_ += dt_s;
  for (signal::TrackingState& s : instant_) s.reset();
  for (Channel& c : ch_) {
    c.new_lock = false;
    if (c.state == State::kTracking) lose(c);
    c.state = State::kIdle;
  }
}

void Acquisition::step_instant(double dt_s, const world::Observables& obs) noexcept {
  // The receiver as it was before acquisition was modelled: C/N0 hysteresis only.
  std::array<bool, kNumSats> above{};
  for (int i = 0; i < obs.num_sats; ++i)
    if (obs.sats[i].above_mask) above[idx(obs.sats[i].sat)] = true;
  for (std::size_t k = 0; k < ch_.size(); ++k) {
    ch_[k].new_lock = false;
    if (!above[k]) instant_[k].reset();
  }
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    if (!o.above_mask) continue;
    const std::size_t k = idx(o.sat);
    bool ok = false;
    if (!obs.signal_modelled) {
      ok = o.received;
    } else if (o.received) {
      ok = instant_[k].update(o.cn0_dbhz, dt_s, thr_);
    } else {
      instant_[k].reset();
    }
    Channel& c = ch_[k];
    c.new_lock = ok && c.state != State::kTracking;
    c.state = ok ? State::kTracking : State::kIdle;
  }
  for (std::size_t k = 0; k < ch_.size(); ++k)
    if (!above[k]) ch_[k].state = State::kIdle;
}

void Acquisition::step(const time::GpsTime& t, double dt_s, const world::Observables& obs,
                       const AidingState& aiding) noexcept {
  now_s_ += dt_s;
  if (!cfg_.modelled) {
    step_instant(dt_s, obs);
    return;
  }
  std::array<bool, kNumSats> seen{};
  bool any_tracked = false;
  for (int i = 0; i < obs.num_sats; ++i) {
    const world::SatObservable& o = obs.sats[i];
    if (!o.above_mask) continue;
    const SatId p = o.sat;
    Channel& c = ch_[idx(p)];
    seen[idx(p)] = true;
    c.new_lock = false;
    // A world without a link budget: every received signal is strong.
    const double cn0 = obs.signal_modelled ? o.cn0_dbhz : cfg_.strong_cn0_dbhz;
    switch (c.state) {
      case State::kTracking:
        if (!o.received || o.lock_break || !(cn0 >= thr_.lose_dbhz)) {
          lose(c);
          break;
        }
        if (!time_known_ && now_s_ >= c.time_at_s) time_known_ = true;
        if (c.downloading && now_s_ >= c.eph_ready_s) {
          c.downloading = false;
          c.eph_until_s = now_s_ + cfg_.ephemeris_validity_s;
        } else if (!c.downloading) {
          c.eph_until_s = now_s_ + cfg_.ephemeris_validity_s;  // decodes each new set while tracking
        }
        break;
      case State::kIdle:
        if (o.received && !o.lock_break) {
          const Search s = classify(p);
          if (cn0 >= threshold_dbhz(s)) {
            c.state = State::kSearching;
            c.search = s;
            c.search_left_s = search_time_s(p, s, cn0);
          }
        }
        break;
      case State::kSearching:
        if (!o.received || !(cn0 >= threshold_dbhz(c.search))) {
          c.state = State::kIdle;  // nothing to find: searched again when it returns
          break;
        }
        c.search_left_s -= dt_s;
        if (c.search_left_s > 0.0) break;
        if (c.search != Search::kCold && !within_aided_window(t, o, aiding, obs.sky)) {
          // Not where the receiver expected it: the full search takes over.
          c.search = Search::kCold;
          c.search_left_s = cfg_.cold_search_s > 0.0 ? search_time_s(p, Search::kCold, cn0) : 0.0;
          if (!(cn0 >= threshold_dbhz(Search::kCold))) c.state = State::kIdle;
          break;
        }
        c.state = State::kTracking;
        c.tracked_before = true;
        c.new_lock = true;
        {
          // Bit synchronisation, then the data at their GPS-time slots: the
          // time of week from the next subframe's first words, the ephemeris
          // from whole subframes 1-3.
          const double phase_s = std::fmod((t + cfg_.bit_sync_s).tow_s(), kFrame_s);
          const double in_subframe_s = std::fmod(phase_s, kSubframe_s);
          c.time_at_s = now_s_ + cfg_.bit_sync_s + (in_subframe_s > 0.0 ? kSubframe_s - in_subframe_s : 0.0) + kHowWords_s;
          if (c.eph_until_s <= now_s_) {
            c.downloading = true;
            c.eph_ready_s = now_s_ + cfg_.bit_sync_s + ephemeris_wait_s(phase_s);
          }
        }
        break;
    }
    if (c.state == State::kTracking) any_tracked = true;
  }
  for (std::size_t k = 0; k < ch_.size(); ++k) {
    if (seen[k]) continue;
    ch_[k].new_lock = false;
    if (ch_[k].state == State::kTracking) lose(ch_[k]);
    ch_[k].state = State::kIdle;
  }
  if (any_tracked && !almanac_known_) {
    almanac_tracking_s_ += dt_s;
    if (almanac_tracking_s_ >= cfg_.almanac_download_s) almanac_known_ = true;
  }
}

}  // namespace gnssemu::receiver
