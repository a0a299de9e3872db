// SPDX-License-Identifier: Apache-2.0
// A port reporting another fix type than the receiver's (the wrong_fix link
// fault): Device::compose with a FixOverride changes exactly the fields
// that carry a fix type, in every message that has one, on that port only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/protocol/nmea/reported_fix.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_message_list.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

constexpr Link kAt{0, kPortUart1};

Device device(bool coast_as_no_fix = true) {
  DeviceSetup setup;
  setup.coast_as_no_fix = coast_as_no_fix;
  OutputSetup o;
  o.rates = {{msg::kNavPvt, 1},    {msg::kNavStatus, 1}, {msg::kNavSol, 1},    {msg::kNavPosllh, 1},
             {msg::kNmeaRmc, 1},   {msg::kNmeaVtg, 1},   {msg::kNmeaGga, 1},   {msg::kNmeaGsa, 1},
             {msg::kNmeaGll, 1}};
  setup.outputs = {o, o};
  return Device(setup);
}

std::string compose(const Device& d, FixOverride reported, Link at = kAt) {
  MessageList list;
  d.compose(at, list, Layout::kLine, reported);
  return std::string(list.buffer());
}

template <class T>
T payload(const std::string& stream, MsgId id) {
  for (const test::Frame& f : test::split_frames(stream)) {
    if (f.id != id) continue;
    T m{};
    EXPECT_EQ(f.payload.size(), sizeof m);
    std::memcpy(&m, f.payload.data(), sizeof m);
    return m;
  }
  ADD_FAILURE() << "no message " << message_label(id);
  return {};
}

/// The NMEA field index (0: the address) of sentence (e.g. "GGA") in stream.
std::string field(const std::string& stream, std::string_view sentence, std::size_t index) {
  std::vector<std::string> lines;
  test::split_frames(stream, &lines);
  for (const std::string& line : lines) {
    if (line.compare(3, 3, sentence) != 0) continue;
    std::vector<std::string> f(1);
    for (char c : line.substr(0, line.find('*'))) {
      if (c == ',') {
        f.emplace_back();
      } else {
        f.back() += c;
      }
    }
    return index < f.size() ? f[index] : std::string("<none>");
  }
  return "<no " + std::string(sentence) + ">";
}

TEST(UbxReportedFix, NoOverrideIsTheReceiversFixByteForByte) {
  Device d = device();
  d.on_epoch(test::sample_fix(), 10.0);
  MessageList plain;
  d.compose(kAt, plain);
  EXPECT_EQ(compose(d, std::nullopt), std::string(plain.buffer()));
  EXPECT_EQ(payload<wire::NavPvt>(compose(d, std::nullopt), msg::kNavPvt).fixType, 3);
}

TEST(UbxReportedFix, EveryFixTypeFieldFollowsTheOverride) {
  Device d = device();
  d.on_epoch(test::sample_fix(), 10.0);  // a 3D fix
  struct Want {
    ReportedFix type;
    bool ok;
    const char* quality;
    const char* status;
    const char* mode;
    const char* nav_mode;
  };
  const Want wants[] = {
      {ReportedFix::kNoFix, false, "0", "V", "N", "1"},
      {ReportedFix::kDeadReckoning, false, "6", "A", "E", "2"},
      {ReportedFix::k2D, true, "1", "A", "A", "2"},
      {ReportedFix::k3D, true, "1", "A", "A", "3"},
      {ReportedFix::kGnssDeadReckoning, true, "1", "A", "A", "3"},
      {ReportedFix::kTimeOnly, false, "0", "V", "N", "1"},
  };
  const std::string truth = compose(d, std::nullopt);
  for (const Want& w : wants) {
    SCOPED_TRACE(static_cast<int>(w.type));
    const std::string s = compose(d, w.type);
    const auto pvt = payload<wire::NavPvt>(s, msg::kNavPvt);
    EXPECT_EQ(pvt.fixType, static_cast<int>(w.type));
    EXPECT_EQ(pvt.flags & 0x01, w.ok ? 1 : 0);
    const auto st = payload<wire::NavStatus>(s, msg::kNavStatus);
    EXPECT_EQ(st.gpsFix, static_cast<int>(w.type));
    EXPECT_EQ(st.flags & 0x01, w.ok ? 1 : 0);
    const auto sol = payload<wire::NavSol>(s, msg::kNavSol);
    EXPECT_EQ(sol.gpsFix, static_cast<int>(w.type));
    EXPECT_EQ(sol.flags & 0x01, w.ok ? 1 : 0);
    EXPECT_EQ(field(s, "GGA", 6), w.quality);
    EXPECT_EQ(field(s, "RMC", 2), w.status);
    EXPECT_EQ(field(s, "RMC", 12), w.mode);
    EXPECT_EQ(field(s, "VTG", 9), w.mode);
    EXPECT_EQ(field(s, "GLL", 6), w.status);
    EXPECT_EQ(field(s, "GLL", 7), w.mode);
    EXPECT_EQ(field(s, "GSA", 2), w.nav_mode);
    // The position is still the receiver's: the lie is in the fix type only.
    EXPECT_EQ(field(s, "GGA", 2), field(truth, "GGA", 2));
    EXPECT_EQ(payload<wire::NavPvt>(s, msg::kNavPvt).lat, payload<wire::NavPvt>(truth, msg::kNavPvt).lat);
    EXPECT_EQ(payload<wire::NavPosllh>(s, msg::kNavPosllh).lat, payload<wire::NavPosllh>(truth, msg::kNavPosllh).lat);
  }
}

