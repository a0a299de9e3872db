// SPDX-License-Identifier: Apache-2.0
// Golden regression: the NMEA golden cases' Fixes (tests/golden/nmea/<case>/
// fix.json, so both protocols are pinned on the same inputs) encoded as one
// UBX epoch of every message; tests/golden/ubx/<case>.txt holds one line per
// frame (name, length, hex). GNSSEMU_REBUILD_GOLDEN=1 rewrites them; a
// missing file is a failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "nmea_test_util.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const struct {
  MsgId id;
  const char* name;
} kMessages[] = {{msg::kNavPosllh, "NAV-POSLLH"}, {msg::kNavStatus, "NAV-STATUS"}, {msg::kNavDop, "NAV-DOP"},
                 {msg::kNavSol, "NAV-SOL"},       {msg::kNavPvt, "NAV-PVT"},       {msg::kNavVelned, "NAV-VELNED"},
                 {msg::kNavTimegps, "NAV-TIMEGPS"}, {msg::kNavTimeutc, "NAV-TIMEUTC"},
                 {msg::kNavSvinfo, "NAV-SVINFO"}, {msg::kNavSat, "NAV-SAT"},       {msg::kMonHw, "MON-HW"},
                 {msg::kNavEoe, "NAV-EOE"}};

std::string encode_case(const fs::path& fix_json) {
  const nlohmann::json j = nlohmann::json::parse(read_file(fix_json));
  std::vector<nlohmann::json> fixes;
  if (j.contains("fixes")) {
    for (const auto& f : j.at("fixes")) fixes.push_back(f);
  } else {
    fixes.push_back(j.at("fix"));
  }
  const UbxEncoder enc;
  std::string text;
  for (const auto& jf : fixes) {
    receiver::Fix f = nmea::test::fix_from_json(jf);
    test::complete_fix(f);
    f.speed_acc_m_s = jf.value("speed_acc_m_s", 0.3);
    f.time_acc_s = jf.value("time_acc_s", 30e-9);
    for (const auto& m : kMessages) {
      std::string bytes;
      enc.encode(m.id, f, EpochInfo{60000, 31000, ItfmSettings{false}, std::nullopt}, bytes);
      text += std::string(m.name) + " " + std::to_string(bytes.size() - 8) + " " + test::to_hex(bytes) + "\n";
    }
  }
  return text;
}

TEST(UbxGolden, NmeaGoldenFixesMatchByteForByte) {
  const char* env = std::getenv("GNSSEMU_REBUILD_GOLDEN");
  const bool rebuild = env != nullptr && std::string(env) == "1";
  const fs::path nmea_dir = fs::path(GNSSEMU_SOURCE_DIR) / "tests" / "golden" / "nmea";
  const fs::path ubx_dir = fs::path(GNSSEMU_SOURCE_DIR) / "tests" / "golden" / "ubx";
  std::vector<fs::path> cases;
  for (const auto& e : fs::directory_iterator(nmea_dir)) {
    if (e.is_directory() && fs::exists(e.path() / "fix.json")) cases.push_back(e.path());
  }
  std::sort(cases.begin(), cases.end());
  EXPECT_GE(cases.size(), 12u);
  for (const auto& dir : cases) {
    const std::string name = dir.filename().string();
    SCOPED_TRACE(name);
    const std::string got = encode_case(dir / "fix.json");
    const fs::path expected = ubx_dir / (name + ".txt");
    if (rebuild) {
      std::ofstream(expected, std::ios::binary) << got;
      continue;
    }
    ASSERT_TRUE(fs::exists(expected)) << "missing " << expected << " (GNSSEMU_REBUILD_GOLDEN=1 writes it)";
    const std::string want = read_file(expected);
    std::istringstream a(want), b(got);
    std::string la, lb;
    int line = 0;
    while (true) {
      const bool ha = static_cast<bool>(std::getline(a, la));
      const bool hb = static_cast<bool>(std::getline(b, lb));
      if (!ha && !hb) break;
      ++line;
      EXPECT_EQ(ha ? la : "<none>", hb ? lb : "<none>") << "line " << line;
    }
  }
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
