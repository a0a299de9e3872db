// SPDX-License-Identifier: Apache-2.0
// Golden regression cases, gpsd style: tests/golden/nmea/<case>/fix.json (one
// Fix or a list of Fixes, plus the encoder config) and expected.nmea beside it.
// GNSSEMU_REBUILD_GOLDEN=1 rewrites the expected files; a missing one fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/nmea/nmea_format.hpp"
#include "nmea_test_util.hpp"

namespace gnssemu::protocol::nmea {
namespace {

namespace fs = std::filesystem;

fs::path golden_dir() { return fs::path(GNSSEMU_SOURCE_DIR) / "tests" / "golden" / "nmea"; }

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string encode_case(const fs::path& dir) {
  const nlohmann::json j = nlohmann::json::parse(read_file(dir / "fix.json"));
  const NmeaEncoder enc(test::config_from_json(j.value("config", nlohmann::json::object())));
  std::string out;
  if (j.contains("fixes")) {
    for (const auto& f : j.at("fixes")) enc.encode_epoch(test::fix_from_json(f), out);
  } else {
    enc.encode_epoch(test::fix_from_json(j.at("fix")), out);
  }
  return out;
}

std::vector<fs::path> cases() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(golden_dir())) {
    if (e.is_directory() && fs::exists(e.path() / "fix.json")) v.push_back(e.path());
  }
  std::sort(v.begin(), v.end());
  return v;
}

TEST(NmeaGolden, AllCasesMatchByteForByte) {
  const char* rebuild_env = std::getenv("GNSSEMU_REBUILD_GOLDEN");
  const bool rebuild = rebuild_env != nullptr && std::string(rebuild_env) == "1";
  const auto dirs = cases();
  EXPECT_GE(dirs.size(), 15u);
  for (const auto& dir : dirs) {
    SCOPED_TRACE(dir.filename().string());
    const std::string got = encode_case(dir);
    for (const auto& line : test::split_lines(got)) {
      EXPECT_LE(line.size() + 2, kMaxSentenceLength) << line;
      EXPECT_TRUE(nmea_checksum_ok(line)) << line;
    }
    const fs::path expected = dir / "expected.nmea";
    if (rebuild) {
      std::ofstream(expected, std::ios::binary) << got;
      continue;
    }
    ASSERT_TRUE(fs::exists(expected)) << "missing " << expected << " (GNSSEMU_REBUILD_GOLDEN=1 writes it)";
    const std::string want = read_file(expected);
    if (want != got) {
      const auto a = test::split_lines(want);
      const auto b = test::split_lines(got);
      for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
        const std::string x = i < a.size() ? a[i] : "<none>";
        const std::string y = i < b.size() ? b[i] : "<none>";
        EXPECT_EQ(x, y) << "line " << i + 1;
      }
      ADD_FAILURE() << "output differs from " << expected;
    }
  }
}

}  // namespace
}  // namespace gnssemu::protocol::nmea
