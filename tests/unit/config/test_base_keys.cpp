// SPDX-License-Identifier: Apache-2.0
// [base]: messages in str2str's syntax, unknown numbers rejected at their
// line, receiver keys overriding the top level's, the distance warning.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "config/setup/base_station.hpp"
#include "config/setup/nav_setup.hpp"
#include "core/pipeline/pipeline.hpp"
#include "config/config.hpp"
#include "core/common/error.hpp"
#include "core/scene/mesh.hpp"
#include "core/scene/scene.hpp"

namespace gnssemu::config {
namespace {

const std::string kTop = R"([origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "nav/brdc0010.22n"
[receiver]
seed = 1
)";

std::string error_of(const std::string& text) {
  try {
    parse_config(text, "base.toml", GNSSEMU_TEST_DATA);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(BaseKeys, MessagesIntervalsAndOverrides) {
  const Config c = parse_config(kTop + R"toml([base]
lat_deg = 48.9
lon_deg = 2.4
height_m = 80.0
station_id = 12
messages = "1005(10), 1077, 1087(1), 1230(5), 1019(60)"
seed = 7
[base.ntrip]
port = 0
mountpoint = "M1"
)toml",
                                "base.toml", GNSSEMU_TEST_DATA);
  ASSERT_TRUE(c.base);
  ASSERT_EQ(c.base->messages.size(), 5u);
  EXPECT_EQ(c.base->messages[0].number, 1005);
  EXPECT_EQ(c.base->messages[0].interval_s, 10.0);
  EXPECT_EQ(c.base->messages[1].interval_s, 1.0);
  EXPECT_EQ(c.base->settings.world.seed, 7u);
  EXPECT_EQ(c.world.seed, 1u);
  EXPECT_TRUE(c.base->ntrip.enabled);
  EXPECT_EQ(c.base->ntrip.mountpoint, "M1");
  EXPECT_TRUE(base_distance_warning(c).empty());
}

// 1230 as a u-blox F9 base sends it (docs/base-station.md): DF421 = 1, the
// phase ranges aligned, and an empty mask, no bias field.
TEST(BaseStation, Sends1230AlignedWithoutBiases) {
  const Config c = parse_config(kTop + R"toml([base]
lat_deg = 48.9
lon_deg = 2.4
height_m = 80.0
station_id = 12
messages = "1230(1)"
)toml",
                                "base.toml", GNSSEMU_TEST_DATA);
  const time::GpsTime start(2190, 518400.0 + 3600.0);
  const orbit::Constellation con = make_constellation(c, load_nav(c), start);
  const orbit::EphemerisStore store(con.nav.ephemerides, con.store_options());
  BaseStation base(c, store, pipeline::broadcast_of(con.nav), nullptr);
  std::string out;
  base.step(start, out);
  // Frame D3, length 4; payload 1230 (12 bits), station 12 (12), DF421 1, reserved 000, DF422 0000.
  ASSERT_EQ(out.size(), 3u + 4u + 3u);
  const std::string head = out.substr(0, 7);
  EXPECT_EQ(head, std::string("\xD3\x00\x04\x4C\xE0\x0C\x80", 7));
}

// [base] open_sky: by default the base stands in the world's scene where it
// is (here inside a closed building, so it tracks nothing); open_sky sees the
// whole sky whatever the scene.
TEST(BaseStation, StandsInTheSceneUnlessOpenSky) {
  const scene::Scene box(scene::load_mesh(std::string(GNSSEMU_TEST_DATA) + "/scenes/closed_box.obj"));
  const time::GpsTime start(2190, 518400.0 + 3600.0);
  auto tracked = [&](bool open_sky) {
    const Config c = parse_config(kTop + "[scene]\nmesh = \"scenes/closed_box.obj\"\n[base]\nlat_deg = 48.8738\nlon_deg = 2.2950\nheight_m = 101.5\n"
                                         "messages = \"1077(1)\"\nopen_sky = " + (open_sky ? "true" : "false") + "\n",
                                  "base.toml", GNSSEMU_TEST_DATA);
    EXPECT_EQ(c.base->open_sky, open_sky);
    const orbit::Constellation con = make_constellation(c, load_nav(c), start);
    const orbit::EphemerisStore store(con.nav.ephemerides, con.store_options());
    BaseStation base(c, store, pipeline::broadcast_of(con.nav), &box);
    std::string out;
    for (int k = 0; k < 90; ++k) {
      out.clear();
      base.step(start + k, out);
    }
    return base.raw().num_meas;
  };
  const int in_building = tracked(false);
  const int open = tracked(true);
  EXPECT_EQ(in_building, 0);
  EXPECT_GE(open, 6);
  std::printf("base inside a closed building: %d signals; open_sky: %d\n", in_building, open);
}

TEST(BaseKeys, UnknownMessageIsAnErrorAtItsLine) {
  const std::string e = error_of(kTop + "[base]\nlat_deg = 48.9\nlon_deg = 2.4\nheight_m = 80.0\nmessages = \"1005,1004\"\n");
  EXPECT_NE(e.find("base.toml:13:"), std::string::npos) << e;  // the messages line
  EXPECT_NE(e.find("message 1004 is not one the base sends"), std::string::npos) << e;
  EXPECT_NE(error_of(kTop + "[base]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\nmessages = \"1074,1087\"\n").find("MSM4 and MSM7"),
            std::string::npos);
  EXPECT_NE(error_of(kTop + "[base]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\nmessages = \"1077(1),1087(2)\"\n")
                .find("different intervals"),
            std::string::npos);
  EXPECT_NE(error_of(kTop + "[base]\nlat_deg = 1\nlon_deg = 2\nheight_m = 0\nmessages = \"1005(x)\"\n").find("NUMBER(INTERVAL_S)"),
            std::string::npos);
}

TEST(BaseKeys, FarBaseWarns) {
  const Config c = parse_config(kTop + "[base]\nlat_deg = 50.0\nlon_deg = 2.3\nheight_m = 80.0\nmessages = \"1005\"\n",
                                "base.toml", GNSSEMU_TEST_DATA);
  const std::string w = base_distance_warning(c);
  EXPECT_NE(w.find("base.toml:"), std::string::npos) << w;
  EXPECT_NE(w.find("DGNSS baseline big"), std::string::npos) << w;
}

}  // namespace
}  // namespace gnssemu::config
