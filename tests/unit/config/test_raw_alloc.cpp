// SPDX-License-Identifier: Apache-2.0
// The raw-output paths allocate nothing after warm-up (issue 25 "Speed"): a
// two-band ZED-F9P (receiver epoch on GPS, GLONASS, Galileo and BeiDou, then
// RXM-RAWX and RXM-SFRBX composed as batch and the daemon do), and a [base]
// station's step (MSM7 of every system, 1005, 1230 and the ephemerides).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "config/config.hpp"
#include "config/setup/base_station.hpp"
#include "config/setup/device_setup.hpp"
#include "config/setup/nav_setup.hpp"
#include "config/setup/pipeline_setup.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::config {
namespace {

const std::string kF9pTop = R"([origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz"
[receiver]
seed = 3
generation = "f9p"
)";

// 2024-01-10 02:05 GPS, inside the cut nav file's span.
const time::GpsTime kRawStart = time::GpsTime::from_calendar({2024, 1, 10, 2, 5, 0.0});

TEST(RawAlloc, F9pTwoBandEpochWithRawxAndSfrbxDoesNotAllocate) {
  const Config c = parse_config(kF9pTop, "f9p.toml", GNSSEMU_TEST_DATA);
  ASSERT_EQ(c.receiver.bands, 2);
  const orbit::Constellation con = make_constellation(c, load_nav(c), kRawStart);
  const orbit::EphemerisStore store(con.nav.ephemerides, con.store_options());
  const std::unique_ptr<pipeline::Pipeline> rx = make_pipeline(c, store, pipeline::broadcast_of(con.nav), nullptr);
  protocol::ubx::Device device(device_setup(c, orbit::systems_of(con.nav)));
  apply_chip_settings(device, rx->receiver());
  std::string reply;
  for (const protocol::ubx::MsgId id : {protocol::ubx::msg::kRxmRawx, protocol::ubx::msg::kRxmSfrbx}) {
    const std::uint8_t p[3] = {id.cls, id.id, 1};
    reply.clear();
    ASSERT_EQ(device.handle_ubx({}, protocol::ubx::FrameView{protocol::ubx::msg::kCfgMsg, p}, 0.0, reply).reply,
              protocol::ubx::Reply::kAck);
  }
  world::Truth truth;
  truth.pos_m = geo::ecef_from_lla(Lla{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0});
  truth.valid = true;
  const orbit::NavData& nav = con.nav;
  protocol::ubx::MessageList messages;
  int band1 = 0, rawx = 0, sfrbx = 0;
  const auto run = [&](int first, int epochs) {
    for (int k = first; k < first + epochs; ++k) {
      truth.t = kRawStart + 0.5 * k;
      const receiver::Fix& fix = rx->step(truth.t, truth);
      const receiver::RawEpoch& raw = rx->receiver().raw();
      for (int j = 0; j < raw.num_meas; ++j) band1 += signal_info(raw.meas[static_cast<std::size_t>(j)].signal).band;
      device.on_epoch(fix, 0.5 * k,
                      protocol::ubx::RawSource{&raw, &store, {&nav.klobuchar, &nav.utc, raw.leap_seconds},
                                               &nav.galileo_nequick, &nav.beidou_klobuchar});
      device.compose({}, messages);
      for (const protocol::ubx::MessageList::Message& m : messages.messages()) {
        const std::string_view f = messages.bytes(m);
        if (m.protocol != protocol::ubx::Protocol::kUbx || f.size() < 8 || f[2] != 0x02) continue;
        rawx += f[3] == 0x15;
        sfrbx += f[3] == 0x13;
      }
    }
  };
  run(0, 240);  // two minutes at 2 Hz: acquisition, every subframe and page sent once
  band1 = rawx = sfrbx = 0;
  const long before = support::allocation_count();
  run(240, 240);
  const long after = support::allocation_count();
  EXPECT_EQ(after - before, 0);
  EXPECT_EQ(rawx, 240);
  EXPECT_GT(sfrbx, 100);
  EXPECT_GT(band1, 240 * 15);  // second-band measurements of every system
  // The counter works: a vector allocates.
  std::vector<int>* probe = new std::vector<int>(10);
  delete probe;
  EXPECT_GE(support::allocation_count() - after, 2);
}

TEST(RawAlloc, BaseStationStepDoesNotAllocate) {
  const Config c = parse_config(kF9pTop + R"toml([base]
lat_deg = 48.9
lon_deg = 2.4
height_m = 80.0
station_id = 12
messages = "1005(10), 1077, 1087, 1097, 1127, 1230(5), 1019(30), 1020(30), 1042(30), 1046(30)"
)toml",
                                "base.toml", GNSSEMU_TEST_DATA);
  const orbit::Constellation con = make_constellation(c, load_nav(c), kRawStart);
  const orbit::EphemerisStore store(con.nav.ephemerides, con.store_options());
  BaseStation base(c, store, pipeline::broadcast_of(con.nav), nullptr);
  std::string out;
  out.reserve(1 << 16);
  const auto run = [&](int first, int epochs) {
    for (int k = first; k < first + epochs; ++k) {
      out.clear();
      base.step(kRawStart + static_cast<double>(k), out);
    }
  };
  run(0, 90);  // acquisition, every message sent at least once
  const BaseStats warm = base.stats();
  const long before = support::allocation_count();
  run(90, 120);
  EXPECT_EQ(support::allocation_count() - before, 0);
  const BaseStats& s = base.stats();
  EXPECT_EQ(s.epochs - warm.epochs, 120u);
  // Four MSM7 a second, plus 1005, 1230 and the ephemerides.
  EXPECT_GT(s.messages - warm.messages, 4u * 120u + 12u + 24u);
  int cells = 0;
  for (int j = 0; j < base.raw().num_meas; ++j) cells += signal_info(base.raw().meas[static_cast<std::size_t>(j)].signal).band + 1;
  EXPECT_GT(cells, 30);
}

}  // namespace
}  // namespace gnssemu::config
