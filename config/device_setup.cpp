// SPDX-License-Identifier: Apache-2.0
#include "config/device_setup.hpp"

#include <cmath>

#include "core/protocol/ubx/ubx_gnss.hpp"

namespace gnssemu::config {

protocol::ubx::OutputSetup output_setup(const OutputPortConfig& port) {
  protocol::ubx::OutputSetup o;
  o.baud_bps = port.baud;
  o.protocols_in = port.protocols_in;
  o.protocols_out = port.protocols_out;
  for (const MessageRate& m : message_rates(port)) o.rates.push_back({{m.msg_class, m.msg_id}, m.rate});
  o.nmea_version = port.nmea.version;
  o.course_min_speed_m_s = port.nmea.course_min_speed_m_s;
  return o;
}

SystemSet chip_systems(const Config& config) { return protocol::ubx::gnss_capabilities(config.generation).defaults; }

bool coast_as_no_fix(const Config& config) {
  return config.receiver.filter.coast_report == receiver::CoastReport::kNoFix;
}

protocol::ubx::DeviceSetup device_setup(const Config& config, SystemSet nav_systems) {
  protocol::ubx::DeviceSetup s;
  s.mon_ver = protocol::ubx::mon_ver_of(config.generation);
  s.raw_firmware = config.raw_data;
  s.nav_period_s = 1.0 / config.rate_hz;
  const receiver::NavFilterConfig& f = config.receiver.filter;
  s.dyn_model = static_cast<std::uint8_t>(f.dynamic_model);
  s.static_hold_thresh_cm_s = static_cast<std::uint8_t>(std::lround(f.static_hold_speed_m_s * 100.0));
  s.static_hold_max_dist_m = static_cast<std::uint16_t>(std::lround(f.static_hold_max_dist_m));
  s.coast_as_no_fix = coast_as_no_fix(config);
  s.sky_systems = config.world.systems.intersect(nav_systems);
  for (const OutputPortConfig& p : config.outputs) s.outputs.push_back(output_setup(p));
  return s;
}

}  // namespace gnssemu::config
