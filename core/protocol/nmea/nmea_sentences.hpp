// SPDX-License-Identifier: Apache-2.0
#pragma once
// The NMEA sentences the encoder writes: one table, indexed by Sentence, in
// u-blox epoch output order (shared/reference/nmea0183.md §6; GNS before GGA
// and GBS last as real M8 and NEO-M9N epochs have them, docs/nmea.md), with the
// class 0xF0 ids CFG-MSG and $PUBX,40 rate them by (UBX-13003221 §31.1
// "NMEA messages overview").
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gnssemu::protocol::nmea {

enum class Sentence : std::uint8_t { kRmc, kVtg, kGns, kGga, kGsa, kGsv, kGll, kGst, kZda, kGbs };
inline constexpr std::size_t kNumSentences = 10;

/// UBX class of the standard NMEA sentences in CFG-MSG.
inline constexpr std::uint8_t kMsgClass = 0xF0;

struct SentenceInfo {
  Sentence sentence;
  std::string_view name;  ///< formatter, e.g. "GGA"
  std::uint8_t msg_id;    ///< CFG-MSG id in class kMsgClass
};

inline constexpr std::array<SentenceInfo, kNumSentences> kSentences{{
    {Sentence::kRmc, "RMC", 0x04},
    {Sentence::kVtg, "VTG", 0x05},
    {Sentence::kGns, "GNS", 0x0D},
    {Sentence::kGga, "GGA", 0x00},
    {Sentence::kGsa, "GSA", 0x02},
    {Sentence::kGsv, "GSV", 0x03},
    {Sentence::kGll, "GLL", 0x01},
    {Sentence::kGst, "GST", 0x07},
    {Sentence::kZda, "ZDA", 0x08},
    {Sentence::kGbs, "GBS", 0x09},
}};

constexpr const SentenceInfo& info(Sentence s) noexcept { return kSentences[static_cast<std::size_t>(s)]; }

/// Sentence of a formatter name ("GGA", exact case), or nullopt.
constexpr std::optional<Sentence> sentence_by_name(std::string_view name) noexcept {
  for (const SentenceInfo& s : kSentences) {
    if (s.name == name) return s.sentence;
  }
  return std::nullopt;
}

/// Sentence of a class 0xF0 id, or nullopt.
constexpr std::optional<Sentence> sentence_by_msg_id(std::uint8_t msg_id) noexcept {
  for (const SentenceInfo& s : kSentences) {
    if (s.msg_id == msg_id) return s.sentence;
  }
  return std::nullopt;
}

/// A set of sentences (default: empty).
class SentenceSet {
public:
  constexpr SentenceSet() noexcept = default;
  /// What a factory u-blox sends: GGA GLL GSA GSV RMC VTG.
  static constexpr SentenceSet ublox_default() noexcept {
    SentenceSet s;
    for (Sentence x : {Sentence::kGga, Sentence::kGll, Sentence::kGsa, Sentence::kGsv, Sentence::kRmc, Sentence::kVtg}) {
      s.set(x);
    }
    return s;
  }

  constexpr bool has(Sentence s) const noexcept { return (bits_ & bit(s)) != 0; }
  constexpr void set(Sentence s, bool on = true) noexcept {
    bits_ = static_cast<std::uint16_t>(on ? bits_ | bit(s) : bits_ & ~bit(s));
  }
  constexpr bool empty() const noexcept { return bits_ == 0; }
  constexpr bool operator==(const SentenceSet&) const noexcept = default;

private:
  static constexpr unsigned bit(Sentence s) noexcept { return 1U << static_cast<unsigned>(s); }
  std::uint16_t bits_ = 0;
};

}  // namespace gnssemu::protocol::nmea
