// SPDX-License-Identifier: Apache-2.0
#include "core/observation/rinex_obs.hpp"

#include <cctype>
#include <cstdint>
#include <deque>
#include <optional>
#include <string_view>

#include "core/common/error.hpp"
#include "core/common/line_source.hpp"
#include "core/common/text_fields.hpp"
#include "core/observation/obs_lines.hpp"

namespace gnssemu::observation {

namespace {

constexpr std::size_t kFieldWidth = 16;  // F14.3 + LLI + SSI (RINEX 2.11 Table A2, 3.05 Table A3)
constexpr int kV2SatsPerLine = 12;
constexpr int kV2ValuesPerLine = 5;
// A RINEX 3 observation line is 3 + 16 columns per type (99 types at most);
// 8 GiB decompressed is far beyond a day of 1 Hz multi-GNSS data.
constexpr text::LineLimits kObsLimits{4096, 8ull << 30};

using text::columns;
using text::Line;
using text::trim;

/// RINEX 2 two-character type -> RINEX 3 code of system s (RINEX 3.05
/// §5.1 and Table A23's signals): GPS C1->C1C P1->C1W L1->L1C, C2->C2X
/// P2->C2W L2->L2W, band 5 X; GLONASS C->C, P->P (L/D/S of band 1 C, band 2
/// P); SBAS band 1 C; other systems and bands X.
std::string v3_code_from_v2(GnssSystem s, std::string_view t) {
  if (t.size() != 2) return std::string(t);
  const char kind = t[0], band = t[1];
  if (s == GnssSystem::kGlonass) {
    if (kind == 'P') return std::string{'C', band, 'P'};
    if (band == '1' || band == '2') return std::string{kind, band, kind == 'C' || band == '1' ? 'C' : 'P'};
    return std::string{kind, band, 'X'};
  }
  if (s == GnssSystem::kGps) {
    if (kind == 'P') return band == '1' ? "C1W" : band == '2' ? "C2W" : std::string(t);
    if (band == '1') return std::string{kind, '1', 'C'};
    if (band == '2') return std::string{kind, '2', kind == 'C' ? 'X' : 'W'};
    return std::string{kind, band, 'X'};
  }
  if (kind == 'P') return std::string{'C', band, 'X'};
  if (s == GnssSystem::kSbas && band == '1') return std::string{kind, '1', 'C'};
  return std::string{kind, band, 'X'};
}

/// Reads the file line by line; the lines of the record being parsed stay in
/// window_ (a deque: references survive reading further lines).
class Parser : private text::ColumnReader {
public:
  Parser(ObsLines& src, const std::string& name, bool compact, SystemSet systems)
      : ColumnReader(name), src_(src), compact_(compact), systems_(systems) {}

  ObsData parse() {
    ObsData out;
    out.source = name();
    out.header.compact = compact_;
    parse_header(out);
    for (;;) {
      window_.clear();
      const Line* l = take();
      if (l == nullptr) break;
      if (trim(l->text).empty()) continue;
      if (major_ == 3) {
        epoch_v3(out, *l);
      } else {
        epoch_v2(out, *l);
      }
    }
    return out;
  }

private:
  /// The next line, kept in window_ until the next record; nullptr at the end.
  const Line* take() {
    Line l;
    if (!src_.next(l)) return nullptr;
    ++consumed_;
    window_.push_back(std::move(l));
    return &window_.back();
  }

  /// The next line of a record announced at record_line, or a clear error.
  const Line& need(const char* what, int record_line) {
    const Line* l = take();
    if (l == nullptr) {
      fail(src_.line_number(), std::string("end of file inside ") + what + " started at line " +
                                   std::to_string(record_line));
    }
    return *l;
  }

  // ---- header ----

