// SPDX-License-Identifier: Apache-2.0
#pragma once
// ReportedFix: a fix type as a port reports it, numbered as UBX NAV-PVT
// fixType (u-blox M8 protocol specification, UBX-NAV-PVT; NAV-STATUS and
// NAV-SOL gpsFix use the same numbers). Normally a port reports the
// receiver's own fix type; a link fault (wrong_fix, docs/faults.md) makes
// one port report another, and both encoders take it as an override of the
// fix-type fields only (positions still come from the Fix).
#include <cstdint>
#include <optional>

namespace gnssemu::protocol {

enum class ReportedFix : std::uint8_t {
  kNoFix = 0,
  kDeadReckoning = 1,       ///< dead reckoning only
  k2D = 2,
  k3D = 3,
  kGnssDeadReckoning = 4,   ///< GNSS + dead reckoning combined
  kTimeOnly = 5,            ///< time only (no position solution)
};
inline constexpr int kReportedFixCount = 6;

/// A fix type reported instead of the receiver's; nothing: the receiver's own.
using FixOverride = std::optional<ReportedFix>;

/// gnssFixOK (NAV-PVT) / gpsFixOk (NAV-STATUS, NAV-SOL) for a reported type:
/// set for a GNSS solution (2D, 3D, GNSS + dead reckoning).
constexpr bool gnss_fix_ok(ReportedFix f) noexcept {
  return f == ReportedFix::k2D || f == ReportedFix::k3D || f == ReportedFix::kGnssDeadReckoning;
}

}  // namespace gnssemu::protocol
