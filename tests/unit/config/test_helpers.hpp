// SPDX-License-Identifier: Apache-2.0
#pragma once
// Shared helpers for the config tests.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "config/config.hpp"
#include "core/common/error.hpp"

namespace gnssemu::config::test {

inline const std::string kData = GNSSEMU_TEST_DATA;
inline const std::string kSource = GNSSEMU_SOURCE_DIR;

/// What the shipped default.toml must equal: the struct defaults with the
/// file's receiver profile applied at its origin (one source of truth each).
inline Config struct_defaults_as_shipped(const Config& shipped) {
  Config d;
  if (shipped.profile) {
    const pipeline::PipelineConfig pc = pipeline::apply_profile({d.world, d.receiver}, *shipped.profile,
                                                                shipped.origin.lat_rad);
    d.world = pc.world;
    d.receiver = pc.receiver;
    d.profile = shipped.profile;
  }
  return d;
}

/// Six lines: [origin] and [nav]; appended text starts on line 7.
inline const std::string kBase =
    "[origin]\n"
    "lat_deg = 48.8738\n"
    "lon_deg = 2.2950\n"
    "height_m = 100.0\n"
    "[nav]\n"
    "file = \"nav/brdc0010.22n\"\n";

/// Parses text as "t.toml" with tests/data as its folder.
inline Config parse(const std::string& text) { return parse_config(text, "t.toml", kData); }

/// The message of the gnssemu::Error parse(text) throws, or "no error".
inline std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

/// Runs f, expects a gnssemu::Error whose message contains every piece.
template <class F>
void expect_error(F f, std::initializer_list<std::string> pieces) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    for (const std::string& p : pieces) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

}  // namespace gnssemu::config::test
