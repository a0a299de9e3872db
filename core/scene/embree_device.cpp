// SPDX-License-Identifier: Apache-2.0
#include "core/scene/embree_device.hpp"

#include <embree3/rtcore.h>

namespace gnssemu::scene {

std::string embree_version() {
  RTCDevice dev = rtcNewDevice("threads=1");
  if (dev == nullptr) return "unavailable";
  const auto v = rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION);
  rtcReleaseDevice(dev);
  const long major = v / 10000, minor = (v / 100) % 100, patch = v % 100;
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

}  // namespace gnssemu::scene
