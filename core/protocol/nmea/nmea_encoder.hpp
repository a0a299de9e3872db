// SPDX-License-Identifier: Apache-2.0
#pragma once
// NMEA 0183 encoder formatted like a u-blox M8 / NEO-M9N
// (shared/reference/nmea0183.md, multi-gnss.md §7). One Fix in, one epoch
// of sentences out; checksums, <= 82 characters. Talkers, satellite numbers,
// GSA per system and GSV per talker follow the NmeaSettings (CFG-NMEA).
// Choices where u-blox is not documented are listed in docs/nmea.md.
#include <cstddef>
#include <string>

#include "core/protocol/nmea/nmea_sentences.hpp"
#include "core/protocol/nmea/nmea_settings.hpp"
#include "core/protocol/nmea/reported_fix.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::nmea {

/// The encoder's configuration: the CFG-NMEA settings (base), the sentence
/// set and the course blanking. Defaults: NmeaSettings{} (GPS at 4.11 with
/// the M9's signal ids), u-blox's factory sentence set.
struct NmeaConfig : NmeaSettings {
  SentenceSet sentences = SentenceSet::ublox_default();  ///< what encode_epoch(fix, out) writes
  /// Below this horizontal speed (m/s) the course fields of RMC and VTG are
  /// left empty, as u-blox does when its heading is not valid. Static u-blox
  /// logs show an empty course at up to 0.30 m/s; 0 always prints it.
  double course_min_speed_m_s = 0.5;
};

/// Largest epoch encode_epoch can produce, each sentence at most 82 bytes:
/// RMC VTG GNS GGA GLL GST ZDA GBS, a GSA per NMEA system (5) and the GSV
/// of kMaxSatsInView satellites in at most 5 talker groups (96 / 4 + 5).
/// Reserve this much to never allocate.
inline constexpr std::size_t kMaxEpochBytes = (8 + 5 + kMaxSatsInView / 4 + 5) * 82;

/// Told where each sentence an encoder appends ends, so a caller can treat
/// every sentence as a message of its own (a transmit budget drops whole
/// sentences) without scanning the bytes again.
class SentenceSink {
public:
  /// sentence ends at offset end of the output string (exclusive).
  virtual void on_sentence(Sentence sentence, std::size_t end) noexcept = 0;

protected:
  ~SentenceSink() = default;
};

class NmeaEncoder {
public:
  /// Throws gnssemu::Error for a negative or non-finite course_min_speed_m_s.
  explicit NmeaEncoder(const NmeaConfig& config);

  /// Append one epoch of the config's sentences (CR LF terminated) to out,
  /// in u-blox order (RMC, VTG, GNS, GGA, GSA, GSV, GLL, GST, ZDA, GBS). Returns bytes
  /// appended. No allocation once out has capacity (out.size() +
  /// kMaxEpochBytes). Never throws; non-finite inputs give empty fields, a
  /// fix with a non-finite position or without valid time is sent as no fix.
  std::size_t encode_epoch(const receiver::Fix& fix, std::string& out) const;
  /// The same for the sentences in set (instead of the config's); sink, if
  /// not null, hears the end of every sentence (GSV: each of its parts).
  /// reported: the fix type GGA quality, GSA navMode and the RMC/GLL status
  /// and posMode report instead of the Fix's (nothing: the Fix's).
  std::size_t encode_epoch(const receiver::Fix& fix, SentenceSet set, std::string& out,
                           SentenceSink* sink = nullptr, FixOverride reported = std::nullopt) const;

  const NmeaConfig& config() const noexcept { return config_; }
  /// Takes new CFG-NMEA settings (and enabled systems) from the next epoch on.
  void set_settings(const NmeaSettings& settings) noexcept { static_cast<NmeaSettings&>(config_) = settings; }

private:
  NmeaConfig config_;
};

}  // namespace gnssemu::protocol::nmea
