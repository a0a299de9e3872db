// SPDX-License-Identifier: Apache-2.0
#pragma once
// SbasReception: whether the receiver holds a usable set of SBAS L1
// corrections. It decodes a GEO's messages while tracking it at a C/N0 that
// demodulates its 250 bit/s data; the corrections of a service become usable
// once one of its GEOs has been decoded long enough to have received every
// message they need (RTCA DO-229, maximum update intervals), the receiver's
// last fix lies in the service's area, and no message is older than its
// time-out. Pure, no allocation (docs/models.md "SBAS").
#include <array>
#include <span>

#include "core/common/vec3.hpp"
#include "core/receiver/fix.hpp"
#include "core/world/sky/sbas_service.hpp"

namespace gnssemu::receiver {

/// C/N0 at which the receiver decodes SBAS messages, dB-Hz: an estimate
/// (the acquisition threshold of the tracking loops; SBAS's rate-1/2
/// convolutional code at 500 symbols/s needs about as much as GPS LNAV).
inline constexpr double kSbasDecodeCn0_dbhz = 30.0;
/// Decoding time before the fast and long-term corrections are usable: the
/// PRN mask (message type 1) and long-term corrections (type 25) are each
/// sent at least every 120 s (RTCA DO-229, Table A-8), s.
inline constexpr double kSbasFirstCorrections_s = 120.0;
/// Decoding time before the ionospheric grid is usable: the grid mask (type
/// 18) and delays (type 26) are sent at least every 300 s (same table), s.
inline constexpr double kSbasFirstIono_s = 300.0;
/// A GEO not decoded for longer than this loses its set (the fast
/// corrections' time-out for en-route to non-precision approach, 18 s,
/// RTCA DO-229 Table A-8, as we read it), s.
inline constexpr double kSbasTimeout_s = 18.0;

class SbasReception {
public:
  /// Nothing decoded (a restart, the state after construction).
  void reset() noexcept;
  /// One epoch dt_s (>= 0) after the last: sats the receiver's satellites
  /// this epoch (SBAS GEOs tracked with their C/N0), pos its last fix
  /// (nullptr: none yet, so no service area can be chosen).
  void step(double dt_s, std::span<const SatInfo> sats, const Lla* pos) noexcept;

  /// The service whose corrections apply now; nullptr: none.
  const world::SbasService* service() const noexcept { return service_; }
  /// The GEO (PRN) they come from; 0: none.
  int geo_prn() const noexcept { return geo_prn_; }
  /// The fast and long-term (orbit/clock) corrections are usable.
  bool orbit_clock() const noexcept { return service_ != nullptr; }
  /// The ionospheric grid is usable as well.
  bool iono() const noexcept { return iono_; }
  /// Seconds GEO prn has been decoded without a gap beyond the time-out.
  double decoded_s(int prn) const noexcept;

private:
  static constexpr int kFirstPrn = 120, kLastPrn = 158;
  struct Geo {
    double decoded_s = 0.0;
    double silent_s = kSbasTimeout_s + 1.0;  ///< since its last decoded epoch
  };
  std::array<Geo, kLastPrn - kFirstPrn + 1> geo_{};
  const world::SbasService* service_ = nullptr;
  int geo_prn_ = 0;
  bool iono_ = false;
};

}  // namespace gnssemu::receiver
