// SPDX-License-Identifier: Apache-2.0
// gnssemu batch: the daemon's code path over static and moving truth on real
// broadcast ephemerides; error statistics, NMEA validity, determinism.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli_test_util.hpp"
#include "config/config.hpp"
#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "tools/gnssemu/batch/batch.hpp"
#include "tools/gnssemu/batch/truth_csv.hpp"

using namespace gnssemu;
using namespace gnssemu::cli::test;

namespace {

// 2022-01-01 (brdc0010.22n), Paris.
constexpr int kWeek = 2190;
constexpr double kTow0 = 522000.0;

/// East at speed_m_s along the parallel, samples every step_s, ECEF with ENU velocity.
std::string moving_truth(double duration_s, double step_s, double speed_m_s) {
  std::ostringstream s;
  s.precision(12);
  s << "gps_week,tow_s,x_m,y_m,z_m,ve_m_s,vn_m_s,vu_m_s\n";
  const Lla start{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};
  const double r_parallel = geo::ecef_from_lla(start).x / std::cos(start.lon_rad);
  for (double t = 0.0; t <= duration_s + 1e-9; t += step_s) {
    const Lla p{start.lat_rad, start.lon_rad + speed_m_s * t / r_parallel, start.height_m};
    const Ecef e = geo::ecef_from_lla(p);
    s << kWeek << ',' << kTow0 + t << ',' << e.x << ',' << e.y << ',' << e.z << ',' << speed_m_s << ",0,0\n";
  }
  return s.str();
}

bool nmea_checksum_ok(const std::string& line) {
  if (line.size() < 6 || line[0] != '$') return false;
  const std::size_t star = line.rfind('*');
  if (star == std::string::npos || star + 3 != line.size()) return false;
  unsigned sum = 0;
  for (std::size_t i = 1; i < star; ++i) sum ^= static_cast<unsigned char>(line[i]);
  return std::strtoul(line.substr(star + 1).c_str(), nullptr, 16) == sum;
}

struct NmeaStats {
  int lines = 0, bad = 0, gga = 0, rmc = 0;
  double max_speed_knots = 0.0, min_speed_knots = 1e9;
};

NmeaStats check_nmea(const std::string& text) {
  NmeaStats st;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find("\r\n", pos);
    if (end == std::string::npos) {
      ++st.bad;  // unterminated tail
      break;
    }
    const std::string line = text.substr(pos, end - pos);
    pos = end + 2;
    ++st.lines;
    if (!nmea_checksum_ok(line) || line.size() + 2 > 82) {
      ++st.bad;
      ADD_FAILURE() << "bad NMEA line: " << line;
    }
    if (line.compare(3, 3, "GGA") == 0) ++st.gga;
    if (line.compare(3, 3, "RMC") == 0) {
      ++st.rmc;
      std::vector<std::string> fields = split_csv_line(line);
      if (fields.size() > 7 && !fields[7].empty()) {
        const double knots = std::stod(fields[7]);
        st.max_speed_knots = std::max(st.max_speed_knots, knots);
        st.min_speed_knots = std::min(st.min_speed_knots, knots);
      }
    }
  }
  return st;
}

struct ErrorStats {
  int rows = 0, fixes = 0;
  double h_rms = 0.0, v_rms = 0.0;
};

ErrorStats error_stats(const Csv& e) {
  ErrorStats s;
  for (std::size_t i = 0; i < e.rows.size(); ++i) {
    ++s.rows;
    if (e.cell(i, "e_m").empty()) continue;
    ++s.fixes;
    s.h_rms += std::pow(e.num(i, "e_m"), 2) + std::pow(e.num(i, "n_m"), 2);
    s.v_rms += std::pow(e.num(i, "u_m"), 2);
  }
  if (s.fixes > 0) {
    s.h_rms = std::sqrt(s.h_rms / s.fixes);
    s.v_rms = std::sqrt(s.v_rms / s.fixes);
  }
  return s;
}

}  // namespace