  void parse_header(ObsData& out) {
    const Line* head = take();
    if (head == nullptr) fail(1, "empty file");
    const text::RinexVersionLine v = text::read_rinex_version_line(*this, *head);
    const Line& first = *head;
    ObsHeader& h = out.header;
    h.rinex_version = v.version;
    const char type = v.type;
    h.file_system = v.system;
    major_ = v.major;
    if (major_ == 2 && h.file_system == ' ') h.file_system = 'G';  // RINEX 2.11 §5.1: blank = GPS
    if (type != 'O') fail(first.number, std::string("not an observation file (type '") + type + "')");
    if (h.file_system != 'M' && !system_from_letter(h.file_system)) {
      fail(first.number, std::string("observation file for system '") + h.file_system +
                             "', need one of G R E C J S or mixed (M)");
    }
    for (;;) {
      window_.clear();
      const Line* next = take();
      if (next == nullptr) break;
      const Line& l = *next;
      const std::string label = text::rinex_label(l.text);
      if (label == "END OF HEADER") {
        if (!have_types_) fail(l.number, "no observation types in the header (SYS / # / OBS TYPES or # / TYPES OF OBSERV)");
        return;
      }
      header_line(l, label, h);
    }
    fail(src_.line_number(), "end of file before END OF HEADER");
  }

  /// One header line; also used for header records inside flag-4 events.
  void header_line(const Line& l, const std::string& label, ObsHeader& h) {
    if (label == "MARKER NAME") {
      h.marker_name = std::string(trim(columns(l.text, 0, 60)));
    } else if (label == "REC # / TYPE / VERS") {
      h.receiver_type = std::string(trim(columns(l.text, 20, 20)));
    } else if (label == "APPROX POSITION XYZ") {
      h.approx_pos_m = Ecef(real(l, 0, 14, "X"), real(l, 14, 14, "Y"), real(l, 28, 14, "Z"));
    } else if (label == "ANTENNA: DELTA H/E/N") {
      h.antenna_delta_hen_m = Enu(real(l, 0, 14, "H"), real(l, 14, 14, "E"), real(l, 28, 14, "N"));
    } else if (label == "INTERVAL") {
      h.interval_s = real(l, 0, 10, "interval");
      if (h.interval_s < 0.0) fail(l.number, "negative INTERVAL");
    } else if (label == "LEAP SECONDS") {
      h.leap_seconds = integer(l, 0, 6, "leap seconds");
    } else if (label == "RCV CLOCK OFFS APPL") {
      h.rcv_clock_offset_applied = integer(l, 0, 6, "RCV CLOCK OFFS APPL") != 0;
    } else if (label == "TIME OF FIRST OBS") {
      const std::string_view sys = trim(columns(l.text, 48, 3));
      if (!sys.empty() && sys != "GPS") {
        fail(l.number, "time system '" + std::string(sys) + "' not supported (GPS time only)");
      }
      time::CalendarTime c;
      c.year = integer(l, 0, 6, "year");
      c.month = integer(l, 6, 6, "month");
      c.day = integer(l, 12, 6, "day");
      c.hour = integer(l, 18, 6, "hour");
      c.minute = integer(l, 24, 6, "minute");
      c.second = real(l, 30, 13, "second");
      h.first_obs = calendar_time(l, c);
    } else if (major_ == 3 && label == "SYS / # / OBS TYPES") {
      types_v3(l, h);
    } else if (major_ == 2 && label == "# / TYPES OF OBSERV") {
      types_v2(l, h);
    }
  }

  time::GpsTime calendar_time(const Line& l, const time::CalendarTime& c) const {
    if (c.year < 1980 || c.year > 2200 || c.month < 1 || c.month > 12 || c.day < 1 || c.day > 31 || c.hour < 0 ||
        c.hour > 23 || c.minute < 0 || c.minute > 59 || !(c.second >= 0.0 && c.second < 61.0)) {
      fail(l.number, "date/time out of range");
    }
    return time::GpsTime::from_calendar(c);
  }

