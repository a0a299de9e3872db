// SPDX-License-Identifier: Apache-2.0
// RINEX observation reader: the real NYA1 (RINEX 3.05, 90 min and a gzip
// full day) and LARM (3.02) files, RINEX 2.11 variants derived from NYA1
// (tests/data/obs/make_variants.py), event and cycle-slip records, bad files.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "core/common/error.hpp"
#include "core/observation/rinex_obs.hpp"

using namespace gnssemu;
using namespace gnssemu::observation;

namespace {

std::string obs(const std::string& name) { return std::string(GNSSEMU_TEST_DATA) + "/obs/" + name; }
std::string bad(const std::string& name) { return std::string(GNSSEMU_TEST_DATA) + "/bad/" + name; }

const char* kNya90 = "NYA100NOR_S_20241240000_90M_30S_MO.rnx";
const char* kNyaDay = "NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz";

constexpr GnssSystem kGps = GnssSystem::kGps;

const SatObs* find(const ObsEpoch& e, SatId id) {
  for (const SatObs& s : e.sats)
    if (s.sat == id) return &s;
  return nullptr;
}
const SatObs* find(const ObsEpoch& e, int gps_prn) { return find(e, SatId::gps(gps_prn)); }

/// Satellites of system s in an epoch, file order.
std::vector<const SatObs*> of_system(const ObsEpoch& e, GnssSystem s) {
  std::vector<const SatObs*> out;
  for (const SatObs& x : e.sats)
    if (x.sat.system == s) out.push_back(&x);
  return out;
}
std::size_t count(const ObsData& d, GnssSystem s) {
  std::size_t n = 0;
  for (const ObsEpoch& e : d.epochs) n += of_system(e, s).size();
  return n;
}

/// The error message of reading path, or "" if it read.
std::string error_of(const std::string& path) {
  try {
    read_rinex_obs(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(RinexObs, Nya1NinetyMinutesHeader) {
  const ObsData d = read_rinex_obs(obs(kNya90));
  const ObsHeader& h = d.header;
  EXPECT_DOUBLE_EQ(h.rinex_version, 3.05);
  EXPECT_EQ(h.file_system, 'M');
  EXPECT_EQ(h.marker_name, "NYA1");
  EXPECT_EQ(h.receiver_type, "TRIMBLE NETR9");
  ASSERT_TRUE(h.approx_pos_m.has_value());
  EXPECT_DOUBLE_EQ(h.approx_pos_m->x, 1202434.1303);
  EXPECT_DOUBLE_EQ(h.approx_pos_m->y, 252632.2212);
  EXPECT_DOUBLE_EQ(h.approx_pos_m->z, 6237772.4351);
  ASSERT_EQ(h.types_of(kGps).size(), 16u);  // two header lines (13 + 3)
  EXPECT_EQ(h.type_index(kGps, "C1C"), 0);
  EXPECT_EQ(h.type_index(kGps, "S1C"), 3);
  EXPECT_EQ(h.type_index(kGps, "S5X"), 15);
  EXPECT_EQ(h.type_index(kGps, "C1X"), -1);  // a Galileo type, not GPS
  EXPECT_EQ(h.type_index(GnssSystem::kGalileo, "C1X"), 0);
  EXPECT_EQ(h.types_of(GnssSystem::kGlonass).size(), 20u);
  EXPECT_EQ(h.types_of(GnssSystem::kGalileo).size(), 20u);
  EXPECT_EQ(h.types_of(GnssSystem::kBeiDou).size(), 12u);
  EXPECT_TRUE(h.types_of(GnssSystem::kQzss).empty());
  EXPECT_DOUBLE_EQ(h.interval_s, 30.0);
  ASSERT_TRUE(h.first_obs.has_value());
  EXPECT_EQ(h.first_obs->week(), 2312);  // 2024-05-03 is a Friday of GPS week 2312
  EXPECT_DOUBLE_EQ(h.first_obs->tow_s(), 5 * 86400.0);
  EXPECT_FALSE(h.rcv_clock_offset_applied);
}

TEST(RinexObs, Nya1NinetyMinutesEpochs) {
  const ObsData d = read_rinex_obs(obs(kNya90));
  ASSERT_EQ(d.epochs.size(), 180u);
  EXPECT_EQ(d.skipped_records, 0);
  EXPECT_EQ(d.event_records, 0);
  EXPECT_EQ(count(d, kGps), 2178u);
  // GLONASS, Galileo, BeiDou records: 3994 (counted with awk).
  EXPECT_EQ(count(d, GnssSystem::kGlonass) + count(d, GnssSystem::kGalileo) + count(d, GnssSystem::kBeiDou), 3994u);
  EXPECT_DOUBLE_EQ(d.epochs[1].t - d.epochs[0].t, 30.0);
  EXPECT_DOUBLE_EQ(d.epochs.back().t - d.epochs.front().t, 179 * 30.0);
  EXPECT_EQ(d.epochs[0].line, 43);

  const ObsEpoch& e0 = d.epochs[0];
  ASSERT_EQ(e0.sats.size(), 36u);
  ASSERT_EQ(of_system(e0, kGps).size(), 12u);
  EXPECT_EQ(e0.sats[0].sat, SatId::gps(27));
  EXPECT_EQ(e0.sats[12].sat, SatId(GnssSystem::kGlonass, 15));
  EXPECT_EQ(e0.sats[35].sat, SatId(GnssSystem::kBeiDou, 21));
  const SatObs* g27 = find(e0, 27);
  ASSERT_NE(g27, nullptr);
  ASSERT_NE(g27->get(0), nullptr);
  EXPECT_DOUBLE_EQ(g27->get(0)->value, 22265735.555);
  const ObsValue* l1 = g27->get(1);
  ASSERT_NE(l1, nullptr);
  EXPECT_DOUBLE_EQ(l1->value, 117007388.310);
  EXPECT_EQ(l1->lli, 1);
  EXPECT_EQ(l1->ssi, 8);
  EXPECT_DOUBLE_EQ(g27->get(2)->value, 314.898);
  EXPECT_DOUBLE_EQ(g27->get(3)->value, 45.9);
  // G20 has no C2X in the first epoch: the file writes 0.000 -> missing.
  const SatObs* g20 = find(e0, 20);
  ASSERT_NE(g20, nullptr);
  EXPECT_EQ(g20->get(d.header.type_index(kGps, "C2X")), nullptr);
  EXPECT_NE(g20->get(d.header.type_index(kGps, "C2W")), nullptr);
}

TEST(RinexObs, Nya1FullDayGzip) {
  const ObsData d = read_rinex_obs(obs(kNyaDay));
  ASSERT_EQ(d.epochs.size(), 2880u);
  EXPECT_EQ(d.header.types_of(kGps), (std::vector<std::string>{"C1C", "L1C", "D1C", "S1C"}));
  EXPECT_EQ(count(d, kGps), 33830u);
  EXPECT_DOUBLE_EQ(d.epochs.back().t - d.epochs.front().t, 86370.0);
  // The day file and the 90-minute file hold the same first epoch.
  const ObsData m = read_rinex_obs(obs(kNya90));
  ASSERT_EQ(d.epochs[0].sats.size(), of_system(m.epochs[0], kGps).size());
  for (std::size_t k = 0; k < d.epochs[0].sats.size(); ++k) {
    EXPECT_EQ(d.epochs[0].sats[k].sat, m.epochs[0].sats[k].sat);
    for (int t = 0; t < 4; ++t) {
      ASSERT_NE(d.epochs[0].sats[k].get(t), nullptr);
      EXPECT_EQ(d.epochs[0].sats[k].get(t)->value, m.epochs[0].sats[k].get(t)->value);
    }
  }
}

TEST(RinexObs, Larm302) {
  const ObsData d = read_rinex_obs(obs("LARM0010.22O"));
  EXPECT_DOUBLE_EQ(d.header.rinex_version, 3.02);
  ASSERT_EQ(d.epochs.size(), 4u);
  EXPECT_EQ(d.skipped_records, 0);
  EXPECT_EQ(count(d, kGps), 40u);
  EXPECT_EQ(count(d, GnssSystem::kGlonass), 40u);
  EXPECT_NEAR(d.header.antenna_delta_hen_m.x, 0.19, 1e-12);
  const SatObs* g01 = find(d.epochs[0], 1);
  ASSERT_NE(g01, nullptr);
  EXPECT_DOUBLE_EQ(g01->get(d.header.type_index(kGps, "C1C"))->value, 25256919.479);
  EXPECT_DOUBLE_EQ(g01->get(d.header.type_index(kGps, "S1C"))->value, 41.25);
  EXPECT_EQ(d.epochs[0].t.week(), 2190);
  EXPECT_DOUBLE_EQ(d.epochs[0].t.tow_s(), 6 * 86400.0);
}

TEST(RinexObs, Rinex211MixedMatchesRinex3Source) {
  const ObsData v2 = read_rinex_obs(obs("nya1_v211_mixed.o"));
  const ObsData v3 = read_rinex_obs(obs(kNya90));
  EXPECT_DOUBLE_EQ(v2.header.rinex_version, 2.11);
  EXPECT_EQ(v2.header.types_of(kGps), (std::vector<std::string>{"C1C", "L1C", "D1C", "S1C", "C2W", "L2W"}));
  // RINEX 2 P2/L2 are the P-code signals on GLONASS (C2P, L2P), as in the RINEX 3 source.
  EXPECT_EQ(v2.header.types_of(GnssSystem::kGlonass),
            (std::vector<std::string>{"C1C", "L1C", "D1C", "S1C", "C2P", "L2P"}));
  ASSERT_TRUE(v2.header.leap_seconds.has_value());
  EXPECT_EQ(*v2.header.leap_seconds, 18);
  ASSERT_EQ(v2.epochs.size(), 4u);
  EXPECT_EQ(v2.event_records, 1);       // flag 4 with two header records
  EXPECT_EQ(v2.cycle_slip_records, 1);  // flag 6 with two satellites
  EXPECT_EQ(v2.header.marker_name, "NYA1 AFTER EVENT");
  for (std::size_t k = 0; k < 4; ++k) {
    const ObsEpoch& a = v2.epochs[k];
    const ObsEpoch& b = v3.epochs[k];
    EXPECT_EQ(a.t, b.t);
    for (const GnssSystem sys : {kGps, GnssSystem::kGlonass}) {
      const std::vector<const SatObs*> as = of_system(a, sys), bs = of_system(b, sys);
      ASSERT_EQ(as.size(), bs.size()) << "epoch " << k;
      const std::vector<std::string>& codes = v2.header.types_of(sys);
      for (std::size_t s = 0; s < as.size(); ++s) {
        EXPECT_EQ(as[s]->sat, bs[s]->sat);
        for (std::size_t t = 0; t < codes.size(); ++t) {
          const ObsValue* x = as[s]->get(static_cast<int>(t));
          const ObsValue* y = bs[s]->get(v3.header.type_index(sys, codes[t]));
          ASSERT_EQ(x == nullptr, y == nullptr) << codes[t];
          if (x && t < 4) {
            EXPECT_EQ(x->lli, y->lli);
            EXPECT_EQ(x->ssi, y->ssi);
          }
          if (x) {
            EXPECT_EQ(x->value, y->value) << codes[t];
          }
        }
      }
    }
  }
  // More than 12 satellites (G and R) on each epoch: continuation lines.
  EXPECT_GT(v2.epochs[0].sats.size(), 12u);
  EXPECT_EQ(count(v2, GnssSystem::kGlonass), 9u * 4u);
  EXPECT_EQ(v2.skipped_records, 0);
}

TEST(RinexObs, Rinex3EventAndCycleSlipRecordsSkipped) {
  const ObsData d = read_rinex_obs(obs("nya1_v305_events.rnx"));
  const ObsData src = read_rinex_obs(obs(kNya90));
  ASSERT_EQ(d.epochs.size(), 3u);
  EXPECT_EQ(d.event_records, 1);
  EXPECT_EQ(d.cycle_slip_records, 1);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(d.epochs[k].t, src.epochs[k].t);
    EXPECT_EQ(d.epochs[k].sats.size(), src.epochs[k].sats.size());
  }
}

TEST(RinexObs, RinexTwoFromStreamWithEventFlagHeaderTypes) {
  // A flag-4 event that changes the observation types: later epochs use the new list.
  const std::string text =
      "     2.11           OBSERVATION DATA    G (GPS)             RINEX VERSION / TYPE\n"
      "     2    C1    S1                                          # / TYPES OF OBSERV\n"
      "                                                            END OF HEADER\n"
      " 24  5  3  0  0  0.0000000  0  1G27\n"
      "  22265735.555          45.900\n"
      "                            4  1\n"
      "     1    C1                                                # / TYPES OF OBSERV\n"
      " 24  5  3  0  0 30.0000000  1  1 27\n"
      "  22264004.031\n";
  std::istringstream in(text);
  const ObsData d = read_rinex_obs(in, "inline.o");
  ASSERT_EQ(d.epochs.size(), 2u);
  EXPECT_EQ(d.epochs[1].flag, 1);
  EXPECT_EQ(d.header.types_of(kGps), std::vector<std::string>{"C1C"});
  ASSERT_EQ(d.epochs[1].sats.size(), 1u);  // blank system letter = GPS in a G file
  EXPECT_EQ(d.epochs[1].sats[0].sat, SatId::gps(27));
  EXPECT_DOUBLE_EQ(d.epochs[1].sats[0].get(0)->value, 22264004.031);
  EXPECT_DOUBLE_EQ(d.epochs[0].sats[0].get(1)->value, 45.9);
}

struct BadCase {
  const char* file;
  const char* expect;  // file:line and a reason
};

class RinexObsBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(RinexObsBad, ClearErrorWithFileAndLine) {
  const BadCase& c = GetParam();
  const std::string msg = error_of(bad(c.file));
  ASSERT_FALSE(msg.empty()) << c.file << " was accepted";
  EXPECT_NE(msg.find(c.file), std::string::npos) << msg;
  EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    Files, RinexObsBad,
    ::testing::Values(BadCase{"obs_v3_bad_epoch.rnx", ":43: date/time out of range"},
                      BadCase{"obs_v3_truncated.rnx", ":53: end of file inside epoch record started at line 43"},
                      BadCase{"obs_v3_bad_value.rnx", ":44: unparsable number '222x5735.555'"},
                      BadCase{"obs_v3_no_end_of_header.rnx", "end of file before END OF HEADER"},
                      BadCase{"obs_v3_glonass_time.rnx", ":18: time system 'GLO' not supported"},
                      BadCase{"obs_v3_bad_flag.rnx", ":43: epoch flag 7 outside 0..6"},
                      BadCase{"obs_v3_no_types.rnx", "no observation types in the header"},
                      BadCase{"obs_v4_version.rnx", ":1: unsupported RINEX version 4.01"},
                      BadCase{"obs_type_nav.rnx", ":1: not an observation file (type 'N')"},
                      BadCase{"obs_v2_short_sat_list.o", ":13: satellite list shorter than the 21 announced"},
                      BadCase{"obs_v2_bad_lli.o", ":14: bad LLI 'x' at column 15"}),
    [](const ::testing::TestParamInfo<BadCase>& p) {
      std::string n = p.param.file;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(RinexObs, MissingFileAndEmptyStream) {
  EXPECT_NE(error_of(obs("no_such_file.rnx")).find("no_such_file.rnx: cannot open"), std::string::npos);
  std::istringstream empty("");
  EXPECT_THROW(read_rinex_obs(empty, "empty"), Error);
}

// Issue 13: a gzip of newlines was read whole and split before its first
// line was checked (1.3 GB RSS). The reader streams and checks line 1 first.
TEST(RinexObs, GzipOfNewlinesIsRefusedAtTheFirstLine) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("gnssemu-obs-" + std::to_string(::getpid()) + "-bomb.rnx.gz"))
                               .string();
  gzFile f = gzopen(path.c_str(), "wb9");
  const std::string chunk(1u << 20, '\n');
  for (int i = 0; i < 20; ++i) gzwrite(f, chunk.data(), static_cast<unsigned>(chunk.size()));
  gzclose(f);
  try {
    (void)read_rinex_obs(path);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ":1: first line is not 'RINEX VERSION / TYPE'");
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  EXPECT_LT(u.ru_maxrss / 1024, 200);  // MB
  std::filesystem::remove(path);
}
