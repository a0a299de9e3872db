// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/base_command.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "config/setup/base_station.hpp"
#include "config/setup/nav_setup.hpp"
#include "config/setup/scene_loader.hpp"
#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/protocol/rtcm/rtcm_ephemeris.hpp"

namespace gnssemu::cli {

BaseCommand::BaseCommand(CLI::App& app) {
  cmd_ = app.add_subcommand("base", "run the [base] reference station over a time span and write its RTCM 3 stream");
  cmd_->add_option("--config", config_, "gnssemu TOML configuration (its [receiver] settings and nav)")->required();
  cmd_->add_option("--lat", lat_deg_, "base latitude, deg [-90, 90]")->required();
  cmd_->add_option("--lon", lon_deg_, "base longitude, deg [-180, 180]")->required();
  cmd_->add_option("--height", height_m_, "base height above the WGS-84 ellipsoid, m")->required();
  cmd_->add_option("--station-id", station_id_, "RTCM station id DF003 [0, 4095]")->capture_default_str();
  cmd_->add_option("--messages", messages_, "messages and intervals, str2str -msg syntax: 1005(10),1077(1),1019(60)")
      ->required();
  cmd_->add_option("--seed", seed_, "the base's own seed (default: the configuration's)");
  cmd_->add_flag("--open-sky", open_sky_,
                 "the base sees none of the configuration's [scene] buildings (default: it stands in them at its "
                 "position, as gnssemud's [base] does)");
  cmd_->add_option("--week", week_, "GPS week of the first epoch")->required();
  cmd_->add_option("--tow", tow_s_, "GPS time of week of the first epoch, s")->required();
  cmd_->add_option("--duration", duration_s_, "seconds to run (> 0)")->capture_default_str();
  cmd_->add_option("--out", out_path_, "RTCM 3 output file")->required();
  cmd_->add_option("--raw-csv", raw_csv_, "write the encoded raw observations as CSV here");
  cmd_->add_option("--eph-csv", eph_csv_, "write the encoded ephemerides as CSV here");
}

int BaseCommand::run(std::ostream& out, std::ostream& err) {
  (void)out;
  if (!(duration_s_ > 0.0) || duration_s_ > 86400.0) throw Error("--duration must be in (0, 86400] s");
  if (station_id_ < 0 || station_id_ > 4095) throw Error("--station-id must be in [0, 4095]");
  config::Config cfg = config::load_config(config_);
  config::BaseConfig b;
  b.position = Lla{lat_deg_ * kDegToRad, lon_deg_ * kDegToRad, height_m_};
  b.station_id = station_id_;
  b.settings = config::receiver_settings(cfg);
  if (seed_ >= 0) b.settings.world.seed = static_cast<std::uint64_t>(seed_);
  b.open_sky = open_sky_;
  b.messages = config::parse_base_messages(messages_, "--messages", 0);
  cfg.base = b;
  if (const std::string w = config::base_distance_warning(cfg); !w.empty()) err << "gnssemu base: " << w << '\n';

  const time::GpsTime start(week_, tow_s_);
  const orbit::Constellation c = config::make_constellation(cfg, config::load_nav(cfg), start);
  const orbit::EphemerisStore store(c.nav.ephemerides, c.store_options());
  scene::MeshStats mesh_stats;
  const std::unique_ptr<scene::Scene> buildings = open_sky_ ? nullptr : config::load_scene(cfg, &mesh_stats);
  if (const std::string skipped = scene::skip_report(mesh_stats); !skipped.empty()) err << "gnssemu base: scene " << skipped << '\n';
  config::BaseStation base(cfg, store, pipeline::broadcast_of(c.nav), buildings.get());

  std::ofstream rtcm(out_path_, std::ios::binary);
  if (!rtcm) throw Error("cannot write " + out_path_);
  std::ofstream raw_csv, eph_csv;
  if (!raw_csv_.empty()) {
    raw_csv.open(raw_csv_);
    raw_csv << "week,tow_s,sat,code,pseudorange_m,carrier_cycles,doppler_hz,cn0_dbhz,lock_s,half_cycle_resolved\n";
  }
  if (!eph_csv_.empty()) {
    eph_csv.open(eph_csv_);
    eph_csv << "sat,toe_week,toe_tow_s,sqrt_a,e,i0,omega0,omega,m0,af0,pos_x_m,pos_y_m,pos_z_m\n";
  }
  std::string buf;
  const double step_s = 1.0 / base.rate_hz();
  const double k0 = std::ceil(start.tow_s() / step_s - 1e-9);
  std::vector<std::pair<SatId, double>> eph_seen;
  for (double k = k0;; k += 1.0) {
    const time::GpsTime t(start.week(), k * step_s);
    if (t - start > duration_s_ + 1e-9) break;
    buf.clear();
    base.step(t, buf);
    rtcm.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    const receiver::RawEpoch& raw = base.raw();
    for (int i = 0; raw_csv.is_open() && i < raw.num_meas; ++i) {
      const receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(i)];
      if (!m.pseudorange_valid) continue;
      raw_csv << fmt::format("{},{:.9f},{},{},{:.4f},{:.4f},{:.4f},{:.2f},{:.3f},{}\n", raw.t_rx.week(),
                             raw.t_rx.tow_s(), sat_name(m.sat).data(), signal_info(m.signal).rinex_code, m.pseudorange_m,
                             m.carrier_phase_cycles, m.doppler_hz, m.cn0_dbhz, m.lock_time_s,
                             m.half_cycle_resolved ? 1 : 0);
    }
    for (int i = 0; eph_csv.is_open() && i < raw.num_meas; ++i) {
      const SatId sat = raw.meas[static_cast<std::size_t>(i)].sat;
      // What the base sent at t: its ephemeris message for the system is due.
      const bool sent = std::any_of(b.messages.begin(), b.messages.end(), [&](const config::BaseMessage& m) {
        const double n = t.tow_s() / m.interval_s;
        return m.number == protocol::rtcm::ephemeris_message_number(sat.system) &&
               std::abs(n - std::round(n)) * m.interval_s < 1e-3;
      });
      const orbit::Ephemeris* e = sent ? store.select(sat, t) : nullptr;
      if (e == nullptr) continue;
      const std::pair<SatId, double> key{sat, e->toe.total_s()};
      if (std::find(eph_seen.begin(), eph_seen.end(), key) != eph_seen.end()) continue;
      eph_seen.push_back(key);
      eph_csv << fmt::format("{},{},{:.3f},{:.10e},{:.10e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.3f},{:.3f},{:.3f}\n",
                             sat_name(sat).data(), e->toe.week(), e->toe.tow_s(), e->sqrt_a_sqrtm, e->e, e->i0_rad,
                             e->omega0_rad, e->omega_rad, e->m0_rad, e->af0_s, e->pos_m.x, e->pos_m.y, e->pos_m.z);
    }
  }
  const config::BaseStats& s = base.stats();
  err << fmt::format("gnssemu base: {} epochs, {} messages, {} bytes ({:.0f} bytes/s), {} signals dropped\n", s.epochs,
                     s.messages, s.bytes, static_cast<double>(s.bytes) / duration_s_, s.dropped_cells);
  return 0;
}

}  // namespace gnssemu::cli