  /// Where a header record lists observation types: the count, then codes
  /// in fixed columns, per_line to a line; continuation lines repeat label.
  struct TypesLayout {
    const char* label;
    std::size_t count_col, count_width;
    int per_line;
    std::size_t first_col, step, width;  ///< column of the first code, spacing, code width
  };
  static constexpr TypesLayout kTypesV3{"SYS / # / OBS TYPES", 3, 3, 13, 7, 4, 3};  // RINEX 3.05 Table A2
  static constexpr TypesLayout kTypesV2{"# / TYPES OF OBSERV", 0, 6, 9, 10, 6, 2};   // RINEX 2.11 Table A1

  std::vector<std::string> type_codes(const Line& l, const TypesLayout& t) {
    const int n = integer(l, t.count_col, t.count_width, "number of observation types");
    if (n < 1 || n > 99) fail(l.number, "number of observation types " + std::to_string(n) + " outside 1..99");
    std::vector<std::string> codes;
    const Line* cur = &l;
    for (int k = 0; k < n; ++k) {
      const int slot = k % t.per_line;
      if (k > 0 && slot == 0) {
        cur = &need(t.label, l.number);
        if (text::rinex_label(cur->text) != t.label) fail(cur->number, std::string("missing continuation of ") + t.label);
      }
      const std::string_view code = trim(columns(cur->text, t.first_col + t.step * static_cast<std::size_t>(slot), t.width));
      if (code.size() != t.width) {
        fail(cur->number, "observation type " + std::to_string(k + 1) + " is not a " + std::to_string(t.width) +
                              "-character code");
      }
      codes.emplace_back(code);
    }
    return codes;
  }

  /// Systems outside the SatId table (I) keep no types: their records are skipped.
  void types_v3(const Line& l, ObsHeader& h) {
    const char sys = l.text[0];
    std::vector<std::string> codes = type_codes(l, kTypesV3);
    if (const std::optional<GnssSystem> s = system_from_letter(sys)) {
      h.types_of(*s) = std::move(codes);
      have_types_ = true;
    } else if (sys < 'A' || sys > 'Z') {
      fail(l.number, std::string("SYS / # / OBS TYPES for satellite system '") + sys + "'");
    }
  }

  void types_v2(const Line& l, ObsHeader& h) {
    const std::vector<std::string> codes = type_codes(l, kTypesV2);
    for (int i = 0; i < kNumSystems; ++i) {
      const auto s = static_cast<GnssSystem>(i);
      h.types_of(s).clear();
      for (const std::string& code : codes) h.types_of(s).push_back(v3_code_from_v2(s, code));
    }
    have_types_ = true;
  }

  // ---- records ----

  /// Skip or apply the n special records of an event epoch (flags 2..5).
  void event_records(ObsData& out, int n, int flag, int record_line) {
    ++out.event_records;
    for (int k = 0; k < n; ++k) {
      const Line& l = need("event record", record_line);
      if (flag == 4) {  // header information follows (RINEX 3.05 §5.3.2): keep types current
        const std::string label = text::rinex_label(l.text);
        if (label.empty()) fail(l.number, "event flag 4: header record without a label");
        const uint64_t before = consumed_;
        header_line(l, label, out.header);
        k += static_cast<int>(consumed_ - before);  // continuation lines consumed
      }
    }
  }

  ObsValue value(const Line& l, std::size_t col) const {
    ObsValue v;
    v.value = real(l, col, 14, "observation");
    v.valid = v.value != 0.0;
    v.lli = indicator(l, col + 14, "LLI");
    v.ssi = indicator(l, col + 15, "signal strength");
    if (!v.valid) v.lli = v.ssi = 0;
    return v;
  }

  int8_t indicator(const Line& l, std::size_t col, const char* what) const {
    if (col >= l.text.size()) return 0;
    const char c = l.text[col];
    if (c == ' ') return 0;
    if (c < '0' || c > '9') fail(l.number, std::string("bad ") + what + " '" + c + "' at column " + std::to_string(col + 1));
    return static_cast<int8_t>(c - '0');
  }

  int prn_of(const Line& l, std::size_t col) const {
    const int prn = integer(l, col + 1, 2, "satellite number");
    if (prn < 1 || prn > 99) fail(l.number, "satellite number " + std::to_string(prn) + " out of range");
    return prn;
  }

