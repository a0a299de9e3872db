// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/batch/rinex_output.hpp"

#include <algorithm>
#include <map>

#include "core/rinex/rinex_nav_writer.hpp"
#include "core/time/utc.hpp"

namespace gnssemu::cli {

namespace {

const char* receiver_type(protocol::ubx::Generation g) {
  if (g == protocol::ubx::Generation::kF9P) return "U-BLOX ZED-F9P";
  return g == protocol::ubx::Generation::kM9 ? "U-BLOX NEO-M9N" : "U-BLOX NEO-M8N";
}

}  // namespace

RinexOutput::RinexOutput(const config::Config& config, const orbit::NavData& nav_data, orbit::StoreOptions store,
                         std::ostream* obs, std::ostream* nav)
    : nav_data_(nav_data), store_(nav_data.ephemerides, store), nav_(nav) {
  info_.receiver_type = receiver_type(config.generation);
  info_.interval_s = config.rate_hz > 0.0 ? 1.0 / config.rate_hz : 0.0;
  info_.systems = config.world.systems.intersect(orbit::systems_of(nav_data));
  info_.num_bands = config.receiver.bands;
  std::map<int, int> slots;  // the last set of each slot names its channel
  for (const orbit::Ephemeris& e : nav_data.ephemerides) {
    if (e.sat.system == GnssSystem::kGlonass) slots[e.sat.number] = e.glo_channel;
  }
  info_.glonass_channels.assign(slots.begin(), slots.end());
  if (obs != nullptr) obs_.emplace(*obs, info_);
}

void RinexOutput::on_raw(const time::GpsTime& t, const receiver::RawEpoch& raw, const world::Truth& truth) {
  if (obs_) {
    if (obs_->epochs_written() == 0 && raw.time_valid) {
      // The header's approximate position and leap seconds are those of the first epoch written.
      rinex::ObsHeaderInfo& h = obs_->header();
      if (truth.valid) h.approx_pos_m = truth.pos_m;
      h.leap_seconds = nav_data_.leap_seconds.value_or(time::leap_seconds_at(t));
    }
    obs_->write(raw);
  }
  for (int i = 0; i < raw.num_meas; ++i) {
    const orbit::Ephemeris* e = store_.select(raw.meas[static_cast<std::size_t>(i)].sat, t);
    if (e != nullptr && std::find(used_.begin(), used_.end(), e) == used_.end()) used_.push_back(e);
  }
}

void RinexOutput::finish() {
  if (obs_) obs_->finish();
  if (nav_ == nullptr) return;
  orbit::NavData out = nav_data_;
  out.ephemerides.clear();
  // Satellite and time order, as RINEX files are usually sorted.
  std::vector<const orbit::Ephemeris*> sets = used_;
  std::stable_sort(sets.begin(), sets.end(), [](const orbit::Ephemeris* a, const orbit::Ephemeris* b) {
    return a->sat != b->sat ? a->sat < b->sat : a->toe < b->toe;
  });
  for (const orbit::Ephemeris* e : sets) out.ephemerides.push_back(*e);
  rinex::write_nav(*nav_, out);
}

}  // namespace gnssemu::cli
