// SPDX-License-Identifier: Apache-2.0
#pragma once
// FaultEvent: one scripted fault of a scenario (docs/faults.md): its type,
// when it acts, and its parameters, each a constant or a linear ramp over
// the event. Plain data, shared by the scenario reader, the fault stage and
// the status producer (which lists events with their parameters by name).
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"

namespace gnssemu::faults {

enum class FaultType : std::uint8_t { kJammer, kSpoofer, kOutage, kSkyBlock, kSatellite, kPort };
inline constexpr int kFaultTypeCount = 6;

/// The scenario file's name of a type ("jammer", "spoofer", "outage",
/// "sky_block", "satellite", "port").
std::string_view type_name(FaultType t) noexcept;
/// The type called name, if any.
std::optional<FaultType> type_from_name(std::string_view name) noexcept;

/// Every numeric parameter of every type (the scenario file's keys).
enum class Param : std::uint8_t {
  // jammer
  kJsDb, kEirpDbw, kDistanceM, kLatDeg, kLonDeg, kHeightM, kGainDbi, kFreqMhz, kBandwidthMhz,
  // spoofer
  kPowerAdvantageDb, kCaptureMarginDb, kDragSpeedMS, kDragAccelMS2, kDragHeadingDeg, kDragUpMS,
  kPushRateNsS, kDelayUs, kOffsetEastM, kOffsetNorthM, kOffsetUpM, kClockJumpUs, kSystems,
  // sky_block
  kAzFromDeg, kAzToDeg, kElMinDeg, kElMaxDeg, kLossDb,
  // satellite (clock_jump_us is shared with the spoofer)
  kPrn, kBiasM, kRateMS, kEphRadialM, kEphAlongM, kUnhealthy,
  // port (stored for the daemon's link faults)
  kOutput, kProbability, kLatencyMs, kRateHz, kFixType,
  kCount
};
inline constexpr int kParamCount = static_cast<int>(Param::kCount);

/// A number (from == to) or a linear ramp from -> to over the event.
struct Ramp {
  double from = 0.0;
  double to = 0.0;
  /// Value at fraction f of the event, f in [0, 1].
  constexpr double at(double f) const noexcept { return from + (to - from) * f; }
  constexpr bool ramped() const noexcept { return from != to; }
};

/// What the file may say about one parameter.
struct ParamSpec {
  Param id;
  std::string_view name;           ///< key in the scenario file
  Range range;                     ///< valid values (each end of a ramp)
  std::uint8_t types;              ///< bit per FaultType that takes it
  bool rampable = true;            ///< false: a single number (prn, output, fix_type)
  bool integer = false;            ///< whole numbers only
  bool boolean = false;            ///< true/false in the file (stored as 1/0)
  std::string_view doc;            ///< meaning, with unit
  /// A satellite: a GPS PRN or a RINEX name in the file, stored as sat_param().
  bool satellite = false;
  /// Satellite systems: RINEX letters in the file ("G", "G,R"), stored as
  /// SystemSet::bits().
  bool systems = false;
};

/// A satellite as a parameter value: (system << 8) | RINEX number, so a GPS
/// satellite is its PRN, the plain number a scenario file gives for it.
constexpr double sat_param(SatId sat) noexcept {
  return static_cast<double>((static_cast<int>(sat.system) << 8) | sat.number);
}
/// The satellite of a parameter value; nullopt when it names none.
std::optional<SatId> sat_from_param(double v) noexcept;
/// A satellite parameter in the scenario file's words: the PRN of a GPS
/// satellite ("5"), the RINEX name of any other ("E11").
std::string sat_param_text(double v);

/// A systems parameter value as the scenario file writes it ("G,E").
std::string systems_param_text(double v);

/// The table of every parameter (one row per Param, in Param order).
std::span<const ParamSpec> param_specs() noexcept;
const ParamSpec& spec_of(Param p) noexcept;
/// The parameter called name for type t, if t takes it.
const ParamSpec* find_param(FaultType t, std::string_view name) noexcept;

/// Jammer signal kinds; kappa in docs/faults.md (Kaplan & Hegarty).
enum class JammerKind : std::uint8_t { kWideband, kNarrowband, kCw };
/// Spoofer modes.
enum class SpoofMode : std::uint8_t { kDrag, kTimePush, kMeacon, kTakeover };
/// Outages: every signal blocked (a tunnel), or the antenna open / shorted.
enum class OutageKind : std::uint8_t { kBlockage, kOpen, kShort };
/// Link faults of a port (applied by the daemon's ports, not in the core).
/// rtcm_outage and rtcm_stale act on the RTCM 3 a host sends the port (docs/rtk.md).
enum class LinkFault : std::uint8_t {
  kByteLoss, kCorrupt, kDrop, kLatency, kFreeze, kStop, kRate, kWrongFix, kRtcmOutage, kRtcmStale
};

/// The string key of a type ("kind", "mode", "antenna", "fault"), or empty.
std::string_view mode_key(FaultType t) noexcept;
/// Names the mode key takes for t, in enum order; the first is the default.
std::span<const std::string_view> mode_names(FaultType t) noexcept;

/// "No end": the event lasts to the end of the run.
inline constexpr double kForever_s = std::numeric_limits<double>::infinity();

struct FaultEvent {
  FaultType type = FaultType::kOutage;
  double start_s = 0.0;          ///< after the first epoch (or after "now" when injected), s (>= 0)
  double duration_s = kForever_s;///< s (> 0); infinite: to the end
  std::uint8_t mode = 0;         ///< index into mode_names(type)
  int line = 0;                  ///< line of the [[event]] in its file (0: built in code)
  std::array<Ramp, kParamCount> params{};
  std::uint64_t set = 0;         ///< bit per Param given

  /// An event without parameters yet (add them with put()).
  static FaultEvent of(FaultType type, double start_s, double duration_s = kForever_s, std::uint8_t mode = 0) noexcept {
    FaultEvent e;
    e.type = type;
    e.start_s = start_s;
    e.duration_s = duration_s;
    e.mode = mode;
    return e;
  }

  bool has(Param p) const noexcept { return (set >> static_cast<int>(p)) & 1u; }
  const Ramp& param(Param p) const noexcept { return params[static_cast<int>(p)]; }
  /// Value of p at fraction f of the event (its default when not given).
  double value(Param p, double f) const noexcept;
  void put(Param p, Ramp r) noexcept {
    params[static_cast<int>(p)] = r;
    set |= std::uint64_t{1} << static_cast<int>(p);
  }
  void put(Param p, double v) noexcept { put(p, Ramp{v, v}); }
  double end_s() const noexcept { return start_s + duration_s; }
  /// Active at elapsed time s (start_s <= s < end).
  bool active_at(double s) const noexcept { return s >= start_s && s < end_s(); }
  /// Fraction of the event elapsed at s, in [0, 1] (0 for an endless event).
  double fraction_at(double s) const noexcept;
};

/// One line for status displays: the string key and every given parameter
/// at elapsed time s, in the scenario file's words ("kind=cw js_db=35",
/// ramps at their current value). Allocates; not for the per-epoch path.
std::string describe(const FaultEvent& e, double s);

/// Default of a parameter the event does not give.
double default_value(Param p) noexcept;

/// Cross-field and range rules of one event: each end of a ramp in range,
/// ramps only over a finite duration, the parameters the type needs
/// (jammer: js_db, or eirp_dbw with distance_m or lat/lon; satellite: prn,
/// a valid satellite).
/// Returns the first problem (naming the key) or nothing.
std::optional<std::string> check_event(const FaultEvent& e);

}  // namespace gnssemu::faults
