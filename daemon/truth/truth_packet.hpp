// SPDX-License-Identifier: Apache-2.0
#pragma once
// Truth datagram parser (docs/truth-protocol.md). A pure function: one UDP
// payload in, one validated sample (ECEF, SI) or a drop reason out. Two
// encodings share the port, told apart by the first byte: a JSON object, or
// a fixed little-endian binary record starting with kTruthRecordMagic.
// Never throws; the daemon counts drops per reason and keeps running.
#include <array>
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
/// Binary record (docs/truth-protocol.md §Binary record): magic, then
/// version; its size is fixed per version. 0xF7 never occurs in UTF-8, so
/// it cannot start a JSON text.
inline constexpr std::array<uint8_t, 4> kTruthRecordMagic = {0xF7, 'G', 'T', 'R'};
/// Binary record version this parser accepts.
inline constexpr uint8_t kTruthRecordVersion = 1;
/// Size of a version-1 binary record, bytes.
inline constexpr std::size_t kTruthRecordBytes = 160;
/// Size of the binary record's vehicle id field, bytes (NUL-padded).
inline constexpr std::size_t kTruthRecordVehicleBytes = 64;
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
  kBadMagic,
  kBadSize,
  kMissingVersion,
  kUnknownVersion,
  kBadFlags,
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
  kAttitudeRange,
  kBadGpsTime,
  kBadVehicleId,
  kSimTimeBackwards,
  kTooManyVehicles,
  kUnknownVehicle,  ///< a fleet's packet whose vehicle id is not configured
  kNotAllowed,  ///< sender not in [truth] allow
  kCount
};
inline constexpr std::size_t kDropReasonCount = static_cast<std::size_t>(DropReason::kCount);

/// Short snake_case name of a reason ("sim_time_backwards"), for logs.
const char* drop_reason_name(DropReason reason) noexcept;

/// Attitude of the vehicle body (forward-right-down) relative to local
/// north-east-down, Tait-Bryan yaw-pitch-roll (z-y'-x''), rad.
struct Attitude {
  double roll_rad = 0.0;   ///< right side down positive, [-pi, pi]
  double pitch_rad = 0.0;  ///< nose up positive, [-pi/2, pi/2]
  double yaw_rad = 0.0;    ///< heading clockwise from north, [-pi, 2 pi]
};

/// One validated truth sample.
struct TruthSample {
  std::string vehicle;                 ///< vehicle id, 1..64 printable characters
  double sim_time_s = 0.0;             ///< simulation clock, s (finite)
  Ecef pos_m;                          ///< antenna position, ECEF m
  Lla lla;                             ///< same position, geodetic (rad, m)
  std::optional<Ecef> vel_m_s;         ///< ECEF velocity m/s, when the packet had one
  std::optional<time::GpsTime> gps_time;  ///< from gps_week + gps_tow_s, when given
  std::optional<Attitude> attitude;    ///< binary records only; validated, not yet used by the receiver
};

struct ParseResult {
  bool ok = false;
  DropReason reason = DropReason::kMalformedJson;  ///< valid when !ok
  std::string detail;                  ///< human-readable detail when !ok
  TruthSample sample;                  ///< valid when ok
};

/// Parse and validate one datagram, JSON or binary. frame: the configured
/// local origin, for "enu" positions. Checks everything a single packet can
/// show; ordering (sim time going backwards) is checked by the TruthRouter.
ParseResult parse_truth_packet(std::string_view datagram, const geo::LocalFrame& frame);

}  // namespace gnssemu::daemon