TEST(Batch, StaticReceiverDefaultErrorModel) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("truth.csv", static_truth(600.0));
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--nmea", dir.file("out.nmea"), "--errors",
                           dir.file("err.csv")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  // The receiver powers on at the first epoch with a hot start: its first
  // fix comes one epoch later (an M8 hot start takes 1 s).
  EXPECT_NE(r.err.find("epochs 601  fixes 600 (99.8%)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("horizontal error  rms"), std::string::npos) << r.err;

  const Csv e = parse_csv(read_file(dir.file("err.csv")));
  ASSERT_EQ(e.header, (std::vector<std::string>{"gps_week", "tow_s", "fix_type", "nsat", "e_m", "n_m", "u_m", "hdop",
                                                "vdop", "pdop", "hacc_m", "vacc_m"}));
  ASSERT_EQ(e.rows.size(), 601u);
  EXPECT_EQ(e.cell(0, "tow_s"), "522000.000");
  EXPECT_EQ(e.cell(600, "tow_s"), "522600.000");
  EXPECT_EQ(e.cell(0, "fix_type"), "0");
  for (std::size_t i = 1; i < e.rows.size(); ++i) {
    EXPECT_EQ(e.cell(i, "gps_week"), "2190");
    EXPECT_EQ(e.cell(i, "fix_type"), "3");
    EXPECT_GE(e.num(i, "nsat"), 6);
    const double h = e.num(i, "hdop"), v = e.num(i, "vdop"), p = e.num(i, "pdop");
    EXPECT_NEAR(p * p, h * h + v * v, 0.02 * p);  // printed to 0.01
  }
  // Default model: 1.2 m orbit/clock (Gauss-Markov, 30 min) + 0.3 m white per
  // satellite; with HDOP ~1 the horizontal error is metre-level, not zero.
  const ErrorStats s = error_stats(e);
  EXPECT_EQ(s.fixes, 600);
  EXPECT_GT(s.h_rms, 0.1);
  EXPECT_LT(s.h_rms, 6.0);
  EXPECT_GT(s.v_rms, 0.1);
  EXPECT_LT(s.v_rms, 12.0);

  const NmeaStats n = check_nmea(read_file(dir.file("out.nmea")));
  EXPECT_EQ(n.bad, 0);
  EXPECT_EQ(n.gga, 601);
  EXPECT_EQ(n.rmc, 601);
  EXPECT_GT(n.lines, 601 * 5);  // RMC VTG GGA GSA GSV(2-3) GLL per epoch
}

TEST(Batch, SummaryMatchesTheErrorsFile) {
  TempDir dir;
  const std::string nav = nav_path("brdc0010.22n");
  config::Config cfg = config::parse_config(config_text(nav), "c.toml", dir.file(""));
  std::istringstream truth_in(static_truth(300.0));
  const world::TruthTrack track(cli::read_truth_csv(truth_in, "truth.csv"));
  std::ostringstream errors;
  const cli::BatchSummary sum = cli::run_batch(cfg, orbit::read_rinex_nav(nav), track, nullptr, &errors);
  const ErrorStats s = error_stats(parse_csv(errors.str()));
  EXPECT_EQ(sum.epochs, 301);
  EXPECT_EQ(sum.fixes, s.fixes);
  EXPECT_EQ(sum.fixes_3d, s.fixes);
  EXPECT_NEAR(sum.h_rms_m, s.h_rms, 1e-3);
  EXPECT_NEAR(sum.v_rms_m, s.v_rms, 1e-3);
  EXPECT_GE(sum.h_95_m, sum.h_rms_m * 0.8);
  EXPECT_LE(sum.h_95_m, sum.h_max_m);
  EXPECT_LE(sum.v_95_m, sum.v_max_m);
}

TEST(Batch, MovingReceiverInterpolatedTruthAndRate) {
  TempDir dir;
  // 5 Hz epochs from truth sampled every 2 s: the receiver sees interpolated truth.
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n"), "[receiver]\nrate_hz = 5.0\n"));
  const std::string truth = dir.write("truth.csv", moving_truth(120.0, 2.0, 20.0));
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--nmea", dir.file("out.nmea"), "--errors",
                           dir.file("err.csv")});
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv e = parse_csv(read_file(dir.file("err.csv")));
  ASSERT_EQ(e.rows.size(), 601u);  // 120 s at 5 Hz, both ends included
  EXPECT_EQ(e.cell(1, "tow_s"), "522000.200");
  const ErrorStats s = error_stats(e);
  // A fix from the hot start's first second on (5 epochs at 5 Hz).
  EXPECT_GE(s.fixes, 596);
  for (std::size_t i = 5; i < e.rows.size(); ++i) EXPECT_EQ(e.cell(i, "fix_type"), "3") << i;
  // Truth moves 2400 m; errors stay metre-level, so interpolation and ENU are right.
  EXPECT_LT(s.h_rms, 6.0);
  EXPECT_LT(s.v_rms, 12.0);
  const NmeaStats n = check_nmea(read_file(dir.file("out.nmea")));
  EXPECT_EQ(n.bad, 0);
  EXPECT_EQ(n.gga, 601);
  // 20 m/s = 38.88 kn; Doppler velocity noise is cm/s.
  EXPECT_NEAR(n.min_speed_knots, 38.88, 1.0);
  EXPECT_NEAR(n.max_speed_knots, 38.88, 1.0);
}

