// SPDX-License-Identifier: Apache-2.0
#pragma once
// The L1-band civil signal of each system as the signal stage sees it: the
// main lobe an interferer must overlap to hurt it, and how its C/N0 differs
// from the GPS link budget's at the same range, carrier and elevation. One
// row per system in the order of the system table (gnss_systems.hpp);
// sources and the fit in docs/models.md ("C/N0 per system").
#include <array>
#include <cstddef>

#include "core/common/gnss_systems.hpp"

namespace gnssemu::signal {

struct SystemSignal {
  GnssSystem system;
  /// Half width of the main lobe around the satellite's carrier, Hz: BPSK
  /// chip rate (GPS/QZSS/SBAS C/A 1.023 Mchip/s, GLONASS C/A 0.511, BeiDou
  /// B1I 2.046), Galileo E1 CBOC the outer edge of its BOC(1,1) lobes.
  double main_lobe_half_width_hz;
  /// C/N0 over the GPS link budget at the zenith, dB (satellite power and
  /// antenna: fitted to station C/N0; QZSS and SBAS: no fit data, 0).
  double power_offset_db;
  /// Extra C/N0 change per unit of (1 - sin el) over the GPS link budget's,
  /// dB (the satellite antenna's pattern over the Earth, fitted alike).
  double slope_offset_db;
};

inline constexpr std::array<SystemSignal, kNumSystems> kSystemSignals{{
    {GnssSystem::kGps, 1.023e6, 0.0, 0.0},
    {GnssSystem::kGlonass, 0.511e6, 1.85, -0.31},
    {GnssSystem::kGalileo, 2.046e6, 2.69, 0.33},
    {GnssSystem::kBeiDou, 2.046e6, 1.41, 0.12},
    {GnssSystem::kQzss, 1.023e6, 0.0, 0.0},
    {GnssSystem::kSbas, 1.023e6, 0.0, 0.0},
}};

constexpr const SystemSignal& system_signal(GnssSystem s) noexcept {
  return kSystemSignals[static_cast<std::size_t>(s)];
}

constexpr bool system_signals_in_table_order() noexcept {
  for (std::size_t i = 0; i < kSystemSignals.size(); ++i)
    if (kSystemSignals[i].system != kSystems[i].system) return false;
  return true;
}
static_assert(system_signals_in_table_order());

}  // namespace gnssemu::signal
