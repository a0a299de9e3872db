// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/status_setup.hpp"

#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/ip/address.hpp>

#include "core/common/constants.hpp"

namespace gnssemu::daemon {

StatusSettings status_settings(const config::Config& cfg) {
  StatusSettings s;
  s.elevation_mask_deg = cfg.receiver.elevation_mask_rad * kRadToDeg;
  s.acquire_dbhz = cfg.receiver.tracking.acquire_dbhz;
  s.lose_dbhz = cfg.receiver.tracking.lose_dbhz;
  s.rate_hz = cfg.rate_hz;
  s.time_mode = cfg.time.mode == config::TimeMode::kRealtime ? "realtime" : "lockstep";
  return s;
}

bool is_loopback(const std::string& bind) {
  boost::system::error_code ec;
  const boost::asio::ip::address a = boost::asio::ip::make_address(bind, ec);
  return !ec && a.is_loopback();
}

}  // namespace gnssemu::daemon
