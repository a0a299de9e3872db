// SPDX-License-Identifier: Apache-2.0
#pragma once
// Satellite identity: one SatId {system, number} for every layer, numbered as
// RINEX 3 numbers satellites (G05, R12, E30, C19, J02 = QZSS PRN 194, S23 =
// SBAS PRN 123), and a dense index over every satellite of every system for
// per-satellite arrays. Ranges follow RTKLIB's MAXPRN* and satid2no
// (shared/reference/multi-gnss.md §1): what a system's row admits, not what
// is in orbit today.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gnssemu {

/// Satellite systems, in RINEX letter order of the system table below.
enum class GnssSystem : uint8_t { kGps, kGlonass, kGalileo, kBeiDou, kQzss, kSbas };
inline constexpr int kNumSystems = 6;

/// RINEX numbering of one system: numbers first..last are valid; the
/// system's own PRN is number + prn_offset (QZSS J01 = PRN 193, SBAS S20 =
/// PRN 120; GLONASS numbers are orbit slots).
struct SatNumbering {
  GnssSystem system;
  char letter;           ///< RINEX 3 system letter
  int first;             ///< lowest RINEX number
  int last;              ///< highest RINEX number
  int prn_offset;        ///< PRN = number + prn_offset
};

inline constexpr std::array<SatNumbering, kNumSystems> kSatNumbering{{
    {GnssSystem::kGps, 'G', 1, 32, 0},
    {GnssSystem::kGlonass, 'R', 1, 27, 0},
    {GnssSystem::kGalileo, 'E', 1, 36, 0},
    {GnssSystem::kBeiDou, 'C', 1, 63, 0},
    {GnssSystem::kQzss, 'J', 1, 10, 192},
    {GnssSystem::kSbas, 'S', 20, 58, 100},
}};

constexpr const SatNumbering& numbering(GnssSystem s) noexcept { return kSatNumbering[static_cast<std::size_t>(s)]; }
constexpr int system_size(GnssSystem s) noexcept { return numbering(s).last - numbering(s).first + 1; }
/// Dense index of the first satellite of system s.
constexpr int system_base(GnssSystem s) noexcept {
  int base = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(s); ++i) base += kSatNumbering[i].last - kSatNumbering[i].first + 1;
  return base;
}
/// Every satellite of every system: the size of per-satellite arrays.
inline constexpr int kNumSats = system_base(GnssSystem::kSbas) + system_size(GnssSystem::kSbas);

/// Most satellites one antenna can have above its horizon at once, every
/// system together (about 75 with every current constellation at the best
/// place on Earth: half of each system's orbiting satellites plus GEOs):
/// the size of per-epoch lists of satellites in view.
inline constexpr int kMaxSatsInView = 96;

/// RINEX letter of a system ('G', 'R', 'E', 'C', 'J', 'S').
constexpr char system_letter(GnssSystem s) noexcept { return numbering(s).letter; }
/// The system of a RINEX letter; nullopt for a letter not in the table (I, L, ...).
constexpr std::optional<GnssSystem> system_from_letter(char c) noexcept {
  for (const auto& n : kSatNumbering)
    if (n.letter == c) return n.system;
  return std::nullopt;
}
/// "GPS", "GLONASS", "Galileo", "BeiDou", "QZSS", "SBAS".
std::string_view system_name(GnssSystem s) noexcept;

/// One satellite. Default: G01's system with number 0 (not valid()).
struct SatId {
  GnssSystem system = GnssSystem::kGps;
  uint8_t number = 0;  ///< RINEX number within the system

  constexpr SatId() = default;
  constexpr SatId(GnssSystem s, int n) noexcept : system(s), number(static_cast<uint8_t>(n)) {}

