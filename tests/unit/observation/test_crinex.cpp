// SPDX-License-Identifier: Apache-2.0
// Compact RINEX (Hatanaka) decoding: hand-made CRINEX 3.0 and EPN's KOSG
// CRINEX 1.0 files against their plain RINEX (tests/data/README.md), the
// shared NYA1 day against the plain files decoded from the same source
// (skipped without ../shared/data), and malformed files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/error.hpp"
#include "core/observation/rinex_obs.hpp"

using namespace gnssemu;
using namespace gnssemu::observation;

namespace {

std::string test_obs(const std::string& name) { return std::string(GNSSEMU_TEST_DATA) + "/obs/" + name; }
std::string shared_obs(const std::string& name) { return std::string(GNSSEMU_SHARED_DATA) + "/obs/" + name; }

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every epoch, satellite, value and flag of a equal to b's; limit: epochs compared.
void expect_same(const ObsData& a, const ObsData& b, std::size_t limit = SIZE_MAX) {
  const std::size_t n = std::min({a.epochs.size(), b.epochs.size(), limit});
  for (std::size_t k = 0; k < n; ++k) {
    const ObsEpoch& x = a.epochs[k];
    const ObsEpoch& y = b.epochs[k];
    ASSERT_EQ(x.t, y.t) << "epoch " << k;
    ASSERT_EQ(x.flag, y.flag) << "epoch " << k;
    ASSERT_EQ(x.rcv_clock_offset_s, y.rcv_clock_offset_s) << "epoch " << k;
    ASSERT_EQ(x.sats.size(), y.sats.size()) << "epoch " << k;
    for (std::size_t s = 0; s < x.sats.size(); ++s) {
      ASSERT_EQ(x.sats[s].sat, y.sats[s].sat) << "epoch " << k;
      ASSERT_EQ(x.sats[s].values.size(), y.sats[s].values.size());
      for (std::size_t t = 0; t < x.sats[s].values.size(); ++t) {
        const ObsValue& u = x.sats[s].values[t];
        const ObsValue& v = y.sats[s].values[t];
        ASSERT_EQ(u.valid, v.valid) << "epoch " << k << " sat " << s << " type " << t;
        ASSERT_EQ(u.value, v.value) << "epoch " << k << " sat " << s << " type " << t;
        ASSERT_EQ(u.lli, v.lli) << "epoch " << k << " sat " << s << " type " << t;
        ASSERT_EQ(u.ssi, v.ssi) << "epoch " << k << " sat " << s << " type " << t;
      }
    }
  }
}

/// The error message of reading text, or "" if it read.
std::string error_of_text(const std::string& text, const std::string& name = "bad.crx") {
  std::istringstream in(text);
  try {
    read_rinex_obs(in, name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// The tiny CRINEX 3.0 file with line `number` (1-based) replaced.
std::string tiny_with(int number, const std::string& line) {
  std::istringstream in(slurp(test_obs("tiny_v3.crx")));
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n) out += (n == number ? line : l) + "\n";
  return out;
}

/// The tiny CRINEX 3.0 file's first `lines` lines.
std::string tiny_first(int lines) {
  std::istringstream in(slurp(test_obs("tiny_v3.crx")));
  std::string out, l;
  for (int n = 1; n <= lines && std::getline(in, l); ++n) out += l + "\n";
  return out;
}

}  // namespace

TEST(Crinex, HandMadeVersion3MatchesItsPlainFile) {
  const ObsData c = read_rinex_obs(test_obs("tiny_v3.crx"));
  const ObsData r = read_rinex_obs(test_obs("tiny_v3.rnx"));
  EXPECT_TRUE(c.header.compact);
  EXPECT_FALSE(r.header.compact);
  ASSERT_EQ(c.epochs.size(), 4u);
  ASSERT_EQ(r.epochs.size(), 4u);
  expect_same(c, r);
  EXPECT_EQ(c.skipped_records, 1);  // I05: NavIC is outside the SatId table
  EXPECT_EQ(c.event_records, 1);
  EXPECT_EQ(c.header.marker_name, "TINY AFTER EVENT");
  // Spot checks of what the file exercises.
  EXPECT_DOUBLE_EQ(c.epochs[0].rcv_clock_offset_s, 0.123456789012);
  EXPECT_DOUBLE_EQ(c.epochs[2].rcv_clock_offset_s, 0.123456791012);  // second differences
  EXPECT_EQ(c.epochs[3].rcv_clock_offset_s, 0.0);                    // blank clock line
  EXPECT_EQ(c.epochs[0].sats[1].get(1), nullptr);                    // G02 L1C blank
  EXPECT_DOUBLE_EQ(c.epochs[2].sats[1].get(0)->value, 21000500.0);   // G02 C1C arc restarted (2&)
  EXPECT_EQ(c.epochs[2].sats[1].get(0)->ssi, 6);
  EXPECT_EQ(c.epochs[1].sats[0].get(1)->lli, 0);  // '&' cleared G01 L1C's LLI
  EXPECT_EQ(c.epochs[0].sats[0].get(1)->lli, 1);
  EXPECT_EQ(c.epochs[1].sats[3].sat, SatId(GnssSystem::kGalileo, 11));
  EXPECT_DOUBLE_EQ(c.epochs[3].sats[1].get(1)->value, 101000100.0);  // R03 L1C back after a blank
}

TEST(Crinex, KosgVersion1MatchesItsPlainFile) {
  const ObsData c = read_rinex_obs(test_obs("KOSG0010.95D"));
  const ObsData r = read_rinex_obs(test_obs("KOSG0010.95O"));
  EXPECT_TRUE(c.header.compact);
  ASSERT_EQ(c.epochs.size(), 3u);
  expect_same(c, r);
  EXPECT_EQ(c.header.types_of(GnssSystem::kGps),
            (std::vector<std::string>{"L1C", "L2W", "C1W", "C2W", "C1C"}));
  EXPECT_DOUBLE_EQ(c.epochs[2].sats[6].get(1)->value, -3691783.852);  // G24 L2 continued past a restarted L1
}

TEST(Crinex, SharedNya1DayMatchesThePlainFilesDecodedFromIt) {
  const std::string crx = shared_obs("NYA100NOR_S_20241240000_01D_30S_MO.crx.gz");
  if (!std::filesystem::exists(crx)) GTEST_SKIP() << crx << " not present";
  const ObsData day = read_rinex_obs(crx);
  ASSERT_EQ(day.epochs.size(), 2880u);
  EXPECT_EQ(day.skipped_records, 0);
  // The 90-minute plain file: its first 180 epochs, every system and type.
  const ObsData m = read_rinex_obs(test_obs("NYA100NOR_S_20241240000_90M_30S_MO.rnx"));
  ASSERT_EQ(m.epochs.size(), 180u);
  for (int s = 0; s < kNumSystems; ++s) EXPECT_EQ(day.header.types[s], m.header.types[s]);
  expect_same(day, m, 180);
  // The GPS L1 C/A day: every GPS satellite of every epoch.
  const ObsData l1 = read_rinex_obs(test_obs("NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz"));
  ASSERT_EQ(l1.epochs.size(), 2880u);
  const ObsHeader& h = day.header;
  const int idx[4] = {h.type_index(GnssSystem::kGps, "C1C"), h.type_index(GnssSystem::kGps, "L1C"),
                      h.type_index(GnssSystem::kGps, "D1C"), h.type_index(GnssSystem::kGps, "S1C")};
  std::size_t compared = 0;
  for (std::size_t k = 0; k < 2880; ++k) {
    const ObsEpoch& a = day.epochs[k];
    const ObsEpoch& b = l1.epochs[k];
    ASSERT_EQ(a.t, b.t);
    std::size_t j = 0;
    for (const SatObs& s : a.sats) {
      if (s.sat.system != GnssSystem::kGps) continue;
      ASSERT_LT(j, b.sats.size()) << "epoch " << k;
      const SatObs& g = b.sats[j++];
      ASSERT_EQ(s.sat, g.sat) << "epoch " << k;
      for (int t = 0; t < 4; ++t) {
        const ObsValue& u = s.values[static_cast<std::size_t>(idx[t])];
        const ObsValue& v = g.values[static_cast<std::size_t>(t)];
        ASSERT_EQ(u.valid, v.valid) << "epoch " << k;
        ASSERT_EQ(u.value, v.value) << "epoch " << k;
        ASSERT_EQ(u.lli, v.lli) << "epoch " << k;
        ASSERT_EQ(u.ssi, v.ssi) << "epoch " << k;
        ++compared;
      }
    }
    ASSERT_EQ(j, b.sats.size()) << "epoch " << k;
  }
  EXPECT_EQ(compared, 4u * 33830u);
  // GPS alone (as spp reads it): the same GPS records.
  ObsData want = day;
  for (ObsEpoch& e : want.epochs) std::erase_if(e.sats, [](const SatObs& s) { return s.sat.system != GnssSystem::kGps; });
  expect_same(read_rinex_obs(crx, SystemSet::only(GnssSystem::kGps)), want);
}

TEST(Crinex, EverySharedCompactFileDecodes) {
  const std::vector<std::pair<std::string, std::size_t>> files{
      {"AJAC00FRA_R_20242090000_01D_30S_MO.crx.gz", 2880}, {"AJAC00FRA_R_20242100000_01D_30S_MO.crx.gz", 2880},
      {"BELE00BRA_R_20240100000_01D_30S_MO.crx.gz", 2880}, {"CEBR00ESP_R_20182000000_01D_30S_MO.crx.gz", 2880},
      {"TLSE00FRA_R_20240011200_15M_01S_MO.crx.gz", 900}};
  int read = 0;
  for (const auto& [name, epochs] : files) {
    const std::string path = shared_obs(name);
    if (!std::filesystem::exists(path)) continue;
    const ObsData d = read_rinex_obs(path);
    EXPECT_EQ(d.epochs.size(), epochs) << name;
    ++read;
  }
  if (read == 0) GTEST_SKIP() << "no shared Compact RINEX files";
}

struct BadCrx {
  int line;              // line of tiny_v3.crx to replace (0: cut the file after `cut` lines)
  const char* text;      // its replacement
  const char* expect;    // part of the message
};

class CrinexBad : public ::testing::TestWithParam<BadCrx> {};

TEST_P(CrinexBad, ClearErrorWithFileAndLine) {
  const BadCrx& c = GetParam();
  const std::string msg = error_of_text(tiny_with(c.line, c.text));
  ASSERT_FALSE(msg.empty()) << "accepted: line " << c.line << " = '" << c.text << "'";
  EXPECT_EQ(msg.rfind("bad.crx:", 0), 0u) << msg;
  EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    Lines, CrinexBad,
    ::testing::Values(
        BadCrx{1, "2.0                 COMPACT RINEX FORMAT                    CRINEX VERS   / TYPE",
               "bad.crx:1: Compact RINEX version '2.0' not supported"},
        BadCrx{2, "hand-made", "bad.crx:2: expected CRINEX PROG / DATE"},
        BadCrx{3, "     2.11           OBSERVATION DATA    M                   RINEX VERSION / TYPE",
               "bad.crx:3: Compact RINEX 3.0 holds RINEX 3, not version '2.11'"},
        BadCrx{13, "                   3", "bad.crx:13: epoch line difference before the first full epoch line"},
        BadCrx{15, "3&20000000000 3&1050x0000000 3&45000 &515", "bad.crx:15: not a number in field '3&1050x0000000'"},
        BadCrx{15, "3&20000000000 12&105000000000", "bad.crx:15: arc order '12' out of range 1..9"},
        BadCrx{15, "3&20000000000 0&105000000000", "bad.crx:15: arc order '0' out of range 1..9"},
        BadCrx{15, "3&99999999999999", "bad.crx:15: value at column 1 out of F14.3"},
        BadCrx{18, "3&9223372036854775807", "bad.crx:18: not a number"},
        BadCrx{24, "5", "bad.crx:24: a difference with no arc to continue"},
        BadCrx{19, "                   3                              E1x", "bad.crx:19: bad satellite 'E1x'"},
        BadCrx{19, "                   3             9", "bad.crx:19: satellite list shorter than the 9"},
        BadCrx{19, "                   3                              G01", "bad.crx:24: satellite G01 twice"},
        BadCrx{19, "                   3                              J01", "bad.crx:24: satellite of system 'J' without"},
        BadCrx{13, "> 2024 05 03 00 00  0.0000000  6  4      G01G02R03I05", "bad.crx:13: epoch flag 6"},
        BadCrx{13, "> 2024 05 03 00 00  0.0000000  9  4      G01G02R03I05", "bad.crx:13: bad epoch flag"},
        BadCrx{14, "3&1x", "bad.crx:14: not a number in field '3&1x'"},
        BadCrx{15, "3&20000000000 3&105000000000 3&45000 &5x5", "bad.crx:15: bad LLI 'x' at column 34"}));

TEST(Crinex, TruncatedEpochAndEventAreClearErrors) {
  // Cut inside the second epoch (its epoch line is line 19; the satellites end at 24).
  EXPECT_NE(error_of_text(tiny_first(22)).find("bad.crx:22: end of file inside epoch started at line 19 (truncated)"),
            std::string::npos)
      << error_of_text(tiny_first(22));
  // Only the epoch line, no clock line.
  EXPECT_NE(error_of_text(tiny_first(19)).find("end of file inside epoch started at line 19"), std::string::npos);
  // The event announces two records; one is there.
  EXPECT_NE(error_of_text(tiny_first(32)).find("bad.crx:32: end of file inside event record started at line 31"),
            std::string::npos)
      << error_of_text(tiny_first(32));
  // The header ends early.
  EXPECT_NE(error_of_text(tiny_first(2)).find("bad.crx:2: end of file before END OF HEADER"), std::string::npos)
      << error_of_text(tiny_first(2));
}

TEST(Crinex, ReadingOneSystemKeepsItsValuesAsReadingAll) {
  for (const char* name : {"tiny_v3.crx", "tiny_v3.rnx", "KOSG0010.95D", "nya1_v211_mixed.o"}) {
    for (const GnssSystem sys : {GnssSystem::kGps, GnssSystem::kGlonass}) {
      const ObsData all = read_rinex_obs(test_obs(name));
      ObsData want = all;
      for (ObsEpoch& e : want.epochs) std::erase_if(e.sats, [&](const SatObs& s) { return s.sat.system != sys; });
      const ObsData one = read_rinex_obs(test_obs(name), SystemSet::only(sys));
      ASSERT_EQ(one.epochs.size(), want.epochs.size()) << name;
      expect_same(one, want);
      EXPECT_EQ(one.skipped_records, all.skipped_records) << name;
    }
  }
}

TEST(Crinex, Version1BlankSatelliteLetterIsTheFileSystem) {
  const std::string text =
      "1.0                 COMPACT RINEX FORMAT                    CRINEX VERS   / TYPE\n"
      "hand-made                               27-Nov-26 00:00     CRINEX PROG / DATE\n"
      "     2.11           OBSERVATION DATA    R (GLONASS)         RINEX VERSION / TYPE\n"
      "     2    C1    L1                                          # / TYPES OF OBSERV\n"
      "                                                            END OF HEADER\n"
      "&24 05 03 00 00  0.0000000  0  1 05\n"
      "\n"
      "3&20000000000 3&105000000000 &5\n"
      "                3\n"
      "\n"
      "1000 -2000\n";
  for (const SystemSet systems : {SystemSet::all(), SystemSet::only(GnssSystem::kGlonass)}) {
    std::istringstream in(text);
    const ObsData d = read_rinex_obs(in, "glo.crx", systems);
    ASSERT_EQ(d.epochs.size(), 2u);
    ASSERT_EQ(d.epochs[1].sats.size(), 1u);
    EXPECT_EQ(d.epochs[1].sats[0].sat, SatId(GnssSystem::kGlonass, 5));
    EXPECT_DOUBLE_EQ(d.epochs[1].sats[0].get(0)->value, 20000001.0);
    EXPECT_DOUBLE_EQ(d.epochs[1].sats[0].get(1)->value, 104999998.0);
    EXPECT_EQ(d.epochs[1].sats[0].get(0)->ssi, 5);  // flags kept from the first epoch
    EXPECT_DOUBLE_EQ(d.epochs[1].t - d.epochs[0].t, 30.0);
  }
  std::istringstream in(text);
  EXPECT_TRUE(read_rinex_obs(in, "glo.crx", SystemSet::only(GnssSystem::kGps)).epochs[1].sats.empty());
}
