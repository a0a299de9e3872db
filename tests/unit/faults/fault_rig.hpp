// SPDX-License-Identifier: Apache-2.0
#pragma once
// A static receiver on real broadcast ephemerides for the fault tests.
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "core/faults/fault_event.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"

namespace gnssemu::faults::test {

inline const orbit::EphemerisStore& test_store() {
  static const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  static const orbit::EphemerisStore store(nav.ephemerides);
  return store;
}

/// The receiver runs kWarmUp_s before the test's time 0 (acquisition and
/// the filter settle); event times count from the test's time 0.
struct Rig {
  static constexpr double kWarmUp_s = 60.0;
  explicit Rig(std::span<const FaultEvent> events = {}, bool with_stage = true)
      : t0(test_store().first_valid() + 8.0 * 3600.0), rx(test_store(), pipeline::PipelineConfig{}) {
    truth.pos_m = geo::ecef_from_lla(site);
    truth.valid = true;
    if (with_stage) {
      std::vector<FaultEvent> shifted(events.begin(), events.end());
      for (FaultEvent& e : shifted) e.start_s += kWarmUp_s;
      rx.set_faults(shifted);
    }
    for (int k = 0; k < static_cast<int>(kWarmUp_s); ++k) step(k - kWarmUp_s);
  }
  const receiver::Fix& step(double s) {
    truth.t = t0 + kWarmUp_s + s;
    return rx.step(truth.t, truth);
  }
  Enu error(const receiver::Fix& f) const {
    return geo::ecef_to_enu_vector(f.pos_m - truth.pos_m, site.lat_rad, site.lon_rad);
  }
  const Lla site{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};
  time::GpsTime t0;
  pipeline::Pipeline rx;
  world::Truth truth;
};

inline FaultEvent make_event(FaultType type, double start_s, double duration_s = kForever_s, int mode = 0) {
  return FaultEvent::of(type, start_s, duration_s, static_cast<std::uint8_t>(mode));
}

}  // namespace gnssemu::faults::test
