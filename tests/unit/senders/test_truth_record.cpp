// SPDX-License-Identifier: Apache-2.0
// Binary truth records: the sender's encoder (tools/senders/truth_record.hpp)
// against the daemon's parser, a pinned golden record, and every way a
// record can be bad (docs/truth-protocol.md §Binary record).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "daemon/truth/truth_packet.hpp"
#include "tools/senders/truth_record.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;
using senders::PositionFrame;
using senders::TruthRecord;
using senders::VelocityFrame;

namespace {

const Lla kOrigin{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The worked example of docs/truth-protocol.md: ENU position and velocity,
// attitude (heading east) and GPS time.
constexpr const char* kGoldenHex =
    "f747545201368e0865676f000000000000000000000000000000000000000000"
    "0000000000000000000000000000000000000000000000000000000000000000"
    "000000000000000000000000000029400000000002a41f410000000000005e40"
    "00000000000054c0000000000000f83f00000000000014400000000000000000"
    "000000000000000000000000000000000000000000000000182d4454fb21f93f";

TruthRecord golden_record() {
  TruthRecord r;
  r.vehicle = "ego";
  r.sim_time_s = 12.5;
  r.position_frame = PositionFrame::kEnu;
  r.position = {120.0, -80.0, 1.5};
  r.velocity_frame = VelocityFrame::kEnu;
  r.vel_m_s = {5.0, 0.0, 0.0};
  r.has_attitude = true;
  r.attitude_rad = {0.0, 0.0, kPi / 2.0};
  r.has_gps_time = true;
  r.gps_week = 2190;
  r.gps_tow_s = 518400.5;
  return r;
}

const geo::LocalFrame& frame() {
  static const geo::LocalFrame f(kOrigin);
  return f;
}

std::string encode(const TruthRecord& r) {
  senders::RecordBytes b{};
  EXPECT_TRUE(senders::encode_truth_record(r, b));
  return std::string(reinterpret_cast<const char*>(b.data()), b.size());
}

ParseResult parse(const std::string& d) { return parse_truth_packet(d, frame()); }

std::string hex(const std::string& d) {
  std::string out;
  char buf[3];
  for (unsigned char c : d) {
    std::snprintf(buf, sizeof buf, "%02x", c);
    out += buf;
  }
  return out;
}

void expect_drop(const std::string& d, DropReason reason, const std::string& what) {
  const ParseResult r = parse(d);
  EXPECT_FALSE(r.ok) << what;
  EXPECT_STREQ(drop_reason_name(r.reason), drop_reason_name(reason)) << what << " -> " << r.detail;
  EXPECT_FALSE(r.detail.empty()) << what;
}

// Overwrites the little-endian double at byte offset off.
void put_f64(std::string& d, std::size_t off, double v) {
  const auto b = std::bit_cast<uint64_t>(v);
  for (std::size_t i = 0; i < 8; ++i) d[off + i] = static_cast<char>(b >> (8 * i));
}

uint64_t bits(double v) { return std::bit_cast<uint64_t>(v); }

void expect_same_bits(const Vec3& a, const Vec3& b, const std::string& what) {
  EXPECT_EQ(bits(a.x), bits(b.x)) << what;
  EXPECT_EQ(bits(a.y), bits(b.y)) << what;
  EXPECT_EQ(bits(a.z), bits(b.z)) << what;
}

// The same record as a JSON datagram; %.17g round-trips every double.
std::string to_json(const TruthRecord& r) {
  static const char* const kPos[3][4] = {{"lla", "lat_deg", "lon_deg", "height_m"},
                                         {"ecef", "x_m", "y_m", "z_m"},
                                         {"enu", "e_m", "n_m", "u_m"}};
  static const char* const kVel[3][4] = {{"", "", "", ""},
                                         {"vel_enu", "e_m_s", "n_m_s", "u_m_s"},
                                         {"vel_ecef", "x_m_s", "y_m_s", "z_m_s"}};
  char buf[512];
  const auto* p = kPos[static_cast<int>(r.position_frame)];
  std::snprintf(buf, sizeof buf,
                R"({"version":1,"vehicle":"%s","sim_time_s":%.17g,"%s":{"%s":%.17g,"%s":%.17g,"%s":%.17g})",
                std::string(r.vehicle).c_str(), r.sim_time_s, p[0], p[1], r.position[0], p[2], r.position[1], p[3],
                r.position[2]);
  std::string s = buf;
  if (r.velocity_frame != VelocityFrame::kNone) {
    const auto* v = kVel[static_cast<int>(r.velocity_frame)];
    std::snprintf(buf, sizeof buf, R"(,"%s":{"%s":%.17g,"%s":%.17g,"%s":%.17g})", v[0], v[1], r.vel_m_s[0], v[2],
                  r.vel_m_s[1], v[3], r.vel_m_s[2]);
    s += buf;
  }
  if (r.has_gps_time) {
    std::snprintf(buf, sizeof buf, R"(,"gps_week":%d,"gps_tow_s":%.17g)", r.gps_week, r.gps_tow_s);
    s += buf;
  }
  return s + "}";
}

}  // namespace

TEST(TruthPacketBinary, GoldenRecordIsPinned) {
  const std::string d = encode(golden_record());
  ASSERT_EQ(d.size(), kTruthRecordBytes);
  EXPECT_EQ(hex(d), kGoldenHex);

  const ParseResult r = parse(d);
  ASSERT_TRUE(r.ok) << r.detail;
  EXPECT_EQ(r.sample.vehicle, "ego");
  EXPECT_EQ(bits(r.sample.sim_time_s), bits(12.5));
  expect_same_bits(r.sample.pos_m, frame().to_ecef(Enu(120.0, -80.0, 1.5)), "position");
  ASSERT_TRUE(r.sample.vel_m_s.has_value());
  const Enu v = geo::ecef_to_enu_vector(*r.sample.vel_m_s, r.sample.lla.lat_rad, r.sample.lla.lon_rad);
  EXPECT_NEAR(v.x, 5.0, 1e-12);
  EXPECT_NEAR(v.y, 0.0, 1e-12);
  ASSERT_TRUE(r.sample.gps_time.has_value());
  EXPECT_EQ(r.sample.gps_time->week(), 2190);
  EXPECT_EQ(bits(r.sample.gps_time->tow_s()), bits(518400.5));
  ASSERT_TRUE(r.sample.attitude.has_value());
  EXPECT_EQ(bits(r.sample.attitude->roll_rad), bits(0.0));
  EXPECT_EQ(bits(r.sample.attitude->pitch_rad), bits(0.0));
  EXPECT_EQ(bits(r.sample.attitude->yaw_rad), bits(kPi / 2.0));
}

TEST(TruthPacketBinary, RoundTripEqualsJsonToTheLastBit) {
  const Ecef origin_ecef = geo::ecef_from_lla(kOrigin);
  const std::array<std::array<double, 3>, 3> positions = {{
      {48.87381234567891, 350.123456789, 123.456789},  // LLA, lon > 180 wraps
      {origin_ecef.x + 0.1234567, origin_ecef.y - 9876.54321, origin_ecef.z + 1e-9},
      {1234.5678901234, -4321.0987654321, 17.25},
  }};
  int cases = 0;
  for (int pf = 0; pf < 3; ++pf) {
    for (int vf = 0; vf < 3; ++vf) {
      for (int gps = 0; gps < 2; ++gps) {
        TruthRecord rec;
        rec.vehicle = "round-trip vehicle #1";
        rec.sim_time_s = 1234.000123456789 + pf;
        rec.position_frame = static_cast<PositionFrame>(pf);
        rec.position = positions[static_cast<std::size_t>(pf)];
        rec.velocity_frame = static_cast<VelocityFrame>(vf);
        rec.vel_m_s = {12.345678901, -0.000123, 3.0 / 7.0};
        rec.has_gps_time = gps == 1;
        rec.gps_week = 2190;
        rec.gps_tow_s = 604799.999999;
        rec.has_attitude = pf == 1;
        rec.attitude_rad = {-0.1, 0.2, 5.5};
        const std::string what = to_json(rec);
        const ParseResult bin = parse(encode(rec));
        const ParseResult js = parse(what);
        ASSERT_TRUE(bin.ok) << what << ": " << bin.detail;
        ASSERT_TRUE(js.ok) << what << ": " << js.detail;
        EXPECT_EQ(bin.sample.vehicle, js.sample.vehicle);
        EXPECT_EQ(bits(bin.sample.sim_time_s), bits(js.sample.sim_time_s)) << what;
        expect_same_bits(bin.sample.pos_m, js.sample.pos_m, what);
        expect_same_bits(Vec3(bin.sample.lla.lat_rad, bin.sample.lla.lon_rad, bin.sample.lla.height_m),
                         Vec3(js.sample.lla.lat_rad, js.sample.lla.lon_rad, js.sample.lla.height_m), what);
        ASSERT_EQ(bin.sample.vel_m_s.has_value(), vf != 0) << what;
        ASSERT_EQ(js.sample.vel_m_s.has_value(), vf != 0) << what;
        if (vf != 0) expect_same_bits(*bin.sample.vel_m_s, *js.sample.vel_m_s, what);
        ASSERT_EQ(bin.sample.gps_time.has_value(), gps == 1);
        ASSERT_EQ(js.sample.gps_time.has_value(), gps == 1);
        if (gps == 1) {
          EXPECT_EQ(bin.sample.gps_time->week(), js.sample.gps_time->week());
          EXPECT_EQ(bits(bin.sample.gps_time->tow_s()), bits(js.sample.gps_time->tow_s()));
        }
        if (pf == 1) {
          expect_same_bits(bin.sample.pos_m, Vec3(rec.position[0], rec.position[1], rec.position[2]), "ECEF as sent");
          ASSERT_TRUE(bin.sample.attitude.has_value());
          EXPECT_EQ(bits(bin.sample.attitude->yaw_rad), bits(5.5));
        } else {
          EXPECT_FALSE(bin.sample.attitude.has_value());
        }
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 18);
}

TEST(TruthPacketBinary, EncoderRefusesIdsThePaddingCannotCarry) {
  senders::RecordBytes b{};
  TruthRecord r = golden_record();
  r.vehicle = "";
  EXPECT_FALSE(senders::encode_truth_record(r, b));
  const std::string long_id(65, 'x');
  r.vehicle = long_id;
  EXPECT_FALSE(senders::encode_truth_record(r, b));
  r.vehicle = std::string_view("a\0b", 3);
  EXPECT_FALSE(senders::encode_truth_record(r, b));
  const std::string full_id(64, 'x');  // fills the field, no NUL left: still valid
  r.vehicle = full_id;
  ASSERT_TRUE(senders::encode_truth_record(r, b));
  const ParseResult p = parse(std::string(reinterpret_cast<const char*>(b.data()), b.size()));
  ASSERT_TRUE(p.ok) << p.detail;
  EXPECT_EQ(p.sample.vehicle, full_id);
}

TEST(TruthPacketBinary, SizeMagicVersionFlags) {
  const std::string good = encode(golden_record());
  expect_drop("\xF7", DropReason::kBadSize, "one byte");
  expect_drop(good.substr(0, 4), DropReason::kBadSize, "magic only");
  expect_drop(good.substr(0, 159), DropReason::kBadSize, "159 bytes");
  expect_drop(good + '\0', DropReason::kBadSize, "161 bytes");
  expect_drop(good + std::string(5000, '\0'), DropReason::kTooLarge, "over 4096 bytes");
  std::string d = good;
  d[3] = 'X';
  expect_drop(d, DropReason::kBadMagic, "magic F7 47 54 58");
  for (int version : {0, 2, 255}) {
    d = good;
    d[4] = static_cast<char>(version);
    expect_drop(d, DropReason::kUnknownVersion, "version " + std::to_string(version));
    expect_drop(d + std::string(40, '\0'), DropReason::kUnknownVersion, "longer record of another version");
  }
  for (int flags : {0x03, 0x0C, 0x40, 0x80, 0xFF}) {
    d = good;
    d[5] = static_cast<char>(flags);
    expect_drop(d, DropReason::kBadFlags, "flags " + std::to_string(flags));
  }
  // The first byte alone decides: JSON texts still parse, text that is neither
  // is still malformed JSON.
  EXPECT_TRUE(parse(R"( {"version":1,"vehicle":"a","sim_time_s":1,"enu":{"e_m":0,"n_m":0,"u_m":0}})").ok);
  expect_drop("\xF8GTR", DropReason::kMalformedJson, "other high byte");
}

TEST(TruthPacketBinary, VehicleIdField) {
  const std::string good = encode(golden_record());
  std::string d = good;
  d[8] = '\0';  // "\0go"
  expect_drop(d, DropReason::kBadVehicleId, "bytes after the first NUL");
  d = good;
  d[8] = d[9] = d[10] = '\0';
  expect_drop(d, DropReason::kBadVehicleId, "empty id");
  d = good;
  d[9] = '\x07';
  expect_drop(d, DropReason::kBadVehicleId, "control character");
  d = good;
  d[9] = '\x7f';
  expect_drop(d, DropReason::kBadVehicleId, "DEL");
}

TEST(TruthPacketBinary, NonFiniteFields) {
  const std::string good = encode(golden_record());
  for (double bad : {kNaN, kInf, -kInf}) {
    for (std::size_t off : {72u, 80u, 88u, 96u, 104u, 112u, 120u, 128u, 136u, 144u, 152u}) {
      std::string d = good;
      put_f64(d, off, bad);
      expect_drop(d, DropReason::kNonFinite, "offset " + std::to_string(off));
    }
  }
  // Fields the flags do not announce are not read.
  TruthRecord r = golden_record();
  r.velocity_frame = VelocityFrame::kNone;
  r.has_attitude = false;
  r.has_gps_time = false;
  std::string d = encode(r);
  for (std::size_t off : {80u, 112u, 120u, 128u, 136u, 144u, 152u}) put_f64(d, off, kNaN);
  d[6] = d[7] = '\xFF';  // gps_week 65535
  const ParseResult p = parse(d);
  ASSERT_TRUE(p.ok) << p.detail;
  EXPECT_FALSE(p.sample.vel_m_s || p.sample.gps_time || p.sample.attitude);
}

TEST(TruthPacketBinary, ImpossibleValues) {
  auto with = [](auto change) {
    TruthRecord r = golden_record();
    change(r);
    return encode(r);
  };
  auto lla = [](TruthRecord& r, double lat, double lon, double h) {
    r.position_frame = PositionFrame::kLla;
    r.position = {lat, lon, h};
  };
  expect_drop(with([&](TruthRecord& r) { lla(r, 90.0001, 0, 0); }), DropReason::kLatitudeRange, "lat");
  expect_drop(with([&](TruthRecord& r) { lla(r, 0, -180.5, 0); }), DropReason::kLongitudeRange, "lon");
  expect_drop(with([&](TruthRecord& r) { lla(r, 0, 361, 0); }), DropReason::kLongitudeRange, "lon");
  expect_drop(with([&](TruthRecord& r) { lla(r, 0, 0, -1000.5); }), DropReason::kHeightRange, "height");
  expect_drop(with([](TruthRecord& r) {
                r.position_frame = PositionFrame::kEcef;
                r.position = {0, 0, 0};
              }),
              DropReason::kHeightRange, "Earth's centre");
  expect_drop(with([](TruthRecord& r) { r.vel_m_s = {800, 800, 0}; }), DropReason::kSpeedRange, "speed");
  expect_drop(with([](TruthRecord& r) { r.gps_week = 10000; }), DropReason::kBadGpsTime, "week");
  expect_drop(with([](TruthRecord& r) { r.gps_tow_s = 604800.0; }), DropReason::kBadGpsTime, "tow");
  expect_drop(with([](TruthRecord& r) { r.gps_tow_s = -0.001; }), DropReason::kBadGpsTime, "tow");
  expect_drop(with([](TruthRecord& r) { r.attitude_rad = {3.2, 0, 0}; }), DropReason::kAttitudeRange, "roll");
  expect_drop(with([](TruthRecord& r) { r.attitude_rad = {0, -1.6, 0}; }), DropReason::kAttitudeRange, "pitch");
  expect_drop(with([](TruthRecord& r) { r.attitude_rad = {0, 0, -3.2}; }), DropReason::kAttitudeRange, "yaw");
  expect_drop(with([](TruthRecord& r) { r.attitude_rad = {0, 0, 90.0}; }), DropReason::kAttitudeRange, "degrees");
  // Limits themselves are accepted.
  EXPECT_TRUE(parse(with([](TruthRecord& r) { r.attitude_rad = {-kPi, kPi / 2.0, 2.0 * kPi}; })).ok);
  EXPECT_TRUE(parse(with([](TruthRecord& r) { r.attitude_rad = {kPi, -kPi / 2.0, -kPi}; })).ok);
  EXPECT_TRUE(parse(with([&](TruthRecord& r) { lla(r, -90, 180, 100000); })).ok);
  EXPECT_TRUE(parse(with([](TruthRecord& r) { r.gps_week = 9999; })).ok);
}

// Mutated and random records: dropped with a reason or parsed into finite
// values, never a crash (a short, deterministic cousin of the fuzz target).
TEST(TruthPacketBinary, MutationsNeverCrash) {
  const std::string good = encode(golden_record());
  std::mt19937 rng(13);
  int ok = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string d = good;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) d[rng() % d.size()] = static_cast<char>(rng() & 0xFF);
    if (i % 10 == 0) d.resize(rng() % (d.size() + 8));
    const ParseResult r = parse(d);
    if (r.ok) {
      ++ok;
      EXPECT_TRUE(r.sample.pos_m.finite());
      EXPECT_TRUE(std::isfinite(r.sample.sim_time_s));
      EXPECT_FALSE(r.sample.vehicle.empty());
    } else {
      EXPECT_LT(static_cast<std::size_t>(r.reason), kDropReasonCount);
      EXPECT_FALSE(r.detail.empty());
    }
  }
  EXPECT_GT(ok, 0);  // flips in the padding of unused bytes still parse
}
