// SPDX-License-Identifier: Apache-2.0
#include "core/observation/crinex_decoder.hpp"

#include <cctype>
#include <string_view>
#include <utility>

#include "core/common/error.hpp"
#include "core/common/text_fields.hpp"

namespace gnssemu::observation {

namespace {

using text::Line;

constexpr std::size_t kSatsPerV2Line = 12;    // RINEX 2.11 Table A2: satellite list
constexpr std::size_t kValuesPerV2Line = 5;   // RINEX 2.11 Table A2: observations
constexpr std::size_t kV3ListCol = 41;        // CRINEX 3: list after the epoch line's 41 columns
constexpr std::size_t kV2ListCol = 32;        // CRINEX 1: list from column 33, on one line
constexpr int kNumbersPerSystem = 100;

/// Text difference (Hatanaka 2008 §3): a blank keeps the old character, '&'
/// writes a blank, any other character replaces the old one.
void apply_text_difference(std::string& old, std::string_view diff) {
  if (diff.size() > old.size()) old.resize(diff.size(), ' ');
  for (std::size_t i = 0; i < diff.size(); ++i) {
    const char c = diff[i];
    if (c == ' ') continue;
    old[i] = c == '&' ? ' ' : c;
  }
}

/// v / 10^decimals right-aligned in width columns (Fortran Fw.d); false when
/// it does not fit.
bool append_fixed(std::string& out, int64_t v, int decimals, std::size_t width) {
  char buf[32];
  std::size_t n = 0;
  const bool neg = v < 0;
  uint64_t u = neg ? 0u - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
  for (int k = 0; k < decimals; ++k) {
    buf[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  }
  buf[n++] = '.';
  do {
    buf[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u != 0);
  if (neg) buf[n++] = '-';
  if (n > width) return false;
  out.append(width - n, ' ');
  while (n > 0) out.push_back(buf[--n]);
  return true;
}

}  // namespace

bool is_compact_rinex(std::string_view first_line) { return text::rinex_label(first_line) == "CRINEX VERS   / TYPE"; }

CompactRinexDecoder::CompactRinexDecoder(text::LineSource& src, text::Line first, SystemSet systems)
    : src_(src), systems_(systems), sats_(static_cast<std::size_t>(26 * kNumbersPerSystem)) {
  const std::string_view v = text::trim(text::columns(first.text, 0, 20));
  if (!is_compact_rinex(first.text)) fail(first.number, "not a Compact RINEX file (no CRINEX VERS / TYPE)");
  if (v == "1.0") {
    version_ = 1;
  } else if (v == "3.0") {
    version_ = 3;
  } else {
    fail(first.number, "Compact RINEX version '" + std::string(v) + "' not supported (1.0 or 3.0)");
  }
  Line prog;
  need(prog, "Compact RINEX header", first.number);
  if (text::rinex_label(prog.text) != "CRINEX PROG / DATE") {
    fail(prog.number, "expected CRINEX PROG / DATE as the second line");
  }
}

void CompactRinexDecoder::fail(int line, const std::string& what) const { throw Error(src_.name(), line, what); }

bool CompactRinexDecoder::take(Line& l) { return src_.next(l); }

void CompactRinexDecoder::need(Line& l, const char* what, int record_line) {
  if (!src_.next(l)) {
    fail(src_.line_number(), std::string("end of file inside ") + what + " started at line " +
                                 std::to_string(record_line) + " (truncated)");
  }
}

void CompactRinexDecoder::emit(std::string text, int number) {
  out_.push_back(Line{std::move(text), number});
}

bool CompactRinexDecoder::next(Line& line) {
  while (out_pos_ >= out_.size()) {
    out_.clear();
    out_pos_ = 0;
    Line l;
    if (!take(l)) {
      if (in_header_) fail(src_.line_number(), "end of file before END OF HEADER");
      return false;
    }
    if (in_header_) {
      header_line(l);
      emit(std::move(l.text), l.number);
    } else {
      decode_epoch(l);
    }
  }
  line = std::move(out_[out_pos_++]);
  return true;
}

/// A header line (or a header record of a flag-4 event): the version must
/// match CRINEX's, and the type counts lay out the data lines.
void CompactRinexDecoder::header_line(const Line& l) {
  const std::string label = text::rinex_label(l.text);
  if (in_header_ && header_lines_++ == 0) {
    if (label != "RINEX VERSION / TYPE") fail(l.number, "expected RINEX VERSION / TYPE after the Compact RINEX lines");
    const std::string_view v = text::trim(text::columns(l.text, 0, 9));
    const int major = v.empty() ? 0 : v[0] - '0';
    if ((version_ == 1 && major != 2) || (version_ == 3 && major != 3)) {
      fail(l.number, "Compact RINEX " + std::string(version_ == 1 ? "1.0" : "3.0") + " holds RINEX " +
                         (version_ == 1 ? "2" : "3") + ", not version '" + std::string(v) + "'");
    }
    // RINEX 2.11 §5.1: a blank satellite letter is GPS, or the file's one system.
    const char file_system = l.text.size() > 40 ? l.text[40] : ' ';
    blank_system_ = file_system == ' ' || file_system == 'M' ? 'G' : file_system;
  }
  if (label == "END OF HEADER") {
    in_header_ = false;
  } else if (label == "SYS / # / OBS TYPES" && l.text[0] != ' ') {
    const char sys = l.text[0];
    const std::optional<int> n = text::parse_int(text::columns(l.text, 3, 3));
    if (sys < 'A' || sys > 'Z' || !n || *n < 1 || *n > 99) fail(l.number, "bad SYS / # / OBS TYPES record");
    ntypes_[static_cast<std::size_t>(sys - 'A')] = *n;
  } else if (label == "# / TYPES OF OBSERV" && !text::trim(text::columns(l.text, 0, 6)).empty()) {
    const std::optional<int> n = text::parse_int(text::columns(l.text, 0, 6));
    if (!n || *n < 1 || *n > 99) fail(l.number, "bad # / TYPES OF OBSERV record");
    ntypes_v2_ = *n;
  }
}

int CompactRinexDecoder::types_of(char system, const Line& l) const {
  const int n = version_ == 1                    ? ntypes_v2_
                : system >= 'A' && system <= 'Z' ? ntypes_[static_cast<std::size_t>(system - 'A')]
                                                 : 0;
  if (n == 0) fail(l.number, std::string("satellite of system '") + system + "' without observation types in the header");
  return n;
}

/// The value of one field: "" no value (ends the arc), "n&v" a new arc of
/// order n from v, otherwise the arc's next n-th difference.
int64_t CompactRinexDecoder::arc_value(Arc& arc, std::string_view f, const Line& l, std::size_t col) const {
  const auto bad = [&](const std::string& why) {
    fail(l.number, why + " in field '" + std::string(f) + "' at column " + std::to_string(col + 1));
  };
  const std::size_t amp = f.find('&');
  std::string_view digits = f;
  if (amp != std::string_view::npos) {
    const std::string_view order = f.substr(0, amp);
    if (order.size() != 1 || order[0] < '1' || order[0] > '0' + kMaxOrder) {
      bad("arc order '" + std::string(order) + "' out of range 1.." + std::to_string(kMaxOrder));
    }
    arc.order = order[0] - '0';
    arc.level = 0;
    digits = f.substr(amp + 1);
  } else if (arc.order == 0) {
    bad("a difference with no arc to continue (a new arc starts with n&)");
  }
  const bool neg = !digits.empty() && digits[0] == '-';
  if (neg) digits.remove_prefix(1);
  if (digits.empty() || digits.size() > 18) bad("not a number");
  int64_t x = 0;
  for (const char c : digits) {
    if (c < '0' || c > '9') bad("not a number");
    x = x * 10 + (c - '0');
  }
  if (neg) x = -x;
  if (amp != std::string_view::npos) {
    arc.d[0] = x;
    return x;
  }
  if (arc.level < arc.order) ++arc.level;
  arc.d[static_cast<std::size_t>(arc.level)] = x;
  for (int k = arc.level - 1; k >= 0; --k) {
    const auto i = static_cast<std::size_t>(k);
    if (__builtin_add_overflow(arc.d[i], arc.d[i + 1], &arc.d[i])) bad("differences overflow");
  }
  return arc.d[0];
}

void CompactRinexDecoder::event(const Line& e, int flag, int n) {
  emit(epoch_, e.number);
  for (int k = 0; k < n; ++k) {
    Line r;
    need(r, "event record", e.number);
    if (flag == 4) header_line(r);  // header records: new type lists apply from here
    emit(std::move(r.text), r.number);
  }
}

void CompactRinexDecoder::decode_epoch(Line& e) {
  const bool full = version_ == 3 ? (!e.text.empty() && e.text[0] == '>') : (!e.text.empty() && e.text[0] == '&');
  if (full) {
    epoch_ = std::move(e.text);
    if (version_ == 1) epoch_[0] = ' ';
    have_epoch_ = true;
  } else {
    if (!have_epoch_) fail(e.number, "epoch line difference before the first full epoch line");
    apply_text_difference(epoch_, e.text);
  }
  // RINEX 3.05 Table A3 / RINEX 2.11 Table A2: flag and count columns.
  const std::size_t flag_col = version_ == 3 ? 31 : 28;
  const std::optional<int> flag = text::parse_int(text::columns(epoch_, flag_col, 1));
  const std::optional<int> count = text::parse_int(text::columns(epoch_, flag_col + 1, 3));
  if (!flag || *flag < 0 || *flag > 6) fail(e.number, "bad epoch flag in '" + epoch_ + "'");
  if (!count || *count < 0) fail(e.number, "bad number of satellites in '" + epoch_ + "'");
  if (*flag >= 2 && *flag <= 5) return event(e, *flag, *count);
  if (*flag == 6) fail(e.number, "epoch flag 6 (cycle-slip records) in Compact RINEX is not supported");
  const auto n = static_cast<std::size_t>(*count);
  const std::size_t list_col = version_ == 3 ? kV3ListCol : kV2ListCol;
  if (epoch_.size() < list_col + 3 * n) {
    fail(e.number, "satellite list shorter than the " + std::to_string(n) + " satellites announced");
  }
  ++data_epoch_;

  // Receiver clock offset: its own arc, in units of the RINEX field's last digit.
  Line c;
  need(c, "epoch", e.number);
  bool have_clock = false;
  int64_t clock = 0;
  if (c.text.empty()) {
    clock_.order = 0;
  } else {
    clock = arc_value(clock_, c.text, c, 0);
    have_clock = true;
  }
  std::string head = epoch_.substr(0, std::min(epoch_.size(), list_col));
  if (version_ == 3) {
    head.resize(kV3ListCol, ' ');
    if (have_clock && !append_fixed(head, clock, 12, 15)) fail(c.number, "receiver clock offset out of F15.12");
    emit(std::move(head), e.number);
  } else {
    head.resize(kV2ListCol, ' ');
    for (std::size_t k = 0; k < n; ++k) {
      if (k > 0 && k % kSatsPerV2Line == 0) {
        if (k == kSatsPerV2Line && have_clock) {
          head.resize(68, ' ');
          if (!append_fixed(head, clock, 9, 12)) fail(c.number, "receiver clock offset out of F12.9");
        }
        emit(std::move(head), e.number);
        head.assign(kV2ListCol, ' ');
      }
      head.append(epoch_, list_col + 3 * k, 3);
    }
    if (n <= kSatsPerV2Line && have_clock) {
      head.resize(68, ' ');
      if (!append_fixed(head, clock, 9, 12)) fail(c.number, "receiver clock offset out of F12.9");
    }
    emit(std::move(head), e.number);
  }

  for (std::size_t k = 0; k < n; ++k) {
    const std::string_view id(epoch_.data() + list_col + 3 * k, 3);
    const char sys = id[0] == ' ' ? blank_system_ : id[0];
    const std::optional<int> number = text::parse_int(id.substr(1));
    if (!number || *number < 0 || *number >= kNumbersPerSystem || sys < 'A' || sys > 'Z') {
      fail(e.number, "bad satellite '" + std::string(id) + "' in the epoch line");
    }
    Line s;
    need(s, "epoch", e.number);
    const int ntypes = types_of(sys, s);
    SatState& st = sats_[static_cast<std::size_t>((sys - 'A') * kNumbersPerSystem + *number)];
    if (st.epoch == data_epoch_) fail(s.number, "satellite " + std::string(id) + " twice in one epoch");
    if (st.epoch + 1 != data_epoch_) {  // not in the previous epoch: nothing to continue
      st.arcs.assign(static_cast<std::size_t>(ntypes), Arc{});
      st.flags.clear();
    } else if (st.arcs.size() != static_cast<std::size_t>(ntypes)) {
      st.arcs.resize(static_cast<std::size_t>(ntypes), Arc{});
    }
    st.epoch = data_epoch_;

    std::string out;
    out.reserve(3 + 16 * static_cast<std::size_t>(ntypes));
    if (version_ == 3) out.append(id);
    const std::string_view text = s.text;
    std::size_t pos = 0;
    std::size_t field_start[100];
    bool present[100];
    int64_t value[100];
    for (int t = 0; t < ntypes; ++t) {
      const std::size_t start = pos;
      while (pos < text.size() && text[pos] != ' ') ++pos;
      const std::string_view f = text.substr(start, pos - start);
      if (pos < text.size()) ++pos;
      Arc& arc = st.arcs[static_cast<std::size_t>(t)];
      field_start[t] = start;
      present[t] = !f.empty();
      if (f.empty()) {
        arc.order = 0;  // a blank ends the arc: the next value starts a new one
      } else {
        value[t] = arc_value(arc, f, s, start);
      }
    }
    if (pos < text.size()) apply_text_difference(st.flags, text.substr(pos));
    const std::optional<GnssSystem> system = system_from_letter(sys);
    if (!system || !systems_.has(*system)) {  // decoded (the arcs go on), not written
      if (version_ == 3) {
        emit(std::move(out), s.number);
      } else {
        for (int t = 0; t < ntypes; t += static_cast<int>(kValuesPerV2Line)) emit(std::string(), s.number);
      }
      continue;
    }
    for (int t = 0; t < ntypes; ++t) {
      if (version_ == 1 && t > 0 && t % static_cast<int>(kValuesPerV2Line) == 0) {
        emit(std::move(out), s.number);
        out.clear();
      }
      if (present[t]) {
        if (!append_fixed(out, value[t], 3, 14)) {
          fail(s.number, "value at column " + std::to_string(field_start[t] + 1) + " out of F14.3");
        }
      } else {
        out.append(14, ' ');
      }
      const auto i = 2 * static_cast<std::size_t>(t);
      out.push_back(i < st.flags.size() ? st.flags[i] : ' ');
      out.push_back(i + 1 < st.flags.size() ? st.flags[i + 1] : ' ');
    }
    emit(std::move(out), s.number);
  }
}

}  // namespace gnssemu::observation
