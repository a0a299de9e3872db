// SPDX-License-Identifier: Apache-2.0
#pragma once
// The GNSS selection of the emulated chip: which systems and signals each
// generation has, the rules an M8 applies to CFG-GNSS (ACK and apply, or NAK
// and keep the old configuration), the enabled set the receiver tracks, what
// MON-GNSS reports, the satellite numbers of NAV-SVINFO, and the navigation
// rate limits that depend on the enabled set. Facts and sources: docs/ubx.md
// §Multi-GNSS (shared/reference/multi-gnss.md §8).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/common/sat_id.hpp"
#include "core/protocol/ubx/config/ubx_generation.hpp"

namespace gnssemu::protocol::ubx {

class DeviceConfig;

/// UBX gnssIds of CFG-GNSS blocks: 0 GPS, 1 SBAS, 2 Galileo, 3 BeiDou, 4 IMES, 5 QZSS, 6 GLONASS.
inline constexpr std::uint8_t kGnssIdImes = 4;
inline constexpr std::uint8_t kMaxCfgGnssId = 6;
inline constexpr std::size_t kNumCfgGnssIds = kMaxCfgGnssId + 1;

/// The system of a UBX gnssId (nothing for IMES and unknown ids).
std::optional<GnssSystem> system_of_gnss_id(std::uint8_t gnss_id) noexcept;
/// GPS, Galileo, BeiDou and GLONASS are the "major" GNSS of CFG-GNSS; SBAS,
/// QZSS and IMES are augmentations (UBX-13003221 CFG-GNSS).
constexpr bool is_major_gnss_id(std::uint8_t gnss_id) noexcept {
  return gnss_id == 0 || gnss_id == 2 || gnss_id == 3 || gnss_id == 6;
}

/// What a generation's GNSS engine has.
struct GnssCapabilities {
  std::uint8_t num_trk_ch_hw;  ///< CFG-GNSS numTrkChHw: tracking channels
  std::uint8_t max_major;      ///< major GNSS enabled at once (MON-GNSS simultaneous)
  std::uint8_t gnss_ids;       ///< bit per gnssId the firmware knows (0..6)
  /// sigCfgMask bits (CFG-GNSS flags bits 16-23) each gnssId has.
  std::array<std::uint8_t, kNumCfgGnssIds> signals;
  SystemSet supported;         ///< systems it can track
  SystemSet defaults;          ///< the factory enabled set
};
const GnssCapabilities& gnss_capabilities(Generation g) noexcept;

/// The factory CFG-GNSS payload of generation g (msgVer 0, one block per
/// gnssId the firmware knows; sources in docs/ubx.md).
std::span<const std::uint8_t> factory_cfg_gnss(Generation g) noexcept;

/// A CFG-GNSS configuration (payload after merging a set into the stored
/// blocks by gnssId) the generation accepts: every enabled block with
/// maxTrkCh in [max(resTrkCh, 1), numTrkChUse] (>= 4 for a major GNSS) and
/// at least one signal, none the generation lacks; Σ resTrkCh of enabled
/// blocks <= numTrkChUse <= numTrkChHw; 1..max_major major GNSS enabled;
/// gnssIds 0..6, and enabled only where the firmware knows the system.
bool cfg_gnss_valid(std::span<const std::uint8_t> payload, Generation g) noexcept;

/// The systems enabled (flag bit 0 with a signal) in a CFG-GNSS payload / a configuration.
SystemSet enabled_systems(std::span<const std::uint8_t> cfg_gnss) noexcept;
SystemSet enabled_systems(const DeviceConfig& c) noexcept;
/// Tracking channels a CFG-GNSS configuration gives: numTrkChUse (0xFF: all
/// of numTrkChHw) in all, and each enabled system's maxTrkCh.
struct ChannelLimits {
  int total = 0;
  std::array<int, kNumSystems> per_system{};  ///< by GnssSystem; 0 for a disabled system
};
ChannelLimits channel_limits(std::span<const std::uint8_t> cfg_gnss, Generation g) noexcept;
ChannelLimits channel_limits(const DeviceConfig& c, Generation g) noexcept;

/// The (gnssId, flags) pairs of two CFG-GNSS payloads agree: nothing the
/// engine tracks changed (channel counts alone do not restart it).
bool same_signals(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) noexcept;

/// MON-GNSS bits (0 GPS, 1 GLONASS, 2 BeiDou, 3 Galileo) of a set.
std::uint8_t mon_gnss_bits(SystemSet s) noexcept;

/// NAV-SVINFO svid of a satellite as an M8 numbers it: GPS 1-32, SBAS
/// 120-158, Galileo 211-246, BeiDou C01-C05 159-163 and C06-C37 33-64,
/// QZSS 193-202, GLONASS 65-96; 0 when it has no number there.
std::uint8_t svinfo_svid(SatId id) noexcept;
/// NAV-SAT / NAV-SIG svId: the system's own number (QZSS 1-10, SBAS PRN 120-158, GLONASS slot).
std::uint8_t ubx_sv_id(SatId id) noexcept;

/// Navigation rate limits the enabled set imposes (receiver-side data).
struct NavRateLimits {
  double max_nav_rate_hz;      ///< highest navigation rate, Hz
  /// Above this rate (Hz) the solution uses at most max_solution_sats satellites.
  double sat_cap_above_hz;
  int max_solution_sats;       ///< kMaxSatsInView: no cap
};
/// ZED-F9P: RTK solutions up to 20 Hz (SparkFun RTK documentation of the
/// ZED-F9P; PX4-GPSDrivers ubx.cpp configures it at 10 Hz, 8 Hz as a
/// moving-baseline base or rover). The emulator runs at most 10 Hz anyway.
inline constexpr double kF9PMaxRtkRateHz = 20.0;
/// M8: 18 Hz with one major GNSS, 10 Hz with more (NEO-M8 data sheet
/// UBX-15031086, "Max navigation update rate"); NEO-M9N: 25 Hz, and at most
/// 16 satellites in the solution above 8 Hz (PX4-GPSDrivers ubx.cpp, which
/// runs the M9N at 8 Hz for that reason).
NavRateLimits nav_rate_limits(Generation g, SystemSet enabled) noexcept;

}  // namespace gnssemu::protocol::ubx
