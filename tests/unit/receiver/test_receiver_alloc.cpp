// SPDX-License-Identifier: Apache-2.0
// step() must not allocate after warm-up: count every global operator new
// (replaced below for this test executable) across many epochs, including
// no-truth epochs (coasting), 2D-capable states and a teleport (lock breaks,
// full searches, the filter restarting), for the default receiver, one
// with carrier smoothing, a cold start and static hold, and the snapshot
// receiver.
#include <gtest/gtest.h>


#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "tests/support/alloc_counter.hpp"
#include "synthetic_sky.hpp"


namespace gnssemu::receiver {
namespace {

using pipeline::Pipeline;
using pipeline::PipelineConfig;
using world::Truth;

/// The default; every error process and the RTKLIB weights on; carrier
/// smoothing with a cold start and static hold; the snapshot receiver.
std::vector<PipelineConfig> configs() {
  PipelineConfig all;
  all.world.errors.multipath = {0.05, 600.0};
  all.world.errors.gradient.north_m = -0.3;
  all.world.errors.gradient.process = {0.4, 10000.0};
  all.world.errors.iono_scale = {0.3, 20000.0};
  all.receiver.solver = rtklib_single_point(all.receiver.solver);
  PipelineConfig smoothing;
  smoothing.receiver.filter.smoothing_window_s = 100.0;
  smoothing.receiver.filter.static_hold_speed_m_s = 0.5;
  smoothing.receiver.acquisition.start = StartMode::kCold;
  return {PipelineConfig{}, all, smoothing, test::snapshot()};
}

class ReceiverAlloc : public ::testing::TestWithParam<int> {};

TEST_P(ReceiverAlloc, StepDoesNotAllocateAfterWarmUp) {
  const orbit::NavData nav = orbit::read_rinex_nav(std::string(GNSSEMU_TEST_DATA) + "/nav/brdc0010.22n");
  const orbit::EphemerisStore store(nav.ephemerides);
  Pipeline rx(store, configs()[static_cast<std::size_t>(GetParam())]);
  const Lla site{39.6 * kDegToRad, 22.4 * kDegToRad, 100.0};
  const Ecef p0 = geo::ecef_from_lla(site);
  const Vec3 v = geo::enu_to_ecef_vector(Enu(20.0, 15.0, 0.0), site.lat_rad, site.lon_rad);
  const time::GpsTime t0 = time::GpsTime::from_calendar({2022, 1, 1, 3, 0, 0.0});
  auto truth = [&](double dt) {
    Truth tr;
    tr.t = t0 + dt;
    tr.pos_m = Ecef(p0 + v * dt);
    tr.vel_m_s = Ecef(v);
    tr.valid = true;
    return tr;
  };
  rx.step(t0, truth(0.0));  // warm-up (first use of GeographicLib statics)
  const long before = gnssemu::support::allocation_count();
  int fixes = 0;
  for (int k = 1; k <= 2000; ++k) {
    const double dt = 0.5 * k;
    Truth tr = truth(dt);
    if (k % 97 == 0) tr.valid = false;
    if (k == 1500) tr.pos_m = geo::ecef_from_lla({-10.0 * kDegToRad, 60.0 * kDegToRad, 0.0});
    fixes += rx.step(t0 + dt, tr).type == FixType::k3D;
  }
  const long after = gnssemu::support::allocation_count();
  EXPECT_EQ(after - before, 0);
  EXPECT_GT(fixes, 1800);
  // The counter works: a vector allocates.
  std::vector<int>* probe = new std::vector<int>(10);
  delete probe;
  EXPECT_GE(gnssemu::support::allocation_count() - after, 2);
}

std::string receiver_name(const ::testing::TestParamInfo<int>& info) {
  static const char* const kNames[] = {"Default", "EveryErrorProcess", "SmoothingColdStartStaticHold", "Snapshot"};
  return kNames[info.param];
}

INSTANTIATE_TEST_SUITE_P(Receivers, ReceiverAlloc, ::testing::Values(0, 1, 2, 3), receiver_name);

}  // namespace
}  // namespace gnssemu::receiver
