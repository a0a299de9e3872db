// SPDX-License-Identifier: Apache-2.0
#include "core/orbit/ephemeris_store.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/common/constants.hpp"

namespace gnssemu::orbit {

namespace {
/// Transmission time, s from toe's week start; unknown counts as earliest.
double transmit_key(const Ephemeris& e) noexcept {
  return e.transmit_known ? e.transmit_tow_s : -std::numeric_limits<double>::infinity();
}
/// Transmission time comparable across sets (absolute, s from the GPS epoch's week 0).
double transmit_key(const Ephemeris* e) noexcept {
  return e->transmit_known ? e->toe.week() * kSecondsPerWeek + e->transmit_tow_s
                           : -std::numeric_limits<double>::infinity();
}

/// Kept for selection: Galileo I/NAV sets only (clock for (E1,E5b), RTKLIB
/// 2.4.3's default); every set of the other systems.
bool selectable(const Ephemeris& e) noexcept {
  return e.sat.system != GnssSystem::kGalileo || (e.gal_data_sources & kGalClockE5b) != 0;
}

/// Health for the L1-band single-frequency user: Galileo E1-B DVS (bit 0)
/// and HS (bits 1-2) of the RINEX health field (multi-gnss.md §5); QZSS
/// without bit 0; the others' whole health value (GPS SV health, BeiDou
/// SatH1, GLONASS Bn, SBAS).
bool healthy(const Ephemeris& e) noexcept {
  if (e.sat.system == GnssSystem::kGalileo) return (e.health & 0x7) == 0;
  // QZSS: bit 0 is not the L1 signal's (RTKLIB 2.4.3 satexclude masks it;
  // every QZSS set of the 2024 IGS files has health 1).
  if (e.sat.system == GnssSystem::kQzss) return (e.health & ~1) == 0;
  return e.health == 0;
}

/// The GLONASS set `last` integrated forward: a set every
/// kGlonassContinuationStep_s up to kGlonassMaxSpan_s past its tb, each the
/// state of the previous one 30 min on, the clock carried along
/// (-tau_n + gamma_n (t - tb) unchanged).
void continue_glonass(const Ephemeris& last, std::vector<Ephemeris>& out) {
  const int n = static_cast<int>(kGlonassMaxSpan_s / kGlonassContinuationStep_s);
  out.reserve(static_cast<std::size_t>(n));
  Ephemeris e = last;
  for (int k = 1; k <= n; ++k) {
    const time::GpsTime tb = last.toe + k * kGlonassContinuationStep_s;
    const SatState s = glonass_state(e, tb, kGlonassStep_s);
    e.tau_n_s -= e.gamma_n * (tb - e.toe);
    e.pos_m = s.pos_m;
    e.vel_m_s = s.vel_m_s;
    e.toe = tb;
    e.toc = tb;
    e.transmit_known = false;
    e.transmit_tow_s = 0.0;
    out.push_back(e);
  }
}

/// The SBAS set `last` held where it is at the end of its window: its
/// polynomial is a fit for minutes (its acceleration held for a day moves a
/// GEO by ~1000 km), a GEO stands nearly still in ECEF.
Ephemeris hold_sbas(const Ephemeris& last) {
  Ephemeris e = last;
  const time::GpsTime end = last.toe + validity_half_window_s(last);
  const SatState s = sat_state(last, end);
  e.toe = end;
  e.toc = end;
  e.pos_m = s.pos_m;
  e.vel_m_s = Ecef();
  e.acc_m_s2 = Ecef();
  e.af0_s = s.clk_bias_s;
  e.af1_s_s = 0.0;
  e.transmit_known = false;
  e.transmit_tow_s = 0.0;
  return e;
}
/// FNV-1a over what selection depends on: per set its satellite, toe,
/// IODs, health and transmission time, then the options.
std::uint64_t content_hash(const std::array<std::vector<Ephemeris>, kNumSats>& by_sat, StoreOptions options) noexcept {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](std::uint64_t v) {
    for (int b = 0; b < 8; ++b) {
      h ^= (v >> (8 * b)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  for (const auto& v : by_sat) {
    for (const Ephemeris& e : v) {
      mix(static_cast<std::uint64_t>(e.sat.index()));
      mix(static_cast<std::uint64_t>(e.toe.week()));
      mix(static_cast<std::uint64_t>(std::llround(e.toe.tow_s() * 1e3)));
      mix(static_cast<std::uint64_t>(e.iode) << 32 | static_cast<std::uint32_t>(e.iodc));
      mix(static_cast<std::uint64_t>(e.health));
      mix(static_cast<std::uint64_t>(std::llround(e.transmit_tow_s * 1e3)));
    }
  }
  mix(options.continue_after_data ? 1u : 0u);
  return h;
}
}  // namespace

EphemerisStore::EphemerisStore(const std::vector<Ephemeris>& ephemerides, StoreOptions options) : options_(options) {
  for (const Ephemeris& e : ephemerides) {
    if (e.sat.valid() && selectable(e)) by_sat_[static_cast<std::size_t>(e.sat.index())].push_back(e);
  }
  for (std::size_t i = 0; i < by_sat_.size(); ++i) {
    auto& v = by_sat_[i];
    // Stable: equal (toe, transmit) keep file order, so the later one is last.
    std::stable_sort(v.begin(), v.end(), [](const Ephemeris& a, const Ephemeris& b) {
      if (a.toe != b.toe) return a.toe < b.toe;
      return transmit_key(a) < transmit_key(b);
    });
    auto& u = usable_[i];
    // Unhealthy sets stay candidates: they are the current broadcast.
    // Galileo: the first transmitted of equal toes, as RTKLIB 2.4.3's
    // uniqeph() keeps the first set of an IODnav (I/NAV E1-B, E5b and merged
    // records of one toe differ in af0 by up to ~6e-11 s).
    const bool first_wins = !v.empty() && v.front().sat.system == GnssSystem::kGalileo;
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (!u.empty() && v[u.back()].toe == v[k].toe) {
        if (!first_wins) u.back() = k;  // later transmitted duplicate replaces the earlier one
      } else {
        u.push_back(k);
      }
    }
    if (options_.continue_after_data && !u.empty() && v[u.back()].sat.system == GnssSystem::kGlonass) {
      continue_glonass(v[u.back()], continued_[i]);
    }
    if (options_.continue_after_data && !u.empty() && v[u.back()].sat.system == GnssSystem::kSbas) {
      continued_[i].push_back(hold_sbas(v[u.back()]));
    }
  }
  fingerprint_ = content_hash(by_sat_, options_);
}

const Ephemeris* EphemerisStore::select(SatId sat, const time::GpsTime& t) const noexcept {
  if (!sat.valid()) return nullptr;
  const auto& v = by_sat_[static_cast<std::size_t>(sat.index())];
  const auto& u = usable_[static_cast<std::size_t>(sat.index())];
  if (u.empty()) return nullptr;
  // First usable set with toe >= t; its predecessor is the other candidate.
  const auto it = std::lower_bound(u.begin(), u.end(), t,
                                   [&v](std::size_t i, const time::GpsTime& tt) { return v[i].toe < tt; });
  const Ephemeris* after = it != u.end() ? &v[*it] : nullptr;
  const Ephemeris* before = it != u.begin() ? &v[*(it - 1)] : nullptr;
  auto valid = [&t](const Ephemeris* e) {
    return e != nullptr && std::fabs(t - e->toe) <= validity_half_window_s(*e);
  };
  const Ephemeris* first = after;
  const Ephemeris* second = before;
  if (before != nullptr && after != nullptr) {
    const double d_before = t - before->toe, d_after = after->toe - t;
    // Equal distance: the later transmitted, then the later toe (RTKLIB).
    if (d_before < d_after || (d_before == d_after && transmit_key(before) > transmit_key(after))) {
      first = before;
      second = after;
    }
  } else if (before != nullptr) {
    first = before;
    second = nullptr;
  }
  if (sat.system == GnssSystem::kGalileo) {
    // Only sets with toe < t (RTKLIB 2.4.3 seleph: "AOD <= 0" skipped).
    first = before;
    second = nullptr;
  }
  const Ephemeris* chosen = valid(first) ? first : valid(second) ? second : nullptr;
  if (chosen == nullptr && options_.continue_after_data && after == nullptr && before != nullptr) {
    chosen = before;  // past the satellite's last set: its orbit goes on
    const auto& c = continued_[static_cast<std::size_t>(sat.index())];
    if (!c.empty() && sat.system == GnssSystem::kSbas) {
      chosen = &c.front();
    } else if (!c.empty()) {  // GLONASS: the nearest continued set
      const double k = std::round((t - before->toe) / kGlonassContinuationStep_s);
      if (k >= 1.0) chosen = &c[static_cast<std::size_t>(std::min(k, static_cast<double>(c.size()))) - 1];
    }
  }
  // A satellite flagged unhealthy in its current set is not used, even if
  // an older healthy set is still within its validity window. An SBAS GEO's
  // health is its ranging's: flagged, it still broadcasts its corrections and
  // stays in the sky (tracked and decoded, not ranged: receiver SatInfo::healthy).
  if (chosen != nullptr && sat.system == GnssSystem::kSbas) return chosen;
  return chosen != nullptr && healthy(*chosen) ? chosen : nullptr;
}

const Ephemeris* EphemerisStore::select(SatId sat, const time::GpsTime& t, time::GpsTime& until) const noexcept {
  const Ephemeris* chosen = select(sat, t);
  until = t;
  if (!sat.valid()) return chosen;
  const auto& v = by_sat_[static_cast<std::size_t>(sat.index())];
  const auto& u = usable_[static_cast<std::size_t>(sat.index())];
  if (u.empty()) return chosen;
  const auto it = std::lower_bound(u.begin(), u.end(), t,
                                   [&v](std::size_t i, const time::GpsTime& tt) { return v[i].toe < tt; });
  const Ephemeris* after = it != u.end() ? &v[*it] : nullptr;
  const Ephemeris* before = it != u.begin() ? &v[*(it - 1)] : nullptr;
  // Past the last set a continued GLONASS set changes every step: no span.
  if (after == nullptr && options_.continue_after_data && sat.system == GnssSystem::kGlonass) return chosen;
  // What select() compares changes only at these times: the next toe (the
  // pair moves on), the midpoint of the pair, and the validity edges. Each
  // is taken a microsecond early against rounding in t - toe.
  constexpr double kGuard_s = 1e-6;
  double span_s = 1e9;  // ~30 years
  const auto event = [&](double at_s) {
    if (at_s > -kGuard_s) span_s = std::min(span_s, at_s - kGuard_s);
  };
  if (after != nullptr) {
    event(after->toe - t);
    event(after->toe - t - validity_half_window_s(*after));
  }
  if (before != nullptr) event(before->toe - t + validity_half_window_s(*before));
  if (before != nullptr && after != nullptr) event(0.5 * ((before->toe - t) + (after->toe - t)));
  if (span_s > 0.0) until = t + span_s;  // no event ahead: the answer holds
  return chosen;
}

std::size_t EphemerisStore::count(SatId sat) const noexcept {
  if (!sat.valid()) return 0;
  return by_sat_[static_cast<std::size_t>(sat.index())].size();
}

std::size_t EphemerisStore::size() const noexcept {
  std::size_t n = 0;
  for (const auto& v : by_sat_) n += v.size();
  return n;
}

time::GpsTime EphemerisStore::first_valid() const noexcept {
  bool any = false;
  time::GpsTime best;
  for (const auto& v : by_sat_) {
    for (const Ephemeris& e : v) {
      const time::GpsTime s = e.toe - validity_half_window_s(e);
      if (!any || s < best) best = s;
      any = true;
    }
  }
  return best;
}

time::GpsTime EphemerisStore::last_valid() const noexcept {
  bool any = false;
  time::GpsTime best;
  for (const auto& v : by_sat_) {
    for (const Ephemeris& e : v) {
      const time::GpsTime s = e.toe + validity_half_window_s(e);
      if (!any || s > best) best = s;
      any = true;
    }
  }
  return best;
}

}  // namespace gnssemu::orbit

namespace gnssemu::orbit {

std::vector<TimeSpan> EphemerisStore::coverage() const {
  std::vector<TimeSpan> spans;
  for (const auto& v : by_sat_) {
    for (const Ephemeris& e : v) {
      const double w = validity_half_window_s(e);
      spans.push_back({e.toe - w, e.toe + w});
    }
  }
  std::sort(spans.begin(), spans.end(), [](const TimeSpan& a, const TimeSpan& b) { return a.begin < b.begin; });
  std::vector<TimeSpan> merged;
  for (const TimeSpan& s : spans) {
    if (!merged.empty() && !(merged.back().end < s.begin)) {
      if (merged.back().end < s.end) merged.back().end = s.end;
    } else {
      merged.push_back(s);
    }
  }
  return merged;
}

}  // namespace gnssemu::orbit
