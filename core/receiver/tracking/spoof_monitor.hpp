// SPDX-License-Identifier: Apache-2.0
#pragma once
// Spoofing detection of the emulated receiver, reported as u-blox does in
// NAV-STATUS flags2 spoofDetState (0 unknown, 1 no spoofing indicated,
// 2 spoofing indicated, 3 multiple indications). The receiver sees only its
// own measurements and solution; the criteria are the classic receiver-side
// checks (Psiaki & Humphreys, "GNSS Spoofing and Detection", Proc. IEEE
// 104(6), 2016, §IV): a simultaneous C/N0 jump, a receiver clock jump, and
// C/N0 uniformity across satellites (one transmitter sends every PRN at one
// power), and with several systems tracked the disagreement of the GPS
// satellites with the others (a GPS-only spoofer leaves the rest authentic:
// Psiaki & Humphreys §IV, consistency across signals). Pure; no allocation.
#include <array>
#include <cstdint>
#include <optional>

#include "core/common/constants.hpp"
#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/violation.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::receiver {

struct SpoofDetectionConfig {
  bool enabled = true;              ///< false: spoofDetState 0 (deactivated)
  double cn0_jump_db = 5.0;         ///< rise of one satellite's C/N0 between epochs that counts as a jump, dB
  int cn0_jump_sats = 3;            ///< satellites that must jump in the same epoch
  double clock_jump_m = 150.0;      ///< clock bias change beyond the drift prediction, m (c x 500 ns)
  double uniform_std_db = 1.0;      ///< C/N0 spread below which the sky looks like one transmitter, dB
  int uniform_min_sats = 5;         ///< tracked satellites the uniformity test needs
  /// Distance between the positions the used GPS satellites and the used
  /// satellites of the other systems each point to, beyond which they
  /// disagree, m (each side needs kSystemGroupMinSats); one group excluded
  /// wholesale (one_group_excluded) counts as disagreement too. 0 disables both.
  double system_disagreement_m = 50.0;
  double hold_s = 30.0;             ///< an indication is reported this long, s
};

struct SpoofDetectionRanges {
  static constexpr Range cn0_jump_db{0.0, 60.0, "dB", true};
  static constexpr Range cn0_jump_sats{1.0, kMaxSatsInView, ""};
  static constexpr Range clock_jump_m{0.0, 3.0e8, "m", true};
  static constexpr Range uniform_std_db{0.0, 20.0, "dB"};
  static constexpr Range uniform_min_sats{2.0, kMaxSatsInView, ""};
  static constexpr Range system_disagreement_m{0.0, 1.0e6, "m"};
  static constexpr Range hold_s{0.0, 86400.0, "s"};
};

/// Throws gnssemu::Error for a value out of range.
void validate(const SpoofDetectionConfig& c);

/// Which criteria fired, as bits.
enum SpoofIndication : std::uint8_t {
  kSpoofCn0Jump = 1,
  kSpoofClockJump = 2,
  kSpoofCn0Uniform = 4,
  kSpoofSystemDisagreement = 8,
};
inline constexpr int kSpoofCriteria = 4;

/// Used satellites each side of the system-disagreement test needs (four
/// unknowns and one to spare).
inline constexpr int kSystemGroupMinSats = 5;

/// How far the GPS satellites' position lies from the other systems', m: the
/// least-squares position correction each group's post-fit residuals ask
/// for (residual = -los . dx + clock, los from az/el), differenced (ENU norm).
/// Used satellites with their residuals only; nullopt when either group has
/// fewer than kSystemGroupMinSats or a singular geometry.
std::optional<double> system_disagreement_m(const Fix& fix) noexcept;

/// Excluded satellites that make one group's exclusion wholesale.
inline constexpr int kSystemExclusionMinSats = 3;

/// The residual test threw one group out: at least kSystemExclusionMinSats
/// of the GPS satellites (or of the others) excluded, at least half of that
/// group's tracked ones, and none of the other group's (what the solution's
/// fault exclusion makes of a spoofed minority of systems).
bool one_group_excluded(const Fix& fix) noexcept;

class SpoofMonitor {
public:
  explicit SpoofMonitor(const SpoofDetectionConfig& c) : c_(c) {}
  /// Look at this epoch's fix (after the solution); returns spoofDetState.
  std::uint8_t update(const Fix& fix) noexcept;
  void reset() noexcept;
  /// Criteria that fired within the hold time (SpoofIndication bits).
  std::uint8_t indications() const noexcept { return held_; }

private:
  SpoofDetectionConfig c_;
  std::array<double, kNumSats> prev_cn0_{};  ///< last epoch's C/N0 of tracked satellites (0: not tracked)
  bool have_clock_ = false;
  time::GpsTime prev_t_;
  double prev_clock_m_ = 0.0, prev_drift_m_s_ = 0.0;
  std::array<double, kSpoofCriteria> last_seen_s_{-1e30, -1e30, -1e30, -1e30};  ///< per criterion, GPS seconds
  std::uint8_t held_ = 0;
};

}  // namespace gnssemu::receiver