TEST(UbxReportedFix, A3dClaimWithoutAFixKeepsTheEmptyPosition) {
  Device d = device();
  receiver::Fix none = test::sample_fix();
  none.type = receiver::FixType::kNone;
  d.on_epoch(none, 10.0);
  const std::string s = compose(d, ReportedFix::k3D);
  const auto pvt = payload<wire::NavPvt>(s, msg::kNavPvt);
  EXPECT_EQ(pvt.fixType, 3);
  EXPECT_EQ(pvt.flags & 0x01, 1);  // gnssFixOK: a host trusting the flag trusts it
  EXPECT_EQ(pvt.flags3 & 0x01, 1);  // invalidLlh: no position behind it
  EXPECT_EQ(field(s, "GGA", 6), "1");
  EXPECT_EQ(field(s, "GGA", 2), "");
}

// An extrapolated solution (the filter coasting without satellites): a
// receiver without sensors flags it no fix but keeps the extrapolated
// position (ANTARIS 4 SIM §4.6.5.2); an ADR-style one reports fixType 1.
TEST(UbxReportedFix, CoastingIsNoFixWithTheExtrapolatedPositionByDefault) {
  receiver::Fix dr = test::sample_fix();
  dr.type = receiver::FixType::kDeadReckoning;
  dr.num_used = 0;
  Device d = device();
  d.on_epoch(dr, 10.0);
  const std::string s = compose(d, std::nullopt);
  const auto pvt = payload<wire::NavPvt>(s, msg::kNavPvt);
  EXPECT_EQ(pvt.fixType, 0);
  EXPECT_EQ(pvt.flags & 0x01, 0);
  EXPECT_EQ(pvt.lat, static_cast<std::int32_t>(std::lround(dr.lla.lat_rad * 180.0 / M_PI * 1e7)));
  EXPECT_EQ(payload<wire::NavStatus>(s, msg::kNavStatus).gpsFix, 0);
  EXPECT_EQ(field(s, "GGA", 6), "0");
  EXPECT_EQ(field(s, "RMC", 2), "V");
  // A port fault still wins over the policy.
  EXPECT_EQ(payload<wire::NavPvt>(compose(d, ReportedFix::k3D), msg::kNavPvt).fixType, 3);

  Device adr = device(false);
  adr.on_epoch(dr, 10.0);
  const std::string a = compose(adr, std::nullopt);
  EXPECT_EQ(payload<wire::NavPvt>(a, msg::kNavPvt).fixType, 1);
  EXPECT_EQ(field(a, "GGA", 6), "6");
  EXPECT_EQ(field(a, "RMC", 12), "E");

  // A reload of [receiver.nav] coast_report reaches the running chip.
  d.set_coast_as_no_fix(false);
  EXPECT_EQ(compose(d, std::nullopt), a);
  adr.set_coast_as_no_fix(true);
  EXPECT_EQ(compose(adr, std::nullopt), s);
}

TEST(UbxReportedFix, OnlyThePortAskedChanges) {
  Device d = device();
  d.on_epoch(test::sample_fix(), 10.0);
  const std::string other_before = compose(d, std::nullopt, Link{1, kPortUart1});
  EXPECT_NE(compose(d, ReportedFix::kNoFix), compose(d, std::nullopt));
  EXPECT_EQ(compose(d, std::nullopt, Link{1, kPortUart1}), other_before);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
