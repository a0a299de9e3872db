// Building footprint files (TOML, docs/scene.md) through scene::load_mesh,
// which extrudes them; oracles in mesh_checks.hpp.
#include "fuzz_support.hpp"
#include "mesh_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static gnssemu::fuzz::ScratchFile file(".toml");
  gnssemu::fuzz::load_and_check_mesh(file.write({reinterpret_cast<const char*>(data), size}));
  return 0;
}
