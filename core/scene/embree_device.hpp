// SPDX-License-Identifier: Apache-2.0
#pragma once
// Embree device lifetime. The scene module (buildings, multipath) builds on
// this; embree_version() proves the Embree link and names the library version.
#include <string>

namespace gnssemu::scene {

/// Embree library version string, e.g. "3.13.5", from a live RTCDevice.
std::string embree_version();

}  // namespace gnssemu::scene