  /// The satellite of system letter sys and RINEX number n; nullopt for a
  /// system outside the table (skipped, counted); errors for anything else.
  std::optional<SatId> sat_of(const Line& l, char sys, int n, const ObsHeader& h) const {
    const std::optional<GnssSystem> s = system_from_letter(sys);
    if (!s) {
      if (sys < 'A' || sys > 'Z') fail(l.number, std::string("unknown satellite system '") + sys + "'");
      return std::nullopt;
    }
    const SatId id(*s, n);
    if (!id.valid()) {
      fail(l.number, std::string("satellite ") + sys + std::to_string(n) + " out of the system's range " +
                         std::to_string(numbering(*s).first) + ".." + std::to_string(numbering(*s).last));
    }
    if (h.types_of(*s).empty()) fail(l.number, std::string("no observation types for system '") + sys + "'");
    return id;
  }

  struct EpochFlag {
    int flag = 0;  ///< 0, 1 or 6 (events are consumed)
    int n = 0;     ///< satellites announced
  };

  /// Epoch flag (column flag_col, 0-based) and satellite count (the next 3
  /// columns) of epoch record e. An event epoch (flags 2..5) has its special
  /// records consumed and gives nullopt.
  std::optional<EpochFlag> epoch_flag(ObsData& out, const Line& e, std::size_t flag_col) {
    const int flag = integer(e, flag_col, 1, "epoch flag");
    const int n = integer(e, flag_col + 1, 3, "number of satellites");
    if (flag < 0 || flag > 6) fail(e.number, "epoch flag " + std::to_string(flag) + " outside 0..6");
    if (n < 0) fail(e.number, "negative number of satellites");
    if (flag >= 2 && flag <= 5) {
      event_records(out, n, flag, e.number);
      return std::nullopt;
    }
    return EpochFlag{flag, n};
  }

  void epoch_v3(ObsData& out, const Line& e) {
    if (e.text[0] != '>') fail(e.number, "expected an epoch record starting with '>'");
    const std::optional<EpochFlag> head = epoch_flag(out, e, 31);
    if (!head) return;
    const auto [flag, n] = *head;
    if (flag == 6) {  // cycle-slip records: same layout as observations, not observations
      ++out.cycle_slip_records;
      for (int k = 0; k < n; ++k) need("cycle-slip record", e.number);
      return;
    }
    ObsEpoch ep = epoch_head(e, 2, 4, 7, 10, 13, 16, 18);
    ep.flag = flag;
    ep.rcv_clock_offset_s = real(e, 41, 15, "receiver clock offset");
    ep.sats.reserve(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const Line& l = need("epoch record", e.number);
      const char sys = l.text.empty() ? ' ' : l.text[0];
      if (sys == '>') fail(l.number, "epoch record at line " + std::to_string(e.number) + " announced " +
                                         std::to_string(n) + " satellites, found " + std::to_string(k));
      const std::optional<SatId> id = sat_of(l, sys, prn_of(l, 0), out.header);
      if (!id) {
        ++out.skipped_records;
        continue;
      }
      if (!systems_.has(id->system)) continue;
      const std::size_t ntypes = out.header.types_of(id->system).size();
      SatObs s;
      s.sat = *id;
      s.values.reserve(ntypes);
      for (std::size_t t = 0; t < ntypes; ++t) s.values.push_back(value(l, 3 + kFieldWidth * t));
      ep.sats.push_back(std::move(s));
    }
    out.epochs.push_back(std::move(ep));
  }

  /// Epoch time from fixed columns (year width 4 at year_col; v2 passes a 2-digit year).
  ObsEpoch epoch_head(const Line& e, std::size_t year_col, std::size_t year_w, std::size_t month_col,
                      std::size_t day_col, std::size_t hour_col, std::size_t minute_col, std::size_t second_col) const {
    time::CalendarTime c;
    c.year = integer(e, year_col, year_w, "year");
    if (year_w == 2) c.year = time::year_from_two_digits(c.year);
    c.month = integer(e, month_col, 2, "month");
    c.day = integer(e, day_col, 2, "day");
    c.hour = integer(e, hour_col, 2, "hour");
    c.minute = integer(e, minute_col, 2, "minute");
    c.second = real(e, second_col, 11, "second");
    ObsEpoch ep;
    ep.t = calendar_time(e, c);
    ep.line = e.number;
    return ep;
  }

