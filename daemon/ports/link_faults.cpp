// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/link_faults.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/protocol/ubx/wire/ubx_message_list.hpp"

namespace gnssemu::daemon {

namespace {

using faults::FaultEvent;
using faults::FaultType;
using faults::LinkFault;
using faults::Param;

// Salt of the link faults' draws, so they never repeat the world's or the fault stage's.
constexpr std::uint64_t kSeedSalt = 0x6C696E6B00000001ULL;  // "link"
// What a draw is for (the purpose part of the CounterRng key; world's values are below 100).
constexpr auto kByteLossDraw = static_cast<world::Purpose>(201);
constexpr auto kReplyByteLossDraw = static_cast<world::Purpose>(202);
constexpr auto kCorruptDraw = static_cast<world::Purpose>(203);
constexpr auto kDropDraw = static_cast<world::Purpose>(204);
// Rate phases within this of a whole epoch count as due (binary rounding of period * rate).
constexpr double kPhaseSlack = 1e-9;

LinkFault fault_of(const FaultEvent& e) noexcept { return static_cast<LinkFault>(e.mode); }

bool acts_on(const FaultEvent& e, std::size_t output) noexcept {
  const double o = e.value(Param::kOutput, 0.0);
  return o < 0.0 || static_cast<std::size_t>(o) == output;
}

// Two independent chances of the same thing: either happens.
double either(double p, double q) noexcept { return 1.0 - (1.0 - p) * (1.0 - q); }

double probability(const FaultEvent& e, double f) noexcept {
  return std::clamp(e.value(Param::kProbability, f), 0.0, 1.0);
}

char hex_digit(unsigned v) noexcept { return "0123456789ABCDEF"[v & 0x0F]; }

// "file:line: port event (fault = "drop"): what".
std::string port_event_problem(const FaultEvent& e, std::string_view file, std::string_view what) {
  const auto names = faults::mode_names(FaultType::kPort);
  const std::string_view name = e.mode < names.size() ? names[e.mode] : std::string_view("?");
  std::string out(file);
  if (e.line > 0) out.append(":").append(std::to_string(e.line));
  out.append(": port event (fault = \"").append(name).append("\"): ").append(what);
  return out;
}

}  // namespace

LinkFaultSet active_link_faults(std::span<const faults::FaultStatus> status, std::size_t output) noexcept {
  LinkFaultSet s;
  double wrong_fix_start_s = -1.0;
  for (const faults::FaultStatus& st : status) {
    if (st.event == nullptr || !st.active) continue;
    const FaultEvent& e = *st.event;
    if (e.type != FaultType::kPort || !acts_on(e, output)) continue;
    const double f = e.fraction_at(e.start_s + st.elapsed_s);
    switch (fault_of(e)) {
      case LinkFault::kByteLoss: s.byte_loss = either(s.byte_loss, probability(e, f)); break;
      case LinkFault::kCorrupt: s.corrupt = either(s.corrupt, probability(e, f)); break;
      case LinkFault::kDrop: s.drop = either(s.drop, probability(e, f)); break;
      case LinkFault::kLatency: s.latency_s += std::max(0.0, e.value(Param::kLatencyMs, f)) * 1e-3; break;
      case LinkFault::kFreeze: s.freeze = true; break;
      case LinkFault::kStop: s.stop = true; break;
      case LinkFault::kRtcmOutage: s.rtcm_outage = true; break;
      case LinkFault::kRtcmStale: s.rtcm_stale = true; break;
      case LinkFault::kRate: {
        const double hz = e.value(Param::kRateHz, f);
        if (hz > 0.0 && (s.rate_hz == 0.0 || hz < s.rate_hz)) s.rate_hz = hz;
        break;
      }
      case LinkFault::kWrongFix: {
        const int t = static_cast<int>(e.value(Param::kFixType, f));
        if (t >= 0 && t < protocol::kReportedFixCount && e.start_s >= wrong_fix_start_s) {
          wrong_fix_start_s = e.start_s;
          s.fix_type = static_cast<protocol::ReportedFix>(t);
        }
        break;
      }
    }
  }
  return s;
}

std::optional<std::string> check_port_events(std::span<const FaultEvent> events, std::size_t output_count,
                                             std::string_view file) {
  for (const FaultEvent& e : events) {
    if (e.type != FaultType::kPort) continue;
    const auto problem = [&](std::string_view what) { return port_event_problem(e, file, what); };
    if (e.has(Param::kOutput)) {
      const double o = e.param(Param::kOutput).from;
      if (o < 0.0 || o >= static_cast<double>(output_count)) {
        std::string what = fmt::format("output = {:.0f} does not exist: ", o);
        if (output_count == 0) {
          what += "the daemon has no [[output]]";
        } else {
          what += fmt::format("{} [[output]] table(s), index 0..{}", output_count, output_count - 1);
        }
        return problem(what);
      }
    }
    const auto needs = [&](Param p) -> std::optional<std::string> {
      if (e.has(p)) return std::nullopt;
      return problem(fmt::format("{} is required for this fault ({})", faults::spec_of(p).name,
                                 faults::spec_of(p).doc));
    };
    std::optional<std::string> missing;
    switch (fault_of(e)) {
      case LinkFault::kByteLoss:
      case LinkFault::kCorrupt:
      case LinkFault::kDrop: missing = needs(Param::kProbability); break;
      case LinkFault::kLatency: missing = needs(Param::kLatencyMs); break;
      case LinkFault::kRate: missing = needs(Param::kRateHz); break;
      case LinkFault::kWrongFix: missing = needs(Param::kFixType); break;
      case LinkFault::kFreeze:
      case LinkFault::kStop:
      case LinkFault::kRtcmOutage:
      case LinkFault::kRtcmStale: break;
    }
    if (missing) return missing;
  }
  return std::nullopt;
}

std::vector<std::string> check_port_events_on_reload(std::span<const FaultEvent> events,
                                                     std::span<const std::string> running,
                                                     std::span<const std::string> reloaded, std::string_view file,
                                                     std::string_view reloaded_file) {
  std::vector<std::string> out;
  for (const FaultEvent& e : events) {
    if (e.type != FaultType::kPort || !e.has(Param::kOutput)) continue;
    const double o = e.param(Param::kOutput).from;
    if (o < 0.0 || o >= static_cast<double>(running.size())) continue;  // check_port_events' case
    const auto i = static_cast<std::size_t>(o);
    if (i < reloaded.size() && reloaded[i] == running[i]) continue;
    if (i >= reloaded.size()) {
      out.push_back(port_event_problem(
          e, file, fmt::format("output = {} (\"{}\") does not exist in {}: {} [[output]] table(s)", i, running[i],
                               reloaded_file, reloaded.size())));
    } else {
      out.push_back(port_event_problem(
          e, file, fmt::format("output = {} is \"{}\" now but \"{}\" in {}", i, running[i], reloaded[i],
                               reloaded_file)));
    }
  }
  return out;
}

bool break_checksum(std::span<char> m) noexcept {
  const std::size_t n = m.size();
  if (n >= 8 && static_cast<unsigned char>(m[0]) == 0xB5 && static_cast<unsigned char>(m[1]) == 0x62) {
    m[n - 1] = static_cast<char>(~static_cast<unsigned char>(m[n - 1]));  // CK_B
    return true;
  }
  // "$...*hh" with an optional CR LF.
  std::size_t end = n;
  while (end > 0 && (m[end - 1] == '\r' || m[end - 1] == '\n')) --end;
  if (n == 0 || m[0] != '$' || end < 4 || m[end - 3] != '*') return false;
  const auto value = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  };
  const int hi = value(m[end - 2]);
  const int lo = value(m[end - 1]);
  if (hi < 0 || lo < 0) return false;
  const unsigned wrong = (static_cast<unsigned>(hi * 16 + lo) + 1u) & 0xFFu;
  m[end - 2] = hex_digit(wrong >> 4);
  m[end - 1] = hex_digit(wrong);
  return true;
}

