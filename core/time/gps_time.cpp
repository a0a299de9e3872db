// SPDX-License-Identifier: Apache-2.0
#include "core/time/gps_time.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>

#include <string>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"

namespace gnssemu::time {

namespace {
constexpr int64_t kGpsEpochDays = 3657;  // 1980-01-06 minus 1970-01-01

/// Outcome of normalising (week, tow) into tow in [0, 604800).
enum class Fit { kOk, kNotFinite, kBelow, kAbove };

/// week_d: a whole number of weeks as a double (exact below 2^53), so the
/// week shift is checked before any conversion to int.
Fit normalise(double week_d, double tow_s, int32_t& week, double& tow) noexcept {
  if (!std::isfinite(tow_s)) return Fit::kNotFinite;
  const double w = std::floor(tow_s / kSecondsPerWeek);
  double full = week_d + w;
  if (!(full >= -kMaxWeek)) return Fit::kBelow;
  if (!(full <= kMaxWeek)) return Fit::kAbove;
  tow = tow_s - w * kSecondsPerWeek;
  if (tow >= kSecondsPerWeek) {  // rounding at the edge
    tow -= kSecondsPerWeek;
    full += 1.0;
    if (full > kMaxWeek) return Fit::kAbove;
  }
  if (tow < 0.0) tow = 0.0;
  week = static_cast<int32_t>(full);
  return Fit::kOk;
}
}  // namespace

GpsTime::GpsTime(int32_t week, double tow_s) {
  switch (normalise(week, tow_s, week_, tow_s_)) {
    case Fit::kOk: return;
    case Fit::kNotFinite: throw Error("GPS time: time of week " + std::to_string(tow_s) + " s is not finite");
    case Fit::kBelow:
    case Fit::kAbove:
      throw Error("GPS time: week " + std::to_string(week) + " + " + std::to_string(tow_s) +
                  " s lies outside the supported weeks -" + std::to_string(kMaxWeek) + " .. " +
                  std::to_string(kMaxWeek));
  }
}

std::optional<GpsTime> GpsTime::make(int32_t week, double tow_s) noexcept {
  int32_t w = 0;
  double tow = 0.0;
  if (normalise(week, tow_s, w, tow) != Fit::kOk) return std::nullopt;
  return GpsTime(w, tow, Normalised{});
}

double GpsTime::total_s() const noexcept { return week_ * kSecondsPerWeek + tow_s_; }

GpsTime GpsTime::operator+(double dt_s) const noexcept {
  // Within the week (the per-epoch case): no division, no floor. NaN and
  // infinities fail the test and take the general path.
  if (const double t = tow_s_ + dt_s; t >= 0.0 && t < kSecondsPerWeek) return GpsTime(week_, t, Normalised{});
  if (!std::isfinite(dt_s)) return *this;
  int32_t w = 0;
  double tow = 0.0;
  switch (normalise(week_, tow_s_ + dt_s, w, tow)) {
    case Fit::kOk: return GpsTime(w, tow, Normalised{});
    case Fit::kBelow: return GpsTime(-kMaxWeek, 0.0, Normalised{});
    case Fit::kAbove:
    case Fit::kNotFinite:  // tow_s_ + dt_s overflowed: dt_s is huge and positive or negative
      break;
  }
  if (dt_s < 0.0) return GpsTime(-kMaxWeek, 0.0, Normalised{});
  return GpsTime(kMaxWeek, std::nextafter(kSecondsPerWeek, 0.0), Normalised{});
}

double GpsTime::operator-(const GpsTime& o) const noexcept {
  return (week_ - o.week_) * kSecondsPerWeek + (tow_s_ - o.tow_s_);
}

std::partial_ordering GpsTime::operator<=>(const GpsTime& o) const noexcept {
  if (week_ != o.week_) return week_ <=> o.week_;
  return tow_s_ <=> o.tow_s_;
}

int64_t days_from_civil(int year, int month, int day) noexcept {
  const int64_t y = static_cast<int64_t>(year) - (month <= 2 ? 1 : 0);
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const int64_t yoe = y - era * 400;
  const int64_t mp = (month + 9) % 12;
  const int64_t doy = (153 * mp + 2) / 5 + day - 1;
  const int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

void civil_from_days(int64_t z, int& year, int& month, int& day) noexcept {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const int64_t doe = z - era * 146097;
  const int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const int64_t y = yoe + era * 400;
  const int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const int64_t mp = (5 * doy + 2) / 153;
  const int64_t d = doy - (153 * mp + 2) / 5 + 1;
  const int64_t m = mp < 10 ? mp + 3 : mp - 9;
  year = static_cast<int>(y + (m <= 2 ? 1 : 0));
  month = static_cast<int>(m);
  day = static_cast<int>(d);
}

GpsTime GpsTime::from_calendar(const CalendarTime& c) {
  const int64_t days = days_from_civil(c.year, c.month, c.day) - kGpsEpochDays;
  const int64_t week = days >= 0 ? days / 7 : -((-days + 6) / 7);
  if (week < -kMaxWeek || week > kMaxWeek) {
    throw Error("GPS time: year " + std::to_string(c.year) + " lies outside the supported weeks -" +
                std::to_string(kMaxWeek) + " .. " + std::to_string(kMaxWeek));
  }
  const int64_t dow = days - week * 7;
  const double tow = static_cast<double>(dow) * kSecondsPerDay + c.hour * 3600.0 + c.minute * 60.0 + c.second;
  return GpsTime(static_cast<int32_t>(week), tow);
}

CalendarTime GpsTime::to_calendar() const {
  const int64_t dow = static_cast<int64_t>(std::floor(tow_s_ / kSecondsPerDay));
  double sod = tow_s_ - static_cast<double>(dow) * kSecondsPerDay;
  CalendarTime c;
  civil_from_days(kGpsEpochDays + static_cast<int64_t>(week_) * 7 + dow, c.year, c.month, c.day);
  c.hour = static_cast<int>(sod / 3600.0);
  sod -= c.hour * 3600.0;
  c.minute = static_cast<int>(sod / 60.0);
  c.second = sod - c.minute * 60.0;
  return c;
}

std::string calendar_text(const GpsTime& t) {
  const CalendarTime c = t.to_calendar();
  char buf[96];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02d %02d:%02d:%02d GPST", c.year, c.month, c.day, c.hour, c.minute,
                static_cast<int>(std::floor(c.second)));
  return buf;
}

int GpsTime::day_of_year() const {
  const CalendarTime c = to_calendar();
  return static_cast<int>(days_from_civil(c.year, c.month, c.day) - days_from_civil(c.year, 1, 1) + 1);
}

double GpsTime::fractional_day_of_year() const {
  return day_of_year() + std::fmod(tow_s_, kSecondsPerDay) / kSecondsPerDay;
}

int32_t resolve_week_nearest(int32_t truncated_week, int32_t reference_week, int32_t modulus) {
  const int32_t base = reference_week - (reference_week % modulus);
  int32_t best = base + (truncated_week % modulus);
  for (int32_t cand : {best - modulus, best + modulus}) {
    const int32_t d_best = std::abs(best - reference_week);
    const int32_t d_cand = std::abs(cand - reference_week);
    if (d_cand < d_best || (d_cand == d_best && cand > best)) best = cand;
  }
  return best;
}

int32_t resolve_week_at_or_after(int32_t truncated_week, int32_t reference_week, int32_t modulus) {
  int32_t w = reference_week - (reference_week % modulus) + (truncated_week % modulus);
  if (w < reference_week) w += modulus;
  return w;
}

int year_from_two_digits(int yy) noexcept { return yy >= 80 ? 1900 + yy : 2000 + yy; }

}  // namespace gnssemu::time
