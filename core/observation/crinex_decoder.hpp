// SPDX-License-Identifier: Apache-2.0
#pragma once
// Compact RINEX (Hatanaka) decoder: CRINEX 1.0 (RINEX 2 observations) and
// 3.0 (RINEX 3), after Hatanaka (2008), "A Compression Format and Tools for
// GNSS Observation Data", Bulletin of the GSI 55, 21-30 (docs/cli.md,
// "Compact RINEX"). Each call decodes at most one epoch into RINEX lines.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/observation/obs_lines.hpp"

namespace gnssemu::observation {

class CompactRinexDecoder final : public ObsLines {
public:
  /// src: the file; first: its first line (CRINEX VERS / TYPE), already read;
  /// systems: whose values are written (open_obs_lines). Throws
  /// gnssemu::Error "file:line: reason" for a version other than 1.0/3.0 or
  /// a header that is not Compact RINEX.
  CompactRinexDecoder(text::LineSource& src, text::Line first, SystemSet systems);

  bool next(text::Line& line) override;
  int line_number() const noexcept override { return src_.line_number(); }
  bool compact() const noexcept override { return true; }

  /// Highest order of a difference arc ("n&" with n in 1..kMaxOrder).
  static constexpr int kMaxOrder = 9;

  /// One field's arc of differences (integer units of the field's last digit).
  struct Arc {
    int order = 0;  ///< 0: no arc (missing field); else the arc's order
    int level = 0;  ///< differences held so far, up to order
    std::array<int64_t, kMaxOrder + 1> d{};  ///< d[0] value, d[k] k-th difference
  };
  /// What one satellite carries from the previous epoch.
  struct SatState {
    uint32_t epoch = 0;      ///< decoded data epoch it was last seen in (0: never)
    std::vector<Arc> arcs;   ///< per type
    std::string flags;       ///< LLI and SSI characters, two per type
  };

private:
  [[noreturn]] void fail(int line, const std::string& what) const;
  bool take(text::Line& l);
  void need(text::Line& l, const char* what, int record_line);
  void header_line(const text::Line& l);
  void decode_epoch(text::Line& e);
  void event(const text::Line& e, int flag, int n);
  int types_of(char system, const text::Line& l) const;
  int64_t arc_value(Arc& arc, std::string_view field, const text::Line& l, std::size_t col) const;
  void emit(std::string text, int number);

  text::LineSource& src_;
  SystemSet systems_;
  int version_ = 0;            // 1 or 3
  bool in_header_ = true;
  int header_lines_ = 0;
  std::array<int, 26> ntypes_{};  // per system letter (RINEX 3), from SYS / # / OBS TYPES
  int ntypes_v2_ = 0;
  char blank_system_ = 'G';    // RINEX 2: the system of a blank satellite letter          // RINEX 2: # / TYPES OF OBSERV, every system
  std::string epoch_;          // the last epoch line, decoded
  bool have_epoch_ = false;
  Arc clock_;
  uint32_t data_epoch_ = 0;    // data epochs decoded so far
  std::vector<SatState> sats_; // by letter * 100 + number
  std::vector<text::Line> out_;
  std::size_t out_pos_ = 0;
};

}  // namespace gnssemu::observation