LinkFaults::LinkFaults(std::size_t output) : output_(output) {
  held_.reserve(protocol::ubx::MessageList::kMaxBytes);
  held_ends_.reserve(protocol::ubx::MessageList::kMaxMessages);
  set_seed(1);
}

void LinkFaults::set_seed(std::uint64_t seed) noexcept { rng_ = world::CounterRng(world::CounterRng::mix(seed ^ kSeedSalt)); }

void LinkFaults::update(std::span<const faults::FaultStatus> status) noexcept {
  set_ = active_link_faults(status, output_);
}

LinkFaults::Release LinkFaults::release(double period_s, std::string_view last,
                                        std::span<const std::size_t> last_ends) noexcept {
  if (!set_.freeze) holding_ = false;
  if (set_.rate_hz <= 0.0) rate_phase_ = 1.0;
  if (set_.stop) {
    ++stats_.epochs_stopped;
    return Release::kNothing;
  }
  if (set_.freeze && !holding_) {
    // A stuck firmware repeats what it last sent before it hung.
    holding_ = true;
    held_.assign(last.data(), std::min(last.size(), held_.capacity()));
    held_ends_.clear();
    for (const std::size_t e : last_ends) {
      if (e <= held_.size() && held_ends_.size() < held_ends_.capacity()) held_ends_.push_back(e);
    }
  }
  if (set_.rate_hz > 0.0) {
    const bool due = rate_phase_ >= 1.0 - kPhaseSlack;
    if (due) rate_phase_ -= 1.0;
    // At most one epoch banked: a rate at or above the navigation rate sends every epoch.
    rate_phase_ = std::min(rate_phase_ + period_s * set_.rate_hz, 2.0);
    if (!due) {
      ++stats_.epochs_skipped;
      return Release::kNothing;
    }
  }
  if (holding_) {
    ++stats_.epochs_frozen;
    return Release::kHeld;
  }
  return Release::kCurrent;
}

