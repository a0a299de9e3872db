// SPDX-License-Identifier: Apache-2.0
#include "config/setup/device_setup.hpp"

#include <cmath>

#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/config/ubx_hpg.hpp"

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

int default_bands(protocol::ubx::Generation g) noexcept {
  switch (g) {
    case protocol::ubx::Generation::kM8:
    case protocol::ubx::Generation::kM9: return 1;
    case protocol::ubx::Generation::kF9P: return 2;  // L1C/A + L2C, E1 + E5b, B1I + B2I (ZED-F9P datasheet)
  }
  return 1;
}

std::string single_band_reason(protocol::ubx::Generation g) {
  // Neither family has an L2 variant: the M8 and M9 product summaries list L1 signals only.
  switch (g) {
    case protocol::ubx::Generation::kM8: return "the NEO-M8N tracks L1 only; generation = \"f9p\" tracks two bands";
    case protocol::ubx::Generation::kM9: return "the NEO-M9N tracks L1 only; generation = \"f9p\" tracks two bands";
    case protocol::ubx::Generation::kF9P: return "";
  }
  return "";
}

bool default_raw_data(protocol::ubx::Generation g) noexcept {
  return g == protocol::ubx::Generation::kF9P;  // HPG firmware outputs RXM-RAWX/SFRBX (ZED-F9P Integration Manual)
}

SystemSet chip_systems(const Config& config) { return protocol::ubx::gnss_capabilities(config.generation).supported; }

bool coast_as_no_fix(const Config& config) {
  return config.receiver.filter.coast_report == receiver::CoastReport::kNoFix;
}

protocol::ubx::DeviceSetup device_setup(const Config& config, SystemSet nav_systems) {
  protocol::ubx::DeviceSetup s;
  s.mon_ver = protocol::ubx::mon_ver_of(config.generation);
  s.raw_firmware = config.raw_data;
  s.sbas_diffcorr = config.receiver.sbas;
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

void apply_chip_settings(const protocol::ubx::Device& device, receiver::Receiver& rx) noexcept {
  // The CFG-NAV5 handler accepted only dynModels the receiver knows.
  const protocol::ubx::wire::CfgNav5& n = device.config().nav5;
  if (const auto m = receiver::dynamic_model_from_ubx(n.dynModel)) rx.set_dynamic_model(*m);
  rx.set_static_hold(0.01 * n.staticHoldThresh, n.staticHoldMaxDist);
  // CFG-SBAS mode off: no GEO is tracked; usage without diffCorr: none corrects.
  const protocol::ubx::SbasSettings sbas = device.sbas_settings();
  const SystemSet systems = device.enabled_systems();
  rx.set_systems(sbas.enabled ? systems : systems.without(GnssSystem::kSbas));
  rx.set_sbas(sbas.enabled && sbas.diffcorr);
  rx.set_channel_limits(device.channel_limits().per_system);
  const protocol::ubx::NavRateLimits lim = device.nav_rate_limits();
  const double period_s = device.config().nav_period_s();
  const bool capped = period_s > 0.0 && 1.0 / period_s > lim.sat_cap_above_hz + 1e-9;
  rx.set_max_solution_sats(capped ? lim.max_solution_sats : kMaxSatsInView);
  const protocol::ubx::HpgSettings hpg = device.hpg_settings();
  rx.set_dgnss_timeout_s(hpg.dgnss_timeout_s);
  rx.set_rtk_fix_ambiguities(hpg.dgnss_mode == protocol::ubx::DgnssMode::kRtkFixed);
}

}  // namespace gnssemu::config
