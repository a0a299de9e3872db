// SPDX-License-Identifier: Apache-2.0
#pragma once
// One state per satellite for the sky plot, the C/N0 bars and the report
// (docs/status.md): what a u-center user reads from the colours.
#include <string_view>

#include "core/receiver/fix.hpp"

namespace gnssemu::daemon {

enum class SatState {
  kUsed,       ///< in the navigation solution, line of sight
  kNlos,       ///< tracked via reflections only (used or not: the fill tells)
  kExcluded,   ///< tracked, removed by fault detection (residual test)
  kTracked,    ///< tracked, not in the solution (no fix this epoch)
  kSearching,  ///< above the mask with a signal, not (yet) tracked: too weak or being acquired
  kBlocked,    ///< above the mask, no signal path (a building)
  kBelowMask,  ///< above the horizon, below the elevation mask
};

/// State of one satellite of a Fix. NLOS wins over used and tracked: it is
/// what a user looks for; the separate used flag tells whether it is used.
constexpr SatState sat_state(const receiver::SatInfo& s) noexcept {
  if (!s.above_mask) return SatState::kBelowMask;
  if (s.blocked) return SatState::kBlocked;
  if (!s.tracked) return SatState::kSearching;
  if (s.excluded) return SatState::kExcluded;
  if (s.nlos) return SatState::kNlos;
  return s.used ? SatState::kUsed : SatState::kTracked;
}

/// "used", "nlos", "excluded", "tracked", "searching", "blocked", "below_mask".
constexpr std::string_view sat_state_name(SatState s) noexcept {
  switch (s) {
    case SatState::kUsed: return "used";
    case SatState::kNlos: return "nlos";
    case SatState::kExcluded: return "excluded";
    case SatState::kTracked: return "tracked";
    case SatState::kSearching: return "searching";
    case SatState::kBlocked: return "blocked";
    case SatState::kBelowMask: return "below_mask";
  }
  return "unknown";
}

}  // namespace gnssemu::daemon
