// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/version.hpp"

#include "core/geo/geodesy.hpp"
#include "core/scene/embree_device.hpp"
#include "daemon/service/build_info.hpp"

namespace gnssemu::cli {

void write_version(std::ostream& out) {
  out << daemon::version_line("gnssemu") << '\n'
      << "Embree " << scene::embree_version() << '\n'
      << "GeographicLib " << geo::geographiclib_version() << '\n';
}

}  // namespace gnssemu::cli
