// SPDX-License-Identifier: Apache-2.0
// OBJ meshes through scene::load_mesh; oracles in mesh_checks.hpp.
#include "fuzz_support.hpp"
#include "mesh_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static gnssemu::fuzz::ScratchFile file(".obj");
  gnssemu::fuzz::load_and_check_mesh(file.write({reinterpret_cast<const char*>(data), size}),
                                     &gnssemu::fuzz::load_scene_mesh);
  return 0;
}
