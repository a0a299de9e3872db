// SPDX-License-Identifier: Apache-2.0
#include "project_layers.hpp"

namespace gnssemu::layering {

namespace {

/// tests/unit/<folder>: the tests of one layer, with the allocation counter.
Layer tests_of(const std::string& folder, const std::string& layer) {
  return {"tests/unit/" + folder, "tests/unit/" + folder, {layer, "support"}, {}};
}

}  // namespace

Rules project_rules() {
  Rules r;
  // A layer may include its own folder, the layers it uses and everything
  // those may include. Adding a module is one row here (and one for its tests).
  r.layers = {
      {"common", "core/common", {}, {}},
      {"statistics", "core/statistics", {"common"}, {}},
      {"time", "core/time", {"common"}, {}},
      {"orbit", "core/orbit", {"time"}, {}},
      {"observation", "core/observation", {"time"}, {}},
      {"geo", "core/geo", {"time"}, {}},
      {"atmosphere", "core/atmosphere", {"orbit", "geo"}, {}},  // Klobuchar coefficients are nav data
      {"scene", "core/scene", {"geo"}, {}},
      {"signal", "core/signal", {"atmosphere"}, {}},
      {"world", "core/world", {"signal", "scene"}, {}},
      // Faults edit the world's observables; the receiver never sees them.
      {"faults", "core/faults", {"world"}, {}},
      {"receiver", "core/receiver", {"world"}, {}},
      {"pipeline", "core/pipeline", {"receiver", "faults"}, {}},
      // The encoders read the Fix struct only, not the receiver that fills it.
      {"nmea", "core/protocol/nmea", {"time"}, {"core/receiver/fix.hpp"}},
      // Navigation messages re-encoded from the broadcast ephemerides (RXM-SFRBX).
      {"navmsg", "core/protocol/navmsg", {"orbit"}, {}},
      // RTCM 3 arrives on a u-blox port beside UBX and NMEA (RXM-RTCM).
      // Its rooms (wire, config, handlers, device) are one layer: encoders
      // read the configuration and handlers answer with encoders.
      {"ubx", "core/protocol/ubx", {"nmea", "navmsg", "rtcm"},
       {"core/receiver/raw_measurements.hpp", "core/receiver/corrections.hpp"}},
      // RINEX writers: the receiver's raw measurements (plain data) and the nav data.
      {"rinex", "core/rinex", {"orbit", "observation"}, {"core/receiver/raw_measurements.hpp"}},
      // RTCM encodes a RawEpoch (plain header) and the broadcast ephemerides,
      // and decodes into the rover's Corrections (plain header).
      {"rtcm", "core/protocol/rtcm", {"orbit"},
       {"core/receiver/raw_measurements.hpp", "core/receiver/corrections.hpp"}},
      {"config", "config", {"pipeline", "ubx", "rtcm", "observation"}, {}},
      // gnssemud's rooms: truth input, ports, status and control sit side by
      // side below the vehicle loop (daemon/ itself), which alone ties them.
      {"daemon_service", "daemon/service", {"ubx"}, {}},  // the state file keeps the device's settings
      {"daemon_truth", "daemon/truth", {"config"}, {}},
      {"daemon_ports", "daemon/ports", {"config"}, {}},
      // The status reads truth drops and link fault counters, never sends.
      {"daemon_status", "daemon/status", {"daemon_truth", "daemon_ports", "statistics"}, {}},
      {"daemon_control", "daemon/control", {"config"}, {}},
      {"daemon", "daemon", {"daemon_service", "daemon_truth", "daemon_ports", "daemon_status", "daemon_control"}, {}},
      {"tools", "tools", {"daemon", "statistics", "rinex"}, {}},
      {"support", "tests/support", {}, {}},
      {"bench", "bench", {"tools", "support"}, {}},
      {"layering", "tests/layering", {}, {}},
      {"fuzz", "tests/fuzz", {"daemon"}, {}},  // fuzz targets: every parser, up to the truth input
      tests_of("common", "common"),
      tests_of("statistics", "statistics"),
      tests_of("time", "time"),
      tests_of("orbit", "orbit"),
      tests_of("observation", "observation"),
      tests_of("geo", "geo"),
      tests_of("atmosphere", "atmosphere"),
      tests_of("scene", "scene"),
      tests_of("signal", "signal"),
      tests_of("world", "world"),
      tests_of("receiver", "pipeline"),  // receiver tests assemble world + receiver
      tests_of("pipeline", "pipeline"),
      tests_of("faults", "pipeline"),  // fault tests run the whole pipeline
      tests_of("nmea", "nmea"),
      tests_of("navmsg", "navmsg"),
      tests_of("ubx", "ubx"),
      tests_of("rinex", "rinex"),
      tests_of("rtcm", "rtcm"),
      tests_of("config", "config"),
      tests_of("daemon", "daemon"),
      tests_of("cli", "tools"),
      tests_of("senders", "tools"),
  };
  // core/ is pure computation (DESIGN.md §2-3): no I/O framework, logging,
  // formatting or configuration libraries. Embree and GeographicLib each
  // stay inside the one module that wraps them.
  const std::vector<std::string> above_core{"config", "daemon", "tools", "bench", "tests"};
  for (const char* prefix : {"asio", "boost/", "spdlog/", "fmt/", "toml++/", "toml.hpp", "nlohmann/", "CLI/"}) {
    r.externals.push_back({prefix, above_core});
  }
  r.externals.push_back({"embree", {"core/scene"}});
  r.externals.push_back({"GeographicLib/", {"core/geo"}});
  r.skipped = {"tests/data", "tests/golden"};
  return r;
}

}  // namespace gnssemu::layering
