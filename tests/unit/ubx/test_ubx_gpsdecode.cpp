// SPDX-License-Identifier: Apache-2.0
// gpsd's own UBX decoder (gpsdecode, gpsd 3.22) reads the stream we encode
// and must report the Fix we meant to send: time, mode, position, heights,
// speed, track, DOP, satellites with C/N0 and used flags.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/common/constants.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

namespace fs = std::filesystem;

/// gpsdecode's JSON reports for a UBX byte stream; empty if gpsdecode is missing.
std::vector<nlohmann::json> gpsdecode(const std::string& stream) {
  const fs::path file = fs::temp_directory_path() / ("gnssemu_ubx_" + std::to_string(::getpid()) + ".ubx");
  {
    std::ofstream out(file, std::ios::binary);
    out << stream;
  }
  std::vector<nlohmann::json> reports;
  FILE* p = ::popen(("gpsdecode < " + file.string() + " 2>/dev/null").c_str(), "r");
  if (p == nullptr) return reports;
  std::string line;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p) != nullptr) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      reports.push_back(nlohmann::json::parse(line, nullptr, false));
      line.clear();
    }
  }
  ::pclose(p);
  fs::remove(file);
  return reports;
}

bool have_gpsdecode() { return std::system("command -v gpsdecode > /dev/null 2>&1") == 0; }

/// One epoch as gpsd's UBX driver likes it: TIMEGPS (leap seconds), DOP,
/// SAT, PVT, EOE (end of cycle).
void encode_epoch(const UbxEncoder& enc, const receiver::Fix& f, std::string& out) {
  enc.nav_timegps(f, out);
  enc.nav_dop(f, out);
  enc.nav_sat(f, out);
  enc.nav_pvt(f, out);
  enc.nav_eoe(f, out);
}

TEST(UbxGpsdecode, TpvAndSkyMatchTheFix) {
  if (!have_gpsdecode()) GTEST_SKIP() << "gpsdecode not installed";
  const UbxEncoder enc;
  std::string stream;
  std::vector<receiver::Fix> fixes;
  for (int i = 0; i < 5; ++i) {
    receiver::Fix f = test::sample_fix();
    f.t = f.t + 0.2 * i;  // 5 Hz
    f.lla.lat_rad += 1e-6 * i;
    f.lla.height_m += 0.1 * i;
    test::complete_fix(f);
    fixes.push_back(f);
    encode_epoch(enc, f, stream);
  }
  const auto reports = gpsdecode(stream);
  std::vector<nlohmann::json> tpv, sky;
  for (const auto& r : reports) {
    if (r.is_object() && r.value("class", "") == "TPV" && r.contains("lat")) tpv.push_back(r);
    if (r.is_object() && r.value("class", "") == "SKY" && r.contains("satellites")) sky.push_back(r);
  }
  ASSERT_GE(tpv.size(), 5u);
  ASSERT_GE(sky.size(), 1u);
  // The last TPV of each epoch carries that epoch: match by time.
  const char* times[] = {"2022-01-01T12:00:00.250Z", "2022-01-01T12:00:00.450Z", "2022-01-01T12:00:00.650Z",
                         "2022-01-01T12:00:00.850Z", "2022-01-01T12:00:01.050Z"};
  for (int i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    const receiver::Fix& f = fixes[static_cast<std::size_t>(i)];
    const nlohmann::json* found = nullptr;
    for (const auto& r : tpv) {
      if (r.value("time", "") == times[i]) found = &r;
    }
    ASSERT_NE(found, nullptr) << times[i];
    const auto& r = *found;
    EXPECT_EQ(r.value("mode", 0), 3);
    EXPECT_NEAR(r.value("lat", 0.0), f.lla.lat_rad * kRadToDeg, 1e-7);
    EXPECT_NEAR(r.value("lon", 0.0), f.lla.lon_rad * kRadToDeg, 1e-7);
    EXPECT_NEAR(r.value("altHAE", 0.0), f.lla.height_m, 1e-3);
    EXPECT_NEAR(r.value("altMSL", 0.0), f.lla.height_m - f.geoid_sep_m, 1e-3);
    EXPECT_NEAR(r.value("speed", 0.0), 13.4, 1e-3);
    EXPECT_NEAR(r.value("track", 0.0), 87.3, 1e-4);
    EXPECT_NEAR(r.value("eph", 0.0), f.h_acc_m, 1e-3);
    EXPECT_NEAR(r.value("epv", 0.0), f.v_acc_m, 1e-3);
    // climb and eps: gpsdecode derives them from successive fixes, not from velD/sAcc.
    EXPECT_EQ(r.value("leapseconds", 0), 18);
  }
  const auto& s = sky.back();
  EXPECT_EQ(s.value("uSat", 0), 9);
  EXPECT_EQ(s.value("nSat", 0), 10);
  EXPECT_NEAR(s.value("hdop", 0.0), 1.18, 1e-9);
  EXPECT_NEAR(s.value("pdop", 0.0), 1.94, 1e-9);
  EXPECT_NEAR(s.value("vdop", 0.0), 1.54, 1e-9);
  const receiver::Fix& f = fixes.back();
  ASSERT_EQ(s["satellites"].size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) {
    const auto& js = s["satellites"][k];
    const auto& sat = f.sats[k];
    SCOPED_TRACE(sat.sat.prn());
    EXPECT_EQ(js.value("PRN", 0), sat.sat.prn());
    EXPECT_EQ(js.value("used", !sat.used), sat.used);
    EXPECT_NEAR(js.value("ss", -1.0), sat.tracked ? std::round(sat.cn0_dbhz) : 0.0, 1e-9);
    EXPECT_NEAR(js.value("el", -100.0), std::round(sat.el_rad * kRadToDeg), 1e-9);
    EXPECT_NEAR(js.value("az", -1.0), std::round(sat.az_rad * kRadToDeg), 1e-9);
    EXPECT_EQ(js.value("health", 0), 1);
  }
}

TEST(UbxGpsdecode, NoFixIsModeOne) {
  if (!have_gpsdecode()) GTEST_SKIP() << "gpsdecode not installed";
  receiver::Fix f = test::sample_fix();
  f.type = receiver::FixType::kNone;
  std::string stream;
  encode_epoch(UbxEncoder(), f, stream);
  int tpvs = 0;
  for (const auto& r : gpsdecode(stream)) {
    if (r.is_object() && r.value("class", "") == "TPV") {
      ++tpvs;
      EXPECT_LE(r.value("mode", 0), 1);
      EXPECT_FALSE(r.contains("lat"));
    }
  }
  EXPECT_GE(tpvs, 1);
}

TEST(UbxGpsdecode, TwoDimensionalFixIsModeTwo) {
  if (!have_gpsdecode()) GTEST_SKIP() << "gpsdecode not installed";
  receiver::Fix f = test::sample_fix();
  f.type = receiver::FixType::k2D;
  std::string stream;
  encode_epoch(UbxEncoder(), f, stream);
  bool seen = false;
  for (const auto& r : gpsdecode(stream)) {
    if (r.is_object() && r.value("class", "") == "TPV" && r.contains("lat")) {
      seen = true;
      EXPECT_EQ(r.value("mode", 0), 2);
      EXPECT_NEAR(r.value("lat", 0.0), f.lla.lat_rad * kRadToDeg, 1e-7);
    }
  }
  EXPECT_TRUE(seen);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
