#pragma once
// Truth datagram parser (docs/truth-protocol.md). A pure function: one UDP
// payload in, one validated sample (ECEF, SI) or a drop reason out. Never
// throws; the daemon counts drops per reason and keeps running.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/vec3.hpp"
#include "core/geo/local_frame.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::daemon {

/// Protocol version this parser accepts in the "version" field.
inline constexpr int kTruthProtocolVersion = 1;
/// Largest datagram accepted, bytes.
inline constexpr std::size_t kMaxTruthDatagramBytes = 4096;
/// Limits of plausible truth (docs/truth-protocol.md §Validation).
inline constexpr double kMinHeight_m = -1000.0;
inline constexpr double kMaxHeight_m = 100000.0;
inline constexpr double kMaxSpeed_m_s = 1000.0;
inline constexpr std::size_t kMaxVehicleIdChars = 64;

/// Why a datagram was dropped. Order is the log/report order.
enum class DropReason : uint8_t {
  kTooLarge,
  kMalformedJson,
  kNotObject,
  kMissingVersion,
  kUnknownVersion,
  kMissingField,
  kBadType,
  kNonFinite,
  kMissingPosition,
  kDuplicatePosition,
  kDuplicateVelocity,
  kDuplicateKey,
  kLatitudeRange,
  kLongitudeRange,
  kHeightRange,
  kSpeedRange,
  kBadGpsTime,
  kBadVehicleId,
  kSimTimeBackwards,
  kTooManyVehicles,
  kCount
};
inline constexpr std::size_t kDropReasonCount = static_cast<std::size_t>(DropReason::kCount);

/// Short snake_case name of a reason ("sim_time_backwards"), for logs.
const char* drop_reason_name(DropReason reason) noexcept;

/// One validated truth sample.
struct TruthSample {
  std::string vehicle;                 ///< vehicle id, 1..64 printable characters
  double sim_time_s = 0.0;             ///< simulation clock, s (finite)
  Ecef pos_m;                          ///< antenna position, ECEF m
  Lla lla;                             ///< same position, geodetic (rad, m)
  std::optional<Ecef> vel_m_s;         ///< ECEF velocity m/s, when the packet had one
  std::optional<time::GpsTime> gps_time;  ///< from gps_week + gps_tow_s, when given
};

struct ParseResult {
  bool ok = false;
  DropReason reason = DropReason::kMalformedJson;  ///< valid when !ok
  std::string detail;                  ///< human-readable detail when !ok
  TruthSample sample;                  ///< valid when ok
};

/// Parse and validate one datagram. frame: the configured local origin, for
/// "enu" positions. Checks everything a single packet can show; ordering
/// (sim time going backwards) is checked by the TruthTrack.
ParseResult parse_truth_packet(std::string_view datagram, const geo::LocalFrame& frame);

}  // namespace gnssemu::daemon
