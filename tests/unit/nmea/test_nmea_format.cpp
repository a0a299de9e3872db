// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/protocol/nmea/nmea_format.hpp"

namespace gnssemu::protocol::nmea {
namespace {

// Body of a sentence between '$' and '*'.
std::string body(SentenceWriter& w) {
  std::string s(w.finish());
  return s.substr(1, s.size() - 6);
}

TEST(NmeaChecksum, KnownSentencesFromReference) {
  // u-blox M8 examples (UBXEX in shared/reference/nmea0183.md).
  EXPECT_TRUE(nmea_checksum_ok("$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B"));
  EXPECT_TRUE(nmea_checksum_ok("$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57\r\n"));
  EXPECT_TRUE(nmea_checksum_ok("$GPGST,082356.00,1.8,,,,1.7,1.3,2.2*7e"));
  EXPECT_EQ(nmea_checksum("GPGSV,1,1,00"), 0x79);
  EXPECT_FALSE(nmea_checksum_ok("$GPGST,082356.00,1.8,,,,1.7,1.3,2.3*7E"));
  EXPECT_FALSE(nmea_checksum_ok("$GPGST,082356.00*"));
  EXPECT_FALSE(nmea_checksum_ok("GPGSV,1,1,00*79"));
  EXPECT_FALSE(nmea_checksum_ok("$GPGSV,1,1,00*7G"));
  EXPECT_FALSE(nmea_checksum_ok(""));
}

TEST(NmeaWriter, FinishAddsUpperCaseChecksumAndCrLf) {
  SentenceWriter w("GPGSV");
  w.integer(1, 1);
  w.integer(1, 1);
  w.integer(0, 2);
  EXPECT_EQ(std::string(w.finish()), "$GPGSV,1,1,00*79\r\n");
  SentenceWriter v("GPVTG");
  for (int i = 0; i < 8; ++i) v.empty();
  v.character('N');
  EXPECT_EQ(std::string(v.finish()), "$GPVTG,,,,,,,,,N*30\r\n");
}

TEST(NmeaWriter, FixedRoundsHalfAwayAndNeverPrintsMinusZero) {
  SentenceWriter w("X");
  w.fixed(499.64, 1);
  w.fixed(0.25, 1);     // exact half -> away from zero
  w.fixed(-0.04, 1);    // rounds to 0: no sign
  w.fixed(-0.06, 1);
  w.fixed(0.0045, 3);
  w.fixed(7.0, 2, 3);
  w.fixed(std::numeric_limits<double>::quiet_NaN(), 2);
  w.fixed(std::numeric_limits<double>::infinity(), 2);
  w.fixed(1e30, 2);
  w.fixed(12.5, 0);
  EXPECT_EQ(body(w), "X,499.6,0.3,0.0,-0.1,0.005,007.00,,,,13");
}

TEST(NmeaWriter, LatitudeLongitudeCarryAndHemispheres) {
  SentenceWriter w("X");
  w.latitude(47.285233166);              // 47 deg 17.11399 min
  w.longitude(8.565265);                 // 8 deg 33.91590 min
  w.latitude(-(45.0 + 59.9999996 / 60));  // minutes round to 60.00000 -> 46 deg
  w.longitude(-(121.0 + 59.999996 / 60)); // -> 122 deg 00.00000 W
  w.latitude(90.0);
  w.latitude(-90.0);
  w.longitude(180.0);
  w.longitude(-180.0);
  w.longitude(-1e-10);                   // rounds to zero: E, not W
  w.latitude(std::nan(""));
  EXPECT_EQ(body(w),
            "X,4717.11399,N,00833.91590,E,4600.00000,S,12200.00000,W,9000.00000,N,9000.00000,S,"
            "18000.00000,E,18000.00000,W,00000.00000,E,,");
}

TEST(NmeaWriter, TimeAndDate) {
  SentenceWriter w("X");
  w.time_of_day(9, 27, 5, 3);
  w.date_ddmmyy(9, 12, 2002);
  w.date_ddmmyy(1, 1, 2100);
  EXPECT_EQ(body(w), "X,092705.03,091202,010100");
}

TEST(NmeaWriter, OverflowIsCutNotCorrupt) {
  SentenceWriter w("GPTXT");
  for (int i = 0; i < 100; ++i) w.text("0123456789");
  EXPECT_TRUE(w.overflowed());
  const std::string s(w.finish());
  EXPECT_LE(s.size(), 160u);
  EXPECT_TRUE(nmea_checksum_ok(s));
  EXPECT_EQ(s.substr(s.size() - 2), "\r\n");
}

}  // namespace
}  // namespace gnssemu::protocol::nmea