  /// The number lies in its system's range.
  constexpr bool valid() const noexcept {
    const auto& n = numbering(system);
    return number >= n.first && number <= n.last;
  }
  /// The system's own PRN (QZSS 193..202, SBAS 120..158; GLONASS: slot).
  constexpr int prn() const noexcept { return number + numbering(system).prn_offset; }
  /// Dense index in [0, kNumSats); only for valid() ids.
  constexpr int index() const noexcept { return system_base(system) + number - numbering(system).first; }
  /// The id with dense index i in [0, kNumSats).
  static constexpr SatId from_index(int i) noexcept {
    for (const auto& n : kSatNumbering) {
      const int size = n.last - n.first + 1;
      if (i < size) return SatId(n.system, n.first + i);
      i -= size;
    }
    return SatId();
  }
  /// From a system and its own PRN (QZSS 193..202, SBAS 120..158); nullopt out of range.
  static constexpr std::optional<SatId> from_prn(GnssSystem s, int prn) noexcept {
    const SatId id(s, prn - numbering(s).prn_offset);
    if (prn - numbering(s).prn_offset < 0 || prn - numbering(s).prn_offset > 255 || !id.valid()) return std::nullopt;
    return id;
  }
  static constexpr SatId gps(int prn) noexcept { return SatId(GnssSystem::kGps, prn); }

  constexpr bool operator==(const SatId&) const = default;
  /// Systems in table order, then number (the order of index()).
  constexpr auto operator<=>(const SatId& o) const noexcept {
    if (system != o.system) return static_cast<int>(system) <=> static_cast<int>(o.system);
    return static_cast<int>(number) <=> static_cast<int>(o.number);
  }
};

/// "G05", "R12", "S23": three characters, RINEX 3 style.
std::array<char, 4> sat_name(SatId id) noexcept;
/// Parses "G05", "G5", "R12", "J02", "S23" (letter, 1-2 digits); nullopt when
/// malformed or out of the system's range.
std::optional<SatId> parse_sat(std::string_view text) noexcept;

/// A set of systems (bit per GnssSystem).
class SystemSet {
public:
  constexpr SystemSet() = default;
  constexpr explicit SystemSet(uint8_t bits) noexcept : bits_(bits) {}
  static constexpr SystemSet all() noexcept { return SystemSet((1u << kNumSystems) - 1u); }
  static constexpr SystemSet only(GnssSystem s) noexcept { return SystemSet().with(s); }
  constexpr bool has(GnssSystem s) const noexcept { return (bits_ >> static_cast<int>(s)) & 1u; }
  constexpr SystemSet with(GnssSystem s) const noexcept { return SystemSet(static_cast<uint8_t>(bits_ | (1u << static_cast<int>(s)))); }
  constexpr SystemSet without(GnssSystem s) const noexcept { return SystemSet(static_cast<uint8_t>(bits_ & ~(1u << static_cast<int>(s)))); }
  /// The systems in both sets; in this one and not in o.
  constexpr SystemSet intersect(SystemSet o) const noexcept { return SystemSet(static_cast<uint8_t>(bits_ & o.bits_)); }
  constexpr SystemSet unite(SystemSet o) const noexcept { return SystemSet(static_cast<uint8_t>(bits_ | o.bits_)); }
  constexpr SystemSet minus(SystemSet o) const noexcept { return SystemSet(static_cast<uint8_t>(bits_ & ~o.bits_)); }
  constexpr bool empty() const noexcept { return bits_ == 0; }
  constexpr int count() const noexcept {
    int n = 0;
    for (int i = 0; i < kNumSystems; ++i) n += (bits_ >> i) & 1u;
    return n;
  }
  constexpr uint8_t bits() const noexcept { return bits_; }
  constexpr bool operator==(const SystemSet&) const = default;

private:
  uint8_t bits_ = 0;
};

/// "G,R,E" (RINEX letters, comma-separated) -> set; nullopt with an unknown
/// or repeated letter or an empty list.
std::optional<SystemSet> parse_systems(std::string_view letters) noexcept;
/// The set as "G,R,E" in table order.
std::array<char, 2 * kNumSystems> systems_text(SystemSet set) noexcept;

}  // namespace gnssemu
