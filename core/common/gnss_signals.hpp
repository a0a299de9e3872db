// SPDX-License-Identifier: Apache-2.0
#pragma once
// The signal table: one row per civil signal a receiver of ours tracks, in
// the style of the system table (gnss_systems.hpp). Band 0 is the L1-band
// signal every receiver tracks; band 1 the second frequency of dual-band
// receivers (the ZED-F9P's default set, IMF9 R02 §3.6). Sources per column
// (shared/reference): carriers multi-gnss.md §1; UBX sigId multi-gnss.md §8;
// RINEX 3 code rtk-raw.md §1.2 (RTKLIB ubx_sig); RTCM MSM signal id
// rtk-raw.md §2.5 (RTKLIB msm_sig_*, pyrtcm rtcmtables.py).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "core/common/sat_id.hpp"

namespace gnssemu {

/// A signal of one system, as the rows of kSignals.
enum class SignalId : uint8_t {
  kGpsL1CA,
  kGpsL2CL,
  kGloL1OF,
  kGloL2OF,
  kGalE1C,
  kGalE5bQ,
  kBdsB1I,
  kBdsB2I,
  kQzsL1CA,
  kQzsL2CL,
  kSbasL1CA,
};
inline constexpr int kNumSignals = 11;

/// Bands a receiver may track per satellite (L1 band, second frequency).
inline constexpr int kNumBands = 2;

struct SignalInfo {
  SignalId id;
  GnssSystem system;
  int band;               ///< 0: L1 band; 1: second frequency
  /// Carrier, Hz; GLONASS: the channel-0 carrier, channel k adds k * step_hz (FDMA).
  double freq_hz;
  double step_hz;
  char rinex_code[3];     ///< RINEX 3 observation code: band digit + attribute ("1C", "2L", "7Q", "2I")
  uint8_t ubx_sig_id;     ///< UBX sigId (RXM-RAWX, NAV-SIG); BeiDou D2 (GEO) adds 1
  uint8_t rtcm_msm_sig;   ///< RTCM 3 MSM signal id (1 = the signal mask's MSB)
  /// Minimum received power of the tracked component at the user antenna,
  /// dBW (docs/models.md "Second frequency": IS-GPS-200 Table 3-Va,
  /// GLONASS ICD 5.1 §3.3.1.6, Galileo OS SIS ICD §2.3.3, BDS ICD B1I/B2I
  /// §4.4.1; a data/pilot pair's pilot carries half of the signal's power).
  double min_power_dbw;
  /// A dataless pilot: its carrier loop is a pure PLL (no Costas half-cycle
  /// ambiguity, whole-cycle slips).
  bool pilot;
};

inline constexpr std::array<SignalInfo, kNumSignals> kSignals{{
    {SignalId::kGpsL1CA, GnssSystem::kGps, 0, 1575.42e6, 0.0, "1C", 0, 2, -158.5, false},
    {SignalId::kGpsL2CL, GnssSystem::kGps, 1, 1227.60e6, 0.0, "2L", 3, 16, -163.0, true},
    {SignalId::kGloL1OF, GnssSystem::kGlonass, 0, 1602.0e6, 0.5625e6, "1C", 0, 2, -161.0, false},
    {SignalId::kGloL2OF, GnssSystem::kGlonass, 1, 1246.0e6, 0.4375e6, "2C", 2, 8, -167.0, false},
    {SignalId::kGalE1C, GnssSystem::kGalileo, 0, 1575.42e6, 0.0, "1C", 0, 2, -160.0, true},
    {SignalId::kGalE5bQ, GnssSystem::kGalileo, 1, 1207.140e6, 0.0, "7Q", 6, 15, -158.0, true},
    {SignalId::kBdsB1I, GnssSystem::kBeiDou, 0, 1561.098e6, 0.0, "2I", 0, 2, -163.0, false},
    {SignalId::kBdsB2I, GnssSystem::kBeiDou, 1, 1207.140e6, 0.0, "7I", 2, 14, -163.0, false},
    {SignalId::kQzsL1CA, GnssSystem::kQzss, 0, 1575.42e6, 0.0, "1C", 0, 2, -158.5, false},
    {SignalId::kQzsL2CL, GnssSystem::kQzss, 1, 1227.60e6, 0.0, "2L", 5, 16, -163.0, true},
    {SignalId::kSbasL1CA, GnssSystem::kSbas, 0, 1575.42e6, 0.0, "1C", 0, 2, -161.0, false},
}};

constexpr const SignalInfo& signal_info(SignalId s) noexcept { return kSignals[static_cast<std::size_t>(s)]; }

/// The signal of system sys on band (0 or 1); nullopt when the system has none
/// there (SBAS has no second frequency).
constexpr std::optional<SignalId> signal_of(GnssSystem sys, int band) noexcept {
  for (const auto& s : kSignals)
    if (s.system == sys && s.band == band) return s.id;
  return std::nullopt;
}

/// Carrier of signal s for a satellite on GLONASS channel k (other systems ignore k), Hz.
constexpr double signal_carrier_hz(SignalId s, int glonass_channel = 0) noexcept {
  return signal_info(s).freq_hz + glonass_channel * signal_info(s).step_hz;
}

/// C/N0 of the second signal of sys over its L1-band signal's at the same
/// antenna, dB (the difference of their minimum received powers); 0 when sys
/// has no second signal.
constexpr double band1_power_offset_db(GnssSystem sys) noexcept {
  const std::optional<SignalId> s0 = signal_of(sys, 0), s1 = signal_of(sys, 1);
  return s0 && s1 ? signal_info(*s1).min_power_dbw - signal_info(*s0).min_power_dbw : 0.0;
}

static_assert(kSignals[static_cast<std::size_t>(SignalId::kSbasL1CA)].id == SignalId::kSbasL1CA);

}  // namespace gnssemu
