// SPDX-License-Identifier: Apache-2.0
#include "core/common/sat_id.hpp"

namespace gnssemu {

std::string_view system_name(GnssSystem s) noexcept {
  switch (s) {
    case GnssSystem::kGps: return "GPS";
    case GnssSystem::kGlonass: return "GLONASS";
    case GnssSystem::kGalileo: return "Galileo";
    case GnssSystem::kBeiDou: return "BeiDou";
    case GnssSystem::kQzss: return "QZSS";
    case GnssSystem::kSbas: return "SBAS";
  }
  return "?";
}

std::array<char, 4> sat_name(SatId id) noexcept {
  const int n = id.number % 100;
  return {system_letter(id.system), static_cast<char>('0' + n / 10), static_cast<char>('0' + n % 10), '\0'};
}

std::optional<SatId> parse_sat(std::string_view text) noexcept {
  if (text.size() < 2 || text.size() > 3) return std::nullopt;
  const auto sys = system_from_letter(text[0]);
  if (!sys) return std::nullopt;
  int n = 0;
  for (std::size_t i = 1; i < text.size(); ++i) {
    const char c = text[i];
    // RINEX 3 writes a blank for a leading zero in some files ("G 5").
    if (c == ' ' && i == 1 && text.size() == 3) continue;
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + (c - '0');
  }
  const SatId id(*sys, n);
  if (!id.valid()) return std::nullopt;
  return id;
}

std::optional<SystemSet> parse_systems(std::string_view letters) noexcept {
  SystemSet set;
  std::size_t i = 0;
  while (i < letters.size()) {
    std::size_t j = letters.find(',', i);
    if (j == std::string_view::npos) j = letters.size();
    std::string_view item = letters.substr(i, j - i);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item.size() != 1) return std::nullopt;
    const auto sys = system_from_letter(item[0]);
    if (!sys || set.has(*sys)) return std::nullopt;
    set = set.with(*sys);
    i = j + 1;
    if (j == letters.size()) break;
    if (i == letters.size()) return std::nullopt;  // trailing comma
  }
  if (set.empty()) return std::nullopt;
  return set;
}

std::array<char, 2 * kNumSystems> systems_text(SystemSet set) noexcept {
  std::array<char, 2 * kNumSystems> out{};
  std::size_t k = 0;
  for (const auto& n : kSatNumbering) {
    if (!set.has(n.system)) continue;
    if (k > 0) out[k++] = ',';
    out[k++] = n.letter;
  }
  return out;
}

}  // namespace gnssemu
