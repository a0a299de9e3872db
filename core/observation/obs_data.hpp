// SPDX-License-Identifier: Apache-2.0
#pragma once
// Contents of a RINEX observation file, every satellite system of the
// SatId table (G R E C J S): header facts a positioning tool needs and the
// epochs with their per-satellite values.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::observation {

/// One observation value (RINEX 3.05 §5.7: F14.3, LLI, signal strength).
struct ObsValue {
  double value = 0.0;  ///< unit of its type: C m, L cycles, D Hz, S dB-Hz (per header)
  bool valid = false;  ///< false: blank or 0.000 (gl_Rinex and others write 0 for untracked)
  int8_t lli = 0;      ///< loss-of-lock indicator 0..9 as written (bit 0: slip, bit 1: half cycle)
  int8_t ssi = 0;      ///< signal strength indicator 0..9, 0 = unknown
};

/// Values of one satellite at one epoch, in the order of its system's
/// types (ObsHeader::types_of(sat.system)).
struct SatObs {
  SatId sat;
  std::vector<ObsValue> values;

  /// Value at a type index (ObsHeader::type_index), or nullptr when the index
  /// is negative or the value is missing.
  const ObsValue* get(int index) const noexcept {
    if (index < 0 || index >= static_cast<int>(values.size())) return nullptr;
    const ObsValue& v = values[static_cast<std::size_t>(index)];
    return v.valid ? &v : nullptr;
  }
};

struct ObsEpoch {
  time::GpsTime t;          ///< receiver time tag, GPS time scale
  int flag = 0;             ///< 0 OK, 1 power failure since the previous epoch
  double rcv_clock_offset_s = 0.0;  ///< from the epoch line (0 if blank)
  int line = 0;             ///< line of the epoch record in the file (messages)
  std::vector<SatObs> sats; ///< satellites of the table's systems, file order
};

struct ObsHeader {
  double rinex_version = 0.0;
  char file_system = ' ';     ///< 'G', 'R', 'E', 'C', 'J', 'S' or 'M' from RINEX VERSION / TYPE
  bool compact = false;       ///< read from Compact RINEX (Hatanaka)
  std::string marker_name;
  std::string receiver_type;
  std::optional<Ecef> approx_pos_m;  ///< APPROX POSITION XYZ, ECEF m
  Enu antenna_delta_hen_m;    ///< ANTENNA: DELTA H/E/N, m (x = H, y = E, z = N as in the file)
  /// Observation types per system (index: GnssSystem) as RINEX 3 codes
  /// ("C1C", "S1C"). RINEX 2 types apply to every system and are mapped per
  /// system (docs/cli.md, "Observation files"); GPS: C1->C1C P1->C1W L1->L1C
  /// D1->D1C S1->S1C, C2->C2X P2->C2W L2->L2W D2->D2W S2->S2W, C5->C5X ...
  std::array<std::vector<std::string>, kNumSystems> types;
  double interval_s = 0.0;    ///< INTERVAL, s (0 if absent)
  std::optional<time::GpsTime> first_obs;
  std::optional<int> leap_seconds;
  bool rcv_clock_offset_applied = false;  ///< RCV CLOCK OFFS APPL

  const std::vector<std::string>& types_of(GnssSystem s) const noexcept {
    return types[static_cast<std::size_t>(s)];
  }
  std::vector<std::string>& types_of(GnssSystem s) noexcept { return types[static_cast<std::size_t>(s)]; }

  /// Index of a type (RINEX 3 code) among system s's types, or -1.
  int type_index(GnssSystem s, std::string_view code) const noexcept {
    const std::vector<std::string>& t = types_of(s);
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] == code) return static_cast<int>(i);
    }
    return -1;
  }
};

struct ObsData {
  std::string source;               ///< file name it was read from
  ObsHeader header;
  std::vector<ObsEpoch> epochs;     ///< flag 0/1 epochs, file order
  int skipped_records = 0;          ///< satellite records of systems outside the SatId table (I, T, ...) skipped
  int event_records = 0;            ///< epoch records with flags 2..5 (their lines skipped)
  int cycle_slip_records = 0;       ///< epoch records with flag 6 (slip lines skipped)
};

}  // namespace gnssemu::observation
