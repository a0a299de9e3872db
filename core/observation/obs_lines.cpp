// SPDX-License-Identifier: Apache-2.0
#include "core/observation/obs_lines.hpp"

#include <optional>
#include <utility>

#include "core/observation/crinex_decoder.hpp"

namespace gnssemu::observation {

namespace {

/// A RINEX file's lines as they are (the first one already read).
class PlainLines final : public ObsLines {
public:
  PlainLines(text::LineSource& src, std::optional<text::Line> first) : src_(src), first_(std::move(first)) {}

  bool next(text::Line& line) override {
    if (first_) {
      line = std::move(*first_);
      first_.reset();
      return true;
    }
    return src_.next(line);
  }
  int line_number() const noexcept override { return src_.line_number(); }
  bool compact() const noexcept override { return false; }

private:
  text::LineSource& src_;
  std::optional<text::Line> first_;
};

}  // namespace

std::unique_ptr<ObsLines> open_obs_lines(text::LineSource& src, SystemSet systems) {
  text::Line first;
  if (!src.next(first)) return std::make_unique<PlainLines>(src, std::nullopt);
  if (is_compact_rinex(first.text)) return std::make_unique<CompactRinexDecoder>(src, std::move(first), systems);
  return std::make_unique<PlainLines>(src, std::move(first));
}

}  // namespace gnssemu::observation
