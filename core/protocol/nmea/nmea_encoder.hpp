#pragma once
// NMEA 0183 encoder formatted like a u-blox M8 (shared/reference/nmea0183.md).
// One Fix in, one epoch of sentences out; checksums, <= 82 characters.
#include <string>

#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::nmea {

enum class NmeaVersion { k23, k410, k411 };

/// Which sentences an epoch carries (u-blox default set: GGA GLL GSA GSV RMC VTG).
struct SentenceSet {
  bool gga = true, rmc = true, gsa = true, gsv = true, vtg = true, gll = true;
  bool gst = false, zda = false;
};

struct NmeaConfig {
  NmeaVersion version = NmeaVersion::k411;
  SentenceSet sentences;
};

class NmeaEncoder {
public:
  explicit NmeaEncoder(const NmeaConfig& config);

  /// Append one epoch of sentences (CR LF terminated) to out, in u-blox order
  /// (RMC, VTG, GGA, GSA, GSV, GLL, GST, ZDA). Returns bytes appended.
  /// No allocation once out has capacity.
  std::size_t encode_epoch(const receiver::Fix& fix, std::string& out) const;

  const NmeaConfig& config() const noexcept { return config_; }

private:
  NmeaConfig config_;
};

}  // namespace gnssemu::protocol::nmea