TEST(Batch, DeterministicForASeedAndErrorsToStdout) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write("truth.csv", static_truth(60.0));
  const CliResult a = run({"batch", "--config", cfg, "--truth", truth, "--errors", "-"});
  const CliResult b = run({"batch", "--config", cfg, "--truth", truth, "--errors", "-"});
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(parse_csv(a.out).rows.size(), 61u);
  EXPECT_EQ(a.out, b.out);
  const std::string cfg2 =
      dir.write("c2.toml", config_text(nav_path("brdc0010.22n"), "[receiver]\nseed = 2\n"));
  const CliResult c = run({"batch", "--config", cfg2, "--truth", truth, "--errors", "-"});
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(a.out, c.out);
}

TEST(Batch, TruthBetweenEpochsIsAnError) {
  TempDir dir;
  const std::string cfg = dir.write("c.toml", config_text(nav_path("brdc0010.22n")));
  const std::string truth = dir.write(
      "truth.csv", "gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,522000.2,48.8738,2.295,100\n"
                   "2190,522000.7,48.8738,2.295,100\n");
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth});
  EXPECT_EQ(r.status, cli::kExitBadInput);
  EXPECT_NE(r.err.find("truth spans no epoch at 1 Hz"), std::string::npos) << r.err;
}

TEST(Batch, UbxStreamFollowsTheFirstPortsMessageRates) {
  TempDir dir;
  const std::string cfg = dir.write(
      "c.toml", config_text(nav_path("brdc0010.22n"),
                            "[[output]]\nname = \"a\"\ntype = \"pty\"\npath = \"/tmp/gnssemu-test/a\"\n"
                            "ubx_messages = [\"NAV-PVT\", \"NAV-SAT\"]\nsentences = [\"GGA\", \"GSV\"]\n"
                            "rates = { NAV-SAT = 5, GSV = 2 }\n"));
  const std::string truth = dir.write("truth.csv", static_truth(9.0));
  const std::string ubx_path = dir.file("out.ubx"), nmea_path = dir.file("out.nmea");
  const CliResult r = run({"batch", "--config", cfg, "--truth", truth, "--ubx", ubx_path, "--nmea", nmea_path});
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(ubx_path, std::ios::binary);
  const std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::map<std::string, int> count;
  for (std::size_t i = 0; i + 8 <= b.size();) {
    ASSERT_EQ(static_cast<unsigned char>(b[i]), 0xB5u) << "byte " << i;
    ASSERT_EQ(static_cast<unsigned char>(b[i + 1]), 0x62u) << "byte " << i;
    const std::size_t len = static_cast<unsigned char>(b[i + 4]) | static_cast<std::size_t>(static_cast<unsigned char>(b[i + 5])) << 8;
    ASSERT_LE(i + 8 + len, b.size());
    uint8_t ck_a = 0, ck_b = 0;
    for (std::size_t k = i + 2; k < i + 6 + len; ++k) {
      ck_a = static_cast<uint8_t>(ck_a + static_cast<unsigned char>(b[k]));
      ck_b = static_cast<uint8_t>(ck_b + ck_a);
    }
    EXPECT_EQ(ck_a, static_cast<unsigned char>(b[i + 6 + len]));
    EXPECT_EQ(ck_b, static_cast<unsigned char>(b[i + 7 + len]));
    ++count[std::to_string(static_cast<unsigned char>(b[i + 2])) + "-" + std::to_string(static_cast<unsigned char>(b[i + 3]))];
    i += 8 + len;
  }
  EXPECT_EQ(count["1-7"], 10);   // NAV-PVT every epoch, 10 epochs
  EXPECT_EQ(count["1-53"], 2);   // NAV-SAT at rate 5: epochs 1 and 6
  EXPECT_EQ(count.size(), 2u);
  std::ifstream nin(nmea_path);
  int gga = 0, gsv_groups = 0;
  for (std::string line; std::getline(nin, line);) {
    if (line.rfind("$GPGGA", 0) == 0) ++gga;
    // $GPGSV,<total>,<number>,...: one group per epoch it is due in.
    if (line.rfind("$GPGSV,", 0) == 0 && line.substr(line.find(',', 7) + 1, 2) == "1,") ++gsv_groups;
  }
  EXPECT_EQ(gga, 10);
  EXPECT_EQ(gsv_groups, 5);  // rate 2: epochs 1, 3, 5, 7, 9
}