  void epoch_v2(ObsData& out, const Line& e) {
    const std::optional<EpochFlag> head = epoch_flag(out, e, 28);
    if (!head) return;
    const auto [flag, n] = *head;
    // Satellite list: 12 per line, continuation lines from column 33.
    std::vector<std::pair<char, int>> sats;
    const Line* cur = &e;
    for (int k = 0; k < n; ++k) {
      if (k > 0 && k % kV2SatsPerLine == 0) cur = &need("satellite list", e.number);
      const std::size_t col = 32 + 3 * static_cast<std::size_t>(k % kV2SatsPerLine);
      if (col >= cur->text.size()) {
        fail(cur->number, "satellite list shorter than the " + std::to_string(n) + " announced");
      }
      const char sys = cur->text[col];
      // RINEX 2.11 §5.1: blank is GPS (or the system of a single-system file).
      sats.emplace_back(sys != ' ' ? sys : out.header.file_system == 'M' ? 'G' : out.header.file_system,
                        prn_of(*cur, col));
    }
    const std::size_t ntypes = out.header.types_of(GnssSystem::kGps).size();  // the same for every system
    const std::size_t lines_per_sat = (ntypes + kV2ValuesPerLine - 1) / kV2ValuesPerLine;
    if (flag == 6) {
      ++out.cycle_slip_records;
      for (std::size_t k = 0; k < sats.size() * lines_per_sat; ++k) need("cycle-slip record", e.number);
      return;
    }
    ObsEpoch ep = epoch_head(e, 1, 2, 4, 7, 10, 13, 15);
    ep.flag = flag;
    ep.rcv_clock_offset_s = real(e, 68, 12, "receiver clock offset");
    for (const auto& [sys, prn] : sats) {
      const std::optional<SatId> id = sat_of(e, sys, prn, out.header);
      if (!id || !systems_.has(id->system)) {
        if (!id) ++out.skipped_records;
        for (std::size_t k = 0; k < lines_per_sat; ++k) need("observation record", e.number);
        continue;
      }
      SatObs s;
      s.sat = *id;
      s.values.reserve(ntypes);
      for (std::size_t t = 0; t < ntypes; ++t) {
        if (t % kV2ValuesPerLine == 0) cur = &need("observation record", e.number);
        if (cur->text.size() > 0 && cur->text[0] != ' ' && !std::isdigit(static_cast<unsigned char>(cur->text[0])) &&
            cur->text[0] != '-') {
          fail(cur->number, "expected observation values, found '" + cur->text.substr(0, 20) + "'");
        }
        s.values.push_back(value(*cur, kFieldWidth * (t % kV2ValuesPerLine)));
      }
      ep.sats.push_back(std::move(s));
    }
    out.epochs.push_back(std::move(ep));
  }

  ObsLines& src_;
  bool compact_ = false;
  SystemSet systems_;
  std::deque<Line> window_;
  uint64_t consumed_ = 0;  // lines taken so far
  int major_ = 0;
  bool have_types_ = false;
};


ObsData read_rinex_obs(text::LineSource& src, SystemSet systems) {
  const std::unique_ptr<ObsLines> lines = open_obs_lines(src, systems);
  return Parser(*lines, src.name(), lines->compact(), systems).parse();
}

}  // namespace

ObsData read_rinex_obs(std::istream& in, const std::string& name, SystemSet systems) {
  text::LineSource src(in, name, kObsLimits);
  return read_rinex_obs(src, systems);
}

ObsData read_rinex_obs(const std::string& path, SystemSet systems) {
  text::LineSource src(path, kObsLimits);
  return read_rinex_obs(src, systems);
}

}  // namespace gnssemu::observation
