// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/tracking/sbas_reception.hpp"

namespace gnssemu::receiver {

void SbasReception::reset() noexcept {
  geo_.fill(Geo{});
  service_ = nullptr;
  geo_prn_ = 0;
  iono_ = false;
}

double SbasReception::decoded_s(int prn) const noexcept {
  if (prn < kFirstPrn || prn > kLastPrn) return 0.0;
  const Geo& g = geo_[static_cast<std::size_t>(prn - kFirstPrn)];
  return g.silent_s <= kSbasTimeout_s ? g.decoded_s : 0.0;
}

void SbasReception::step(double dt_s, std::span<const SatInfo> sats, const Lla* pos) noexcept {
  if (!(dt_s >= 0.0)) dt_s = 0.0;
  std::array<bool, kLastPrn - kFirstPrn + 1> now{};
  for (const SatInfo& s : sats) {
    if (s.sat.system != GnssSystem::kSbas || !s.tracked || s.cn0_dbhz < kSbasDecodeCn0_dbhz) continue;
    const int prn = s.sat.prn();
    if (prn >= kFirstPrn && prn <= kLastPrn) now[static_cast<std::size_t>(prn - kFirstPrn)] = true;
  }
  for (std::size_t i = 0; i < geo_.size(); ++i) {
    Geo& g = geo_[i];
    if (now[i]) {
      // Decoding resumes within the time-out: the messages held still count.
      g.decoded_s = g.silent_s <= kSbasTimeout_s ? g.decoded_s + dt_s : 0.0;
      g.silent_s = 0.0;
    } else {
      g.silent_s += dt_s;
      if (g.silent_s > kSbasTimeout_s) g.decoded_s = 0.0;
    }
  }
  // The GEO decoded longest among those of a service covering the last fix.
  service_ = nullptr;
  geo_prn_ = 0;
  iono_ = false;
  if (pos == nullptr) return;
  double best_s = -1.0;
  for (int prn = kFirstPrn; prn <= kLastPrn; ++prn) {
    const double d = decoded_s(prn);
    if (d < kSbasFirstCorrections_s || d <= best_s) continue;
    const world::SbasService* s = world::sbas_service_of_prn(prn);
    if (s == nullptr || !world::sbas_covers(*s, *pos)) continue;
    best_s = d;
    service_ = s;
    geo_prn_ = prn;
  }
  iono_ = service_ != nullptr && best_s >= kSbasFirstIono_s;
}

}  // namespace gnssemu::receiver
