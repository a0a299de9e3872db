// SPDX-License-Identifier: Apache-2.0
#include "config/setup/base_station.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "config/setup/pipeline_setup.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/protocol/rtcm/rtcm_ephemeris.hpp"

namespace gnssemu::config {

namespace {

using protocol::rtcm::MsmKind;

/// The system and kind of an MSM message number; nullopt for other messages.
std::optional<std::pair<GnssSystem, MsmKind>> msm_of(int number) noexcept {
  for (std::size_t s = 0; s < kNumSystems; ++s) {
    const auto sys = static_cast<GnssSystem>(s);
    for (MsmKind k : {MsmKind::kMsm4, MsmKind::kMsm7})
      if (protocol::rtcm::msm_message_number(sys, k) == number) return std::pair{sys, k};
  }
  return std::nullopt;
}

MsmKind msm_kind_of(const BaseConfig& b) noexcept {
  for (const BaseMessage& m : b.messages)
    if (auto msm = msm_of(m.number)) return msm->second;
  return MsmKind::kMsm7;
}

}  // namespace

BaseStation::BaseStation(const Config& c, const orbit::EphemerisStore& store, const pipeline::Broadcast& broadcast,
                         const scene::Scene* scene)
    : base_(c.base.value()),
      store_(store),
      pos_m_(geo::ecef_from_lla(base_.position)),
      msm_(base_.station_id, msm_kind_of(base_)) {
  rx_ = make_pipeline(with_receiver_settings(c, base_.settings), store, broadcast, base_.open_sky ? nullptr : scene);
  for (const BaseMessage& m : base_.messages) {
    if (auto msm = msm_of(m.number)) {
      msm_systems_ = msm_systems_.with(msm->first);
      msm_interval_s_ = m.interval_s;
    }
  }
  rx_->receiver().set_systems(msm_systems_.empty() ? SystemSet::all() : msm_systems_);
  station_.station_id = base_.station_id;
  station_.arp_ecef_m = pos_m_;
  station_.antenna_height_m = base_.antenna_height_m;
  station_.gps = msm_systems_.has(GnssSystem::kGps);
  station_.glonass = msm_systems_.has(GnssSystem::kGlonass);
  station_.galileo = msm_systems_.has(GnssSystem::kGalileo);
}

BaseStation::~BaseStation() = default;

const receiver::RawEpoch& BaseStation::raw() const noexcept { return rx_->receiver().raw(); }

bool BaseStation::due(const time::GpsTime& t, double interval_s) noexcept {
  if (!(interval_s > 0.0)) return false;
  const double k = t.tow_s() / interval_s;
  return std::abs(k - std::round(k)) * interval_s < 1e-3;
}

bool BaseStation::is_epoch(const time::GpsTime& t) const noexcept { return due(t, 1.0 / rate_hz()); }

void BaseStation::step(const time::GpsTime& t, std::string& out) noexcept {
  rx_->step(t, world::Truth{t, pos_m_, Ecef{}, true});
  encode(t, out);
}

void BaseStation::step(const world::SharedSky& sky, std::string& out) noexcept {
  rx_->step(sky, world::Truth{sky.t(), pos_m_, Ecef{}, true});
  encode(sky.t(), out);
}

void BaseStation::encode(const time::GpsTime& t, std::string& out) noexcept {
  const std::size_t before = out.size();
  const receiver::RawEpoch& raw = rx_->receiver().raw();
  ++stats_.epochs;
  try {
    for (const BaseMessage& m : base_.messages) {
      if (!due(t, m.interval_s)) continue;
      if (m.number == 1005 || m.number == 1006) {
        protocol::rtcm::append_station(station_, m.number == 1006, out);
        ++stats_.messages;
      } else if (m.number == 1230) {
        // As a u-blox F9 base: phase ranges aligned, no bias fields (docs/base-station.md).
        protocol::rtcm::append_glonass_biases(base_.station_id, true, {}, out);
        ++stats_.messages;
      } else if (msm_of(m.number)) {
        continue;  // below, all systems in one go
      } else {
        SatId last;
        for (int i = 0; i < raw.num_meas; ++i) {
          const SatId sat = raw.meas[static_cast<std::size_t>(i)].sat;
          if (sat == last || protocol::rtcm::ephemeris_message_number(sat.system) != m.number) continue;
          last = sat;
          if (const orbit::Ephemeris* eph = store_.select(sat, t)) {
            if (protocol::rtcm::append_ephemeris(*eph, raw.leap_seconds, out)) ++stats_.messages;
          }
        }
      }
    }
    if (due(t, msm_interval_s_)) {
      const protocol::rtcm::MsmEpochStats s = msm_.append_epoch(raw, msm_systems_, out);
      stats_.messages += static_cast<std::uint64_t>(s.messages);
      stats_.dropped_cells += static_cast<std::uint64_t>(s.dropped_cells);
    }
  } catch (...) {
    // Only a failed growth of out lands here; the epoch is dropped whole.
    out.resize(before);
  }
  stats_.bytes += out.size() - before;
}

std::string BaseStation::format_details() const {
  std::string s;
  for (const BaseMessage& m : base_.messages) {
    if (!s.empty()) s += ',';
    s += fmt::format("{}({:g})", m.number, m.interval_s);
  }
  return s;
}

std::vector<BaseMessage> parse_base_messages(std::string_view text, const std::string& where, int line) {
  std::vector<BaseMessage> out;
  const auto fail = [&](const std::string& why) { throw Error(where, line, why); };
  std::optional<std::pair<MsmKind, double>> msm;
  std::size_t at = 0;
  while (at <= text.size()) {
    std::size_t end = text.find(',', at);
    if (end == std::string_view::npos) end = text.size();
    std::string item(text.substr(at, end - at));
    at = end + 1;
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (item.empty()) fail("empty message in \"" + std::string(text) + "\"");
    BaseMessage m;
    m.line = line;
    std::size_t used = 0;
    try {
      m.number = std::stoi(item, &used);
    } catch (const std::exception&) {
      fail("\"" + item + "\" is not a message number");
    }
    if (used < item.size()) {
      const std::string rest = item.substr(used);
      std::size_t n = 0;
      try {
        if (rest.size() < 3 || rest.front() != '(' || rest.back() != ')') throw std::invalid_argument(rest);
        m.interval_s = std::stod(rest.substr(1, rest.size() - 2), &n);
        if (n != rest.size() - 2) throw std::invalid_argument(rest);
      } catch (const std::exception&) {
        fail("\"" + item + "\": expected NUMBER or NUMBER(INTERVAL_S)");
      }
    }
    if (std::find(std::begin(kBaseMessageNumbers), std::end(kBaseMessageNumbers), m.number) ==
        std::end(kBaseMessageNumbers)) {
      fail(fmt::format("message {} is not one the base sends (1005, 1006, 1230, MSM4/MSM7 1074/1077, 1084/1087, "
                       "1094/1097, 1114/1117, 1124/1127, ephemerides 1019, 1020, 1042, 1046)",
                       m.number));
    }
    if (!(m.interval_s > 0.0) || !(m.interval_s <= 3600.0)) fail(fmt::format("message {}: interval must be in (0, 3600] s", m.number));
    for (const BaseMessage& o : out)
      if (o.number == m.number) fail(fmt::format("message {} given twice", m.number));
    if (auto k = msm_of(m.number)) {
      if (msm && msm->first != k->second) fail("MSM4 and MSM7 mixed: a base sends one MSM type");
      if (msm && msm->second != m.interval_s) fail("MSMs at different intervals: observations share one rate");
      msm = std::pair{k->second, m.interval_s};
    }
    out.push_back(m);
  }
  return out;
}

std::string base_distance_warning(const Config& c) {
  if (!c.base) return {};
  const double d = (geo::ecef_from_lla(c.base->position) - geo::ecef_from_lla(c.origin)).norm();
  if (d <= kBaseWarnDistance_m) return {};
  return fmt::format("{}:{}: [base] is {:.0f} km from the rover's origin (more than {:.0f} km): RTK degrades with the "
                     "baseline, and a u-blox F9P rover warns \"DGNSS baseline big\"",
                     c.source, c.base->line, d / 1e3, kBaseWarnDistance_m / 1e3);
}

}  // namespace gnssemu::config
