// SPDX-License-Identifier: Apache-2.0
// The TOML configuration through config::parse_config, as gnssemud
// --check-config reads it. Oracles: errors are gnssemu::Error naming the
// file; an accepted config writes back (to_toml) to a text that reads back
// to the same text; building the emulated u-blox and the receiver pipeline
// succeeds or throws gnssemu::Error, and three epochs at the origin give a
// finite fix or none.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "config/config.hpp"
#include "config/setup/device_setup.hpp"
#include "config/setup/pipeline_setup.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu;
using gnssemu::fuzz::expect;

const std::string kName = "fuzz.toml";
const std::string kTestData = GNSSEMU_TEST_DATA;

// The config's folder, laid out so the relative paths of every seed
// resolve: "nav/x" (config/default.toml), "../nav/x" (config/examples),
// "../../../data/nav/x" and "../../../data/scenes/x" (tests/golden), "scenes/x".
class BaseDir {
public:
  BaseDir() : path_(root_.path() + "/a/b/c") {
    namespace fs = std::filesystem;
    fs::create_directories(path_);
    fs::create_directory_symlink(kTestData, root_.path() + "/data");
    fs::create_directory_symlink(kTestData + "/nav", root_.path() + "/a/b/nav");
    fs::create_directory_symlink(kTestData + "/nav", path_ + "/nav");
    fs::create_directory_symlink(kTestData + "/scenes", path_ + "/scenes");
  }
  const std::string& path() const noexcept { return path_; }

private:
  fuzz::ScratchDir root_;
  std::string path_;
};

const orbit::NavData& nav() {
  static const orbit::NavData n = orbit::read_rinex_nav(kTestData + "/nav/brdc0010.22n");
  return n;
}

void check_fix(const receiver::Fix& f) {
  if (f.type == receiver::FixType::kNone) return;
  expect(f.pos_m.finite() && f.vel_m_s.finite(), "fix position and velocity finite");
  expect(std::isfinite(f.lla.lat_rad) && std::isfinite(f.lla.lon_rad) && std::isfinite(f.lla.height_m), "fix LLA finite");
  expect(std::isfinite(f.dop.pdop) && std::isfinite(f.h_acc_m) && std::isfinite(f.v_acc_m), "fix DOP and accuracy finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const orbit::EphemerisStore store(nav().ephemerides);
  static const BaseDir base;
  const std::string& base_dir = base.path();
  const std::string text(reinterpret_cast<const char*>(data), size);
  config::Config c;
  try {
    c = config::parse_config(text, kName, base_dir);
  } catch (const Error& e) {
    fuzz::expect_names_file(e, kName);
    return 0;
  }

  std::string written;
  try {
    written = config::to_toml(c, base_dir);
  } catch (const Error&) {
    return 0;  // a value TOML cannot carry (documented: seed > 2^63 - 1)
  }
  try {
    const config::Config back = config::parse_config(written, "written.toml", base_dir);
    expect(config::to_toml(back, base_dir) == written, "to_toml(parse_config(to_toml(c))) == to_toml(c)");
  } catch (const Error& e) {
    fuzz::fail(std::string("to_toml wrote a config that does not read back: ") + e.what());
  }

  try {
    protocol::ubx::Device device(config::device_setup(c));
    (void)device;
    auto pipeline = config::make_pipeline(c, store, pipeline::broadcast_of(nav()), nullptr);
    world::Truth truth;
    truth.pos_m = geo::ecef_from_lla(c.origin);
    truth.valid = true;
    for (int k = 0; k < 3; ++k) {
      truth.t = time::GpsTime(2190, 522000.0 + k / c.rate_hz);
      check_fix(pipeline->step(truth.t, truth));
    }
  } catch (const Error& e) {
    // Cross-field rules the core checks when building (gnssemud
    // --check-config builds both too, so the user sees this error).
    expect(*e.what() != '\0', "a build error says why");
  }
  return 0;
}
