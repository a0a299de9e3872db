// SPDX-License-Identifier: Apache-2.0
// The whole pipeline pinned, as gpsd pins its drivers: config + truth ->
// `batch` (receiver, encoders, the emulated u-blox's message rates) ->
// NMEA, UBX, per-epoch errors and the summary, compared byte for byte with
// tests/golden/pipeline/<case>/expected.*. The same case with the snapshot
// receiver (no navigation filter, acquisition not modelled, fixed Doppler
// noise) is compared with <case>/snapshot/expected.*, the outputs of the
// receiver before the filter existed. GNSSEMU_REBUILD_GOLDEN=1 rewrites
// them (review the diff); a missing expected file is a failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "tools/gnssemu/batch/batch.hpp"
#include "tools/gnssemu/batch/truth_csv.hpp"

namespace gnssemu::cli {
namespace {

namespace fs = std::filesystem;

fs::path golden_dir() { return fs::path(GNSSEMU_SOURCE_DIR) / "tests" / "golden" / "pipeline"; }

std::vector<std::string> case_names() {
  std::vector<std::string> v;
  for (const auto& e : fs::directory_iterator(golden_dir())) {
    if (e.is_directory() && fs::exists(e.path() / "config.toml")) v.push_back(e.path().filename().string());
  }
  std::sort(v.begin(), v.end());
  return v;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

bool rebuild() {
  const char* env = std::getenv("GNSSEMU_REBUILD_GOLDEN");
  return env != nullptr && std::string(env) == "1";
}

/// Text outputs: the first differing lines are named.
void expect_text(const fs::path& expected, const std::string& got) {
  if (rebuild()) {
    std::ofstream(expected, std::ios::binary) << got;
    return;
  }
  ASSERT_TRUE(fs::exists(expected)) << "missing " << expected << " (GNSSEMU_REBUILD_GOLDEN=1 writes it)";
  const std::string want = read_file(expected);
  if (want == got) return;
  const auto a = lines(want), b = lines(got);
  int shown = 0;
  for (std::size_t i = 0; i < std::max(a.size(), b.size()) && shown < 5; ++i) {
    const std::string x = i < a.size() ? a[i] : "<none>";
    const std::string y = i < b.size() ? b[i] : "<none>";
    if (x != y) {
      ADD_FAILURE() << expected.filename().string() << " line " << i + 1 << "\n  want " << x << "\n  got  " << y;
      ++shown;
    }
  }
  ADD_FAILURE() << "output differs from " << expected << " (" << a.size() << " lines expected, " << b.size() << " got)";
}

/// UBX: the first differing byte, with the frame it falls in.
void expect_binary(const fs::path& expected, const std::string& got) {
  if (rebuild()) {
    std::ofstream(expected, std::ios::binary) << got;
    return;
  }
  ASSERT_TRUE(fs::exists(expected)) << "missing " << expected << " (GNSSEMU_REBUILD_GOLDEN=1 writes it)";
  const std::string want = read_file(expected);
  if (want == got) return;
  std::size_t i = 0;
  while (i < want.size() && i < got.size() && want[i] == got[i]) ++i;
  // Walk the expected frames (B5 62 cls id len16 payload ck16) to name the one.
  std::size_t frame = 0, start = 0;
  while (start + 6 <= want.size()) {
    const std::size_t len = static_cast<unsigned char>(want[start + 4]) |
                            static_cast<std::size_t>(static_cast<unsigned char>(want[start + 5])) << 8;
    if (start + 8 + len > i) break;
    start += 8 + len;
    ++frame;
  }
  char id[32] = "?";
  if (start + 4 <= want.size()) {
    std::snprintf(id, sizeof id, "%02X-%02X", static_cast<unsigned char>(want[start + 2]),
                  static_cast<unsigned char>(want[start + 3]));
  }
  ADD_FAILURE() << expected.filename().string() << ": " << want.size() << " bytes expected, " << got.size()
                << " got; first difference at byte " << i << ", in frame " << frame << " (class-id " << id
                << ", starting at byte " << start << ")";
}

/// The receiver as it was before acquisition and the navigation filter, as
/// a user selects it (docs/configuration.md): snapshot least squares on raw
/// code, satellites tracked as soon as their C/N0 allows, white Doppler noise
/// of errors.doppler_sigma_m_s. The case's file with those keys added.
config::Config snapshot_receiver(const fs::path& config_file) {
  std::string text = read_file(config_file);
  const std::string header = "\n[receiver]\n";
  const std::size_t at = text.find(header);
  EXPECT_NE(at, std::string::npos) << config_file << " has no [receiver] table";
  if (at != std::string::npos) text.insert(at + header.size(), "filter = \"none\"\n");
  text += "\n[receiver.acquisition]\nmodelled = false\n\n[signal.carrier]\ndoppler_model = \"fixed\"\n";
  return config::parse_config(text, config_file.string(), config_file.parent_path().string());
}

void run_case(const config::Config& cfg, const fs::path& dir, const fs::path& out) {
  const orbit::NavData nav = orbit::read_rinex_nav(cfg.nav_file);
  const world::TruthTrack track(read_truth_csv((dir / "truth.csv").string()));
  std::ostringstream nmea, ubx, errors, summary;
  const BatchSummary sum = run_batch(cfg, nav, track, &nmea, &errors, &ubx);
  write_summary(sum, summary);
  EXPECT_GT(sum.epochs, 0);
  if (rebuild()) fs::create_directories(out);
  expect_text(out / "expected.nmea", nmea.str());
  expect_binary(out / "expected.ubx", ubx.str());
  expect_text(out / "expected_errors.csv", errors.str());
  expect_text(out / "expected_summary.txt", summary.str());
}

class PipelineGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(PipelineGolden, MatchesByteForByte) {
  const fs::path dir = golden_dir() / GetParam();
  run_case(config::load_config((dir / "config.toml").string()), dir, dir);
}

TEST_P(PipelineGolden, SnapshotReceiverMatchesByteForByte) {
  const fs::path dir = golden_dir() / GetParam();
  run_case(snapshot_receiver(dir / "config.toml"), dir, dir / "snapshot");
}

INSTANTIATE_TEST_SUITE_P(Cases, PipelineGolden, ::testing::ValuesIn(case_names()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(PipelineGoldenCases, CoverWhatTheyMustCover) {
  // Static open sky, 10 Hz motion, truth loss, buildings, a 2D fix, a week rollover, four systems,
  // and the M8 and NEO-M9N as they ship (their systems, NMEA version and sentences; NAV-SIG, NAV-TIME*).
  const auto names = case_names();
  for (const char* want : {"static_open_sky", "moving_10hz", "truth_loss", "building_canyon", "fix_2d", "week_rollover",
                          "four_systems", "m8_gps_glonass", "m9_four_systems"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  }
}

}  // namespace
}  // namespace gnssemu::cli
