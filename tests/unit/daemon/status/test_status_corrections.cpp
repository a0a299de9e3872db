// SPDX-License-Identifier: Apache-2.0
// StatusProducer: the RTK baseline and its long-baseline counters in
// /api/status "corrections" (docs/status.md).
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon/status/status_producer.hpp"

namespace gnssemu::daemon {
namespace {

nlohmann::json corrections_json(const CorrectionCounters& c) {
  StatusProducer p(StatusSettings{});
  receiver::Fix f;
  world::Truth t;
  p.on_epoch(EpochStatus{&f, &t, 0.0, 1.0, 0.0});
  p.set_corrections(c);
  std::string out;
  p.write_json(out);
  return nlohmann::json::parse(out)["corrections"];
}

TEST(StatusCorrections, BaselineAndLongBaselineCounters) {
  CorrectionCounters c;
  c.station_id = 7;
  c.baseline_m = 61234.5678;
  c.baseline_big = 12;
  c.long_baseline = 3;
  const nlohmann::json j = corrections_json(c);
  EXPECT_NEAR(j["baseline_m"].get<double>(), 61234.568, 1e-6);
  EXPECT_EQ(j["baseline_big"], 12);
  EXPECT_EQ(j["long_baseline"], 3);
  EXPECT_EQ(j["station_id"], 7);
}

TEST(StatusCorrections, NoDifferentialSolutionGivesNullBaseline) {
  const nlohmann::json j = corrections_json(CorrectionCounters{});
  EXPECT_TRUE(j["baseline_m"].is_null());
  EXPECT_EQ(j["baseline_big"], 0);
  EXPECT_EQ(j["long_baseline"], 0);
}

}  // namespace
}  // namespace gnssemu::daemon
