// SPDX-License-Identifier: Apache-2.0
#pragma once
// The satellites of one epoch as the NMEA sentences report them: per NMEA
// system (GSA) and GSV group, numbered as u-blox numbers them, capped as
// CFG-NMEA caps them. Built once per epoch on the stack; no allocation.
#include <array>
#include <cstddef>

#include "core/protocol/nmea/nmea_numbering.hpp"
#include "core/protocol/nmea/nmea_settings.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::nmea {

/// One reported satellite.
struct ReportedSv {
  int number = 0;                            ///< NMEA number (nmea_sv_number)
  const receiver::SatInfo* sat = nullptr;
  bool used = false;                         ///< listed in GSA, counted in GGA/GNS numSV
};

class NmeaSky {
public:
  /// GSA slots on a u-blox: 12 SV fields per sentence (extra used SVs are not listed).
  static constexpr int kGsaSlots = 12;

  /// fix's satellites under cfg; used ones only with has_fix (a position to report).
  NmeaSky(const receiver::Fix& fix, const NmeaSettings& cfg, bool has_fix) noexcept;

  /// The system has a GSA and a GSV group this epoch (enabled, or has satellites).
  bool present(NmeaSystem s) const noexcept { return present_[index(s)]; }
  /// Number of present NMEA systems.
  int num_present() const noexcept;
  /// Satellites of s's GSV group, in NMEA number order (in view or used).
  const ReportedSv* begin(NmeaSystem s) const noexcept { return sv_.data() + first_[index(s)]; }
  int count(NmeaSystem s) const noexcept { return count_[index(s)]; }
  /// Used satellites of s (GSA lists the first kGsaSlots of them).
  int used(NmeaSystem s) const noexcept { return used_[index(s)]; }
  /// Used satellites of every system (GNS numSV; GGA caps it at 12).
  int total_used() const noexcept;

private:
  static constexpr std::size_t index(NmeaSystem s) noexcept { return static_cast<std::size_t>(s); }

  std::array<ReportedSv, kMaxSatsInView> sv_{};
  std::array<int, kNumNmeaSystems> first_{};
  std::array<int, kNumNmeaSystems> count_{};
  std::array<int, kNumNmeaSystems> used_{};
  std::array<bool, kNumNmeaSystems> present_{};
};

}  // namespace gnssemu::protocol::nmea