bool LinkFaults::drops(std::uint64_t epoch, std::size_t index) noexcept {
  if (set_.drop <= 0.0 || rng_.uniform(output_, epoch, kDropDraw, index) > set_.drop) return false;
  ++stats_.messages_dropped;
  return true;
}

bool LinkFaults::corrupts(std::uint64_t epoch, std::size_t index) noexcept {
  if (set_.corrupt <= 0.0 || rng_.uniform(output_, epoch, kCorruptDraw, index) > set_.corrupt) return false;
  ++stats_.messages_corrupted;
  return true;
}

std::size_t LinkFaults::lose_bytes(std::uint64_t epoch, bool reply, std::string_view in,
                                   std::span<const std::size_t> ends, std::string& out,
                                   std::vector<std::size_t>& out_ends) noexcept {
  out.clear();
  out_ends.clear();
  const std::uint64_t key = reply ? replies_++ : epoch;
  const world::Purpose purpose = reply ? kReplyByteLossDraw : kByteLossDraw;
  std::size_t next_end = 0;  // index into ends
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (set_.byte_loss <= 0.0 || rng_.uniform(output_, key, purpose, i) > set_.byte_loss) out.push_back(in[i]);
    // Close every message that ends after byte i; a message lost whole adds no end.
    for (; next_end < ends.size() && ends[next_end] <= i + 1; ++next_end) {
      if (out_ends.empty() ? !out.empty() : out_ends.back() < out.size()) out_ends.push_back(out.size());
    }
  }
  const std::size_t lost = in.size() - out.size();
  stats_.bytes_lost += lost;
  return lost;
}

}  // namespace gnssemu::daemon
