// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/nmea/nmea_sky.hpp"

#include <algorithm>
#include <cmath>

namespace gnssemu::protocol::nmea {

namespace {

constexpr std::array<NmeaSystem, kNumNmeaSystems> kNmeaSystems{NmeaSystem::kGps, NmeaSystem::kGlonass,
                                                                NmeaSystem::kGalileo, NmeaSystem::kBeiDou,
                                                                NmeaSystem::kQzss};

bool in_view(const receiver::SatInfo& s) noexcept {
  return s.healthy && std::isfinite(s.el_rad) && s.el_rad >= 0.0 && std::isfinite(s.az_rad);
}

// Stable and allocation-free (std::stable_sort may take a heap buffer); n <= kMaxSatsInView.
template <class Less>
void insertion_sort(ReportedSv* first, ReportedSv* last, Less less) noexcept {
  for (ReportedSv* i = first + (first != last ? 1 : 0); i < last; ++i) {
    const ReportedSv v = *i;
    ReportedSv* j = i;
    for (; j > first && less(v, *(j - 1)); --j) *j = *(j - 1);
    *j = v;
  }
}

bool by_number(const ReportedSv& a, const ReportedSv& b) noexcept { return a.number < b.number; }
bool used_first(const ReportedSv& a, const ReportedSv& b) noexcept {
  return a.used != b.used ? a.used : a.number < b.number;
}

}  // namespace

NmeaSky::NmeaSky(const receiver::Fix& fix, const NmeaSettings& cfg, bool has_fix) noexcept {
  const int n = std::clamp(fix.num_sats, 0, static_cast<int>(fix.sats.size()));
  SystemSet enabled = cfg.systems;
  for (int i = 0; i < n; ++i) {
    const SatId id = fix.sats[static_cast<std::size_t>(i)].sat;
    if (id.valid()) enabled = enabled.with(id.system);
  }
  for (const SatNumbering& row : kSatNumbering) {
    if (enabled.has(row.system)) present_[index(nmea_system(row.system, cfg.version))] = true;
  }
  // A receiver with nothing enabled and nothing in view reports as GPS.
  if (num_present() == 0) present_[index(NmeaSystem::kGps)] = true;

  int next = 0;
  for (NmeaSystem ns : kNmeaSystems) {
    const std::size_t k = index(ns);
    first_[k] = next;
    for (int i = 0; i < n && next < kMaxSatsInView; ++i) {
      const receiver::SatInfo& s = fix.sats[static_cast<std::size_t>(i)];
      if (!s.sat.valid() || cfg.filtered.has(s.sat.system) || nmea_system(s.sat.system, cfg.version) != ns) continue;
      const int number = nmea_sv_number(s.sat, cfg.version, cfg.sv_numbering);
      const bool used = has_fix && (s.used || (cfg.consider && s.excluded && s.tracked));
      if (number == 0 || (!used && !in_view(s))) continue;
      sv_[static_cast<std::size_t>(next++)] = {number, &s, used};
    }
    ReportedSv* const seg = sv_.data() + first_[k];
    int count = next - first_[k];
    // CFG-NMEA numSV: the used satellites stay, so used <= in view holds.
    if (cfg.max_svs > 0 && count > cfg.max_svs) {
      insertion_sort(seg, seg + count, used_first);
      count = cfg.max_svs;
      next = first_[k] + count;
    }
    insertion_sort(seg, seg + count, by_number);
    count_[k] = count;
    used_[k] = static_cast<int>(std::count_if(seg, seg + count, [](const ReportedSv& r) { return r.used; }));
  }
}

int NmeaSky::num_present() const noexcept {
  return static_cast<int>(std::count(present_.begin(), present_.end(), true));
}

int NmeaSky::total_used() const noexcept {
  int total = 0;
  for (int u : used_) total += u;
  return total;
}

}  // namespace gnssemu::protocol::nmea
