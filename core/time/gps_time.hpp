// SPDX-License-Identifier: Apache-2.0
#pragma once
// GpsTime: GPS system time as (continuous week, time of week). No leap
// seconds inside GPS time; UTC conversion lives in utc.hpp.
#include <compare>
#include <cstdint>
#include <optional>
#include <string>

namespace gnssemu::time {

/// Calendar date and time of day in some time scale (GPS or UTC).
/// second in [0, 60] (60 only during a positive leap second in UTC).
struct CalendarTime {
  int year = 1980;
  int month = 1;   ///< 1..12
  int day = 6;     ///< 1..31
  int hour = 0;    ///< 0..23
  int minute = 0;  ///< 0..59
  double second = 0.0;
};

/// GpsTime holds weeks -kMaxWeek .. kMaxWeek (about 20,000 years either side
/// of 1980), so week arithmetic never overflows.
inline constexpr int32_t kMaxWeek = 1 << 20;

/// Load time (files, command lines, packets) builds times through the
/// checked constructor or make(), which reject a week shift that does not
/// fit; the per-epoch arithmetic (operator+, operator-) is noexcept and
/// saturates instead (see operator+).
class GpsTime {
public:
  /// GPS epoch 1980-01-06 00:00:00.
  constexpr GpsTime() = default;
  /// week: continuous GPS week (not mod 1024); tow_s: seconds of week, any
  /// finite value (normalised into [0, 604800) with the week adjusted).
  /// Throws gnssemu::Error when tow_s is not finite or the normalised week
  /// leaves [-kMaxWeek, kMaxWeek].
  GpsTime(int32_t week, double tow_s);
  /// As the constructor, without throwing: nullopt where it would throw.
  static std::optional<GpsTime> make(int32_t week, double tow_s) noexcept;

  int32_t week() const noexcept { return week_; }
  /// Seconds of week in [0, 604800).
  double tow_s() const noexcept { return tow_s_; }
  /// Seconds since the GPS epoch (loses sub-microsecond precision after ~2^43 s; use differences).
  double total_s() const noexcept;

  /// Shifted by dt_s seconds (any sign), across week boundaries. Never
  /// throws: a non-finite dt_s leaves the time unchanged, and a result
  /// beyond the supported weeks saturates at the first instant of week
  /// -kMaxWeek or the last of week kMaxWeek.
  GpsTime operator+(double dt_s) const noexcept;
  GpsTime operator-(double dt_s) const noexcept { return *this + (-dt_s); }
  GpsTime& operator+=(double dt_s) noexcept { return *this = *this + dt_s; }
  /// Difference in seconds, exact to double precision of tow.
  double operator-(const GpsTime& o) const noexcept;

  bool operator==(const GpsTime& o) const noexcept { return week_ == o.week_ && tow_s_ == o.tow_s_; }
  std::partial_ordering operator<=>(const GpsTime& o) const noexcept;

  /// From a calendar date/time in the GPS time scale (no leap seconds).
  /// Throws gnssemu::Error when it lies outside the supported weeks.
  static GpsTime from_calendar(const CalendarTime& c);
  /// To a calendar date/time in the GPS time scale.
  CalendarTime to_calendar() const;
  /// Day of year 1..366 of this instant in the GPS time scale.
  int day_of_year() const;
  /// Day of year with the fraction of the day (GPS time scale): 1.0 at
  /// midnight of 1 January, up to 366.99...; what the seasonal terms of the
  /// Niell mapping take.
  double fractional_day_of_year() const;

private:
  struct Normalised {};
  /// week within the range, tow_s in [0, 604800): no checks.
  constexpr GpsTime(int32_t week, double tow_s, Normalised) noexcept : week_(week), tow_s_(tow_s) {}

  int32_t week_ = 0;
  double tow_s_ = 0.0;
};

/// "YYYY-MM-DD HH:MM:SS GPST" (seconds floored), for messages.
std::string calendar_text(const GpsTime& t);

/// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's algorithm).
int64_t days_from_civil(int year, int month, int day) noexcept;
/// Inverse of days_from_civil.
void civil_from_days(int64_t days, int& year, int& month, int& day) noexcept;

/// Full week from a truncated week number (10-bit: modulus 1024, 8-bit: 256),
/// choosing the candidate nearest to reference_week (e.g. the date of the data
/// set or the build date). Ties resolve to the later week.
int32_t resolve_week_nearest(int32_t truncated_week, int32_t reference_week, int32_t modulus = 1024);
/// Full week from a truncated week: the smallest candidate >= reference_week
/// (gpsd's BUILD_WEEK scheme for live receivers).
int32_t resolve_week_at_or_after(int32_t truncated_week, int32_t reference_week, int32_t modulus = 1024);

/// Four-digit year from a RINEX 2 two-digit year: 80..99 -> 19xx, else 20xx.
int year_from_two_digits(int yy) noexcept;

}  // namespace gnssemu::time
