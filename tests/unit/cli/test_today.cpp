// SPDX-License-Identifier: Apache-2.0
// Issue 12: a run on today's date from the 2022 data that ship carries
// today's date and time in every output: NMEA date/time, UBX NAV-PVT UTC,
// NAV-TIMEUTC with its validity flags, NAV-SOL's GPS week, today's leap
// seconds (18 s; the 2022 header's count is not carried over).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "cli_test_util.hpp"

using namespace gnssemu::cli;
using namespace gnssemu::cli::test;

namespace today_test {

namespace {

// 2026-11-24 10:00:00 GPST = 09:59:42 UTC, week 2446 (Tuesday).
constexpr int kWeek = 2446;
constexpr double kTow0 = 2.0 * 86400.0 + 36000.0;

struct Ubx {
  uint8_t cls, id;
  std::string payload;
};

std::vector<Ubx> ubx_frames(const std::string& bytes) {
  std::vector<Ubx> out;
  for (std::size_t i = 0; i + 8 <= bytes.size();) {
    if (static_cast<uint8_t>(bytes[i]) != 0xB5 || static_cast<uint8_t>(bytes[i + 1]) != 0x62) {
      ++i;
      continue;
    }
    const std::size_t len = static_cast<uint8_t>(bytes[i + 4]) | static_cast<uint8_t>(bytes[i + 5]) << 8;
    out.push_back({static_cast<uint8_t>(bytes[i + 2]), static_cast<uint8_t>(bytes[i + 3]), bytes.substr(i + 6, len)});
    i += 8 + len;
  }
  return out;
}

template <class T>
T at(const std::string& p, std::size_t off) {
  T v;
  std::memcpy(&v, p.data() + off, sizeof v);
  return v;
}

}  // namespace

TEST(Today, OutputsCarryTodaysDateTimeWeekAndLeapSeconds) {
  TempDir dir;
  const std::string cfg = dir.write(
      "c.toml", config_text(nav_path("brdc0010.22n"),
                            "[[output]]\nname = \"log\"\ntype = \"file\"\npath = \"" + dir.file("unused.log") +
                                "\"\nubx_messages = [\"NAV-PVT\", \"NAV-SOL\", \"NAV-TIMEUTC\"]\n"
                                "sentences = [\"RMC\", \"GGA\", \"ZDA\"]\n"));
  char truth[256];
  std::snprintf(truth, sizeof truth,
                "gps_week,tow_s,lat_deg,lon_deg,height_m\n%d,%.1f,48.8738,2.2950,100.0\n%d,%.1f,48.8738,2.2950,100.0\n",
                kWeek, kTow0, kWeek, kTow0 + 60.0);
  const std::string t = dir.write("t.csv", truth);
  const CliResult r = run({"batch", "--config", cfg, "--truth", t, "--nmea", dir.file("o.nmea"), "--ubx",
                           dir.file("o.ubx")});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.err.find("nav data moved +1788 days"), std::string::npos) << r.err;
  // NMEA: the last epoch, 10:01:00 GPST = 10:00:42 UTC on 24 Nov 2026.
  const std::string nmea = read_file(dir.file("o.nmea"));
  EXPECT_NE(nmea.find("$GPRMC,100042.00,A,"), std::string::npos);
  EXPECT_NE(nmea.find(",241126,"), std::string::npos);
  EXPECT_NE(nmea.find("$GPZDA,100042.00,24,11,2026,"), std::string::npos);
  EXPECT_NE(nmea.find("$GPGGA,100042.00,4852.4"), std::string::npos);  // a fix, not an empty GGA
  // UBX of the last epoch.
  const std::vector<Ubx> frames = ubx_frames(read_file(dir.file("o.ubx")));
  const Ubx *pvt = nullptr, *sol = nullptr, *utc = nullptr;
  for (const Ubx& f : frames) {
    if (f.cls == 0x01 && f.id == 0x07) pvt = &f;
    if (f.cls == 0x01 && f.id == 0x06) sol = &f;
    if (f.cls == 0x01 && f.id == 0x21) utc = &f;
  }
  ASSERT_TRUE(pvt && sol && utc);
  EXPECT_EQ(at<uint32_t>(pvt->payload, 0), static_cast<uint32_t>((kTow0 + 60.0) * 1000.0));  // iTOW, GPS
  EXPECT_EQ(at<uint16_t>(pvt->payload, 4), 2026);
  EXPECT_EQ(pvt->payload[6], 11);
  EXPECT_EQ(pvt->payload[7], 24);
  EXPECT_EQ(pvt->payload[8], 10);
  EXPECT_EQ(pvt->payload[9], 0);
  EXPECT_EQ(pvt->payload[10], 42);                         // UTC = GPS - 18 s
  EXPECT_EQ(pvt->payload[11] & 0x07, 0x07);                // validDate, validTime, fullyResolved
  EXPECT_EQ(pvt->payload[20], 3);                          // 3D fix
  EXPECT_EQ(at<int16_t>(sol->payload, 8), kWeek);          // NAV-SOL week
  EXPECT_EQ(at<uint16_t>(utc->payload, 12), 2026);         // NAV-TIMEUTC year
  EXPECT_EQ(utc->payload[18], 42);                         // sec
  EXPECT_EQ(utc->payload[19] & 0x07, 0x07);                // validTOW, validWKN, validUTC
}

}  // namespace today_test
