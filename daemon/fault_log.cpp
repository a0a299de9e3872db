// SPDX-License-Identifier: Apache-2.0
#include "daemon/fault_log.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

namespace gnssemu::daemon {

std::span<const FaultTransition> FaultLog::update(std::span<const faults::FaultStatus> status) noexcept {
  const std::size_t n = std::min(status.size(), kMaxEvents);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const faults::FaultStatus& s = status[i];
    const bool same = i < n_ && event_[i] == s.event;
    const bool was = same && active_[i];
    if (s.active != was) out_[k++] = FaultTransition{i, s.active};
    event_[i] = s.event;
    active_[i] = s.active;
  }
  // Entries gone from the list without end_all are forgotten.
  n_ = n;
  return {out_.data(), k};
}

std::span<const FaultTransition> FaultLog::end_all() noexcept {
  std::size_t k = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    if (active_[i]) out_[k++] = FaultTransition{i, false};
  }
  n_ = 0;
  return {out_.data(), k};
}

std::string fault_log_text(const faults::FaultEvent& e, std::span<const std::string> output_names) {
  // describe() gives the parameters at one time: at the start and at the
  // end, its words differ exactly where a parameter ramps.
  const std::string from = faults::describe(e, e.start_s);
  const std::string to = std::isfinite(e.duration_s) ? faults::describe(e, e.end_s()) : from;
  std::string out(faults::type_name(e.type));
  std::size_t a = 0, b = 0;
  while (a < from.size()) {
    std::size_t a_end = from.find(' ', a);
    std::size_t b_end = to.find(' ', b);
    if (a_end == std::string::npos) a_end = from.size();
    if (b_end == std::string::npos) b_end = to.size();
    const std::string_view wa(from.data() + a, a_end - a);
    const std::string_view wb(b < to.size() ? std::string_view(to.data() + b, b_end - b) : std::string_view());
    out += ' ';
    out += wa;
    const std::size_t eq = wb.find('=');
    if (wb != wa && eq != std::string_view::npos) out.append("→").append(wb.substr(eq + 1));
    a = a_end + 1;
    b = b_end + 1;
  }
  if (std::isfinite(e.duration_s)) out += fmt::format(" for {:.1f} s", e.duration_s);
  if (e.type == faults::FaultType::kPort) {
    const double o = e.value(faults::Param::kOutput, 0.0);
    if (o < 0.0) {
      out += " on every output";
    } else if (const auto i = static_cast<std::size_t>(o); i < output_names.size()) {
      out += " on " + output_names[i];
    } else {
      out += fmt::format(" on output {:.0f} (none such)", o);
    }
  }
  return out;
}

}  // namespace gnssemu::daemon
