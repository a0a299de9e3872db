// SPDX-License-Identifier: Apache-2.0
// Building footprint files (TOML, docs/scene.md) through config::load_mesh:
// config parses the text, core/scene extrudes it; oracles in mesh_checks.hpp.
#include "config/setup/footprint_file.hpp"
#include "fuzz_support.hpp"
#include "mesh_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static gnssemu::fuzz::ScratchFile file(".toml");
  gnssemu::fuzz::load_and_check_mesh(file.write({reinterpret_cast<const char*>(data), size}),
                                     &gnssemu::config::load_mesh);
  return 0;
}
