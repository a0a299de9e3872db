// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/batch/batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "config/setup/device_setup.hpp"
#include "config/setup/pipeline_setup.hpp"
#include "config/setup/scene_loader.hpp"
#include "core/common/error.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/statistics/statistics.hpp"

namespace gnssemu::cli {

namespace {

constexpr double kGridTolerance_s = 1e-6;

}  // namespace

BatchSummary run_batch(const config::Config& config, const orbit::NavData& nav, const world::TruthTrack& track,
                       std::ostream* nmea, std::ostream* errors, std::ostream* ubx, orbit::StoreOptions store_options,
                       std::span<BatchObserver* const> observers, const std::vector<faults::FaultEvent>* scenario) {
  if (!(config.rate_hz > 0.0) || !std::isfinite(config.rate_hz)) {
    throw Error(config.source, 0, "rate_hz must be positive");
  }
  const double rate_hz = config.rate_hz;
  const time::GpsTime first = track.first();
  const int32_t week = first.week();
  // First grid epoch at or after the first truth sample.
  const double k0 = std::ceil(first.tow_s() * rate_hz - kGridTolerance_s * rate_hz);
  if (time::GpsTime(week, k0 / rate_hz) - track.last() > kGridTolerance_s) {
    throw Error(fmt::format("truth spans no epoch at {} Hz: it runs from week {} tow {:.3f} to week {} tow {:.3f}",
                            rate_hz, first.week(), first.tow_s(), track.last().week(), track.last().tow_s()));
  }

  const orbit::EphemerisStore store(nav.ephemerides, store_options);
  scene::MeshStats mesh_stats;
  const std::unique_ptr<scene::Scene> buildings = config::load_scene(config, &mesh_stats);
  const std::unique_ptr<pipeline::Pipeline> rx =
      config::make_pipeline(config, store, pipeline::broadcast_of(nav), buildings.get());
  if (scenario != nullptr) rx->set_faults(*scenario);
  // The daemon's emulated u-blox; its first output (a factory UART1 when
  // there is none) writes the NMEA and UBX logs. It powers on at the first epoch.
  protocol::ubx::Device device(config::device_setup(config, orbit::systems_of(nav)));
  config::apply_chip_settings(device, rx->receiver());  // as the daemon: the chip's CFG-GNSS, NAV5, rate
  protocol::ubx::MessageList messages;
  time::GpsTime power_on;
  fmt::memory_buffer row;

  BatchSummary sum;
  sum.scene = buildings != nullptr;
  sum.mesh_skipped = mesh_stats.skipped();
  sum.mesh_report = scene::skip_report(mesh_stats);
  if (errors) {
    *errors << "gps_week,tow_s,fix_type,nsat,e_m,n_m,u_m,hdop,vdop,pdop,hacc_m,vacc_m"
            << (sum.scene ? ",nvisible,ntracked,nlos,nblocked,nlos_delay_mean_m\n" : "\n");
  }
  long visible_sum = 0, nlos_sum = 0, blocked_sum = 0;
  std::vector<double> e_err, n_err, h_err, v_err;
  for (double k = k0;; k += 1.0) {
    const time::GpsTime t(week, k / rate_hz);
    if (t - track.last() > kGridTolerance_s) break;
    const world::Truth truth = track.at(t);
    const receiver::Fix& fix = rx->step(t, truth);
    if (sum.epochs == 0) power_on = t;
    ++sum.epochs;
    // The device feeds only the NMEA and UBX logs: without them its
    // encoding (a tenth of an epoch) is skipped.
    if (nmea != nullptr || ubx != nullptr) {
      const receiver::RawEpoch& raw = rx->receiver().raw();
      device.on_epoch(fix, t - power_on, protocol::ubx::RawSource{&raw, &store, {&nav.klobuchar, &nav.utc, raw.leap_seconds}, &nav.galileo_nequick, &nav.beidou_klobuchar});
      device.compose({}, messages, protocol::ubx::Layout::kLine);
      for (const protocol::ubx::MessageList::Message& m : messages.messages()) {
        std::ostream* log = m.protocol == protocol::ubx::Protocol::kNmea ? nmea : ubx;
        const std::string_view bytes = messages.bytes(m);
        if (log != nullptr) log->write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      }
    }
    // A position without truth (the receiver coasting through an antenna
    // loss) has nothing to be compared with; dead reckoning is reported in
    // the rows (fix_type 1) but is not a GNSS fix in the summary.
    const bool has_fix = fix.type != receiver::FixType::kNone && truth.valid;
    const bool gnss_fix = has_fix && receiver::is_gnss_fix(fix.type);
    Enu d;
    if (has_fix) {
      const Lla truth_lla = geo::lla_from_ecef(truth.pos_m);
      d = geo::ecef_to_enu_vector(fix.pos_m - truth.pos_m, truth_lla.lat_rad, truth_lla.lon_rad);
    }
    if (gnss_fix) {
      ++sum.fixes;
      if (fix.type == receiver::FixType::k3D) ++sum.fixes_3d;
      e_err.push_back(d.x);
      n_err.push_back(d.y);
      h_err.push_back(std::hypot(d.x, d.y));
      v_err.push_back(d.z);
    }
    if (errors) {
      row.clear();
      fmt::format_to(std::back_inserter(row), "{},{:.3f},{},{},", t.week(), t.tow_s(), static_cast<int>(fix.type),
                     fix.num_used);
      if (has_fix) {
        fmt::format_to(std::back_inserter(row), "{:.4f},{:.4f},{:.4f},", d.x, d.y, d.z);
      } else {
        fmt::format_to(std::back_inserter(row), ",,,");
      }
      fmt::format_to(std::back_inserter(row), "{:.2f},{:.2f},{:.2f},{:.3f},{:.3f}", fix.dop.hdop, fix.dop.vdop,
                     fix.dop.pdop, fix.h_acc_m, fix.v_acc_m);
    }
    if (sum.scene) {
      int nlos = 0, blocked = 0;
      double delay_m = 0.0;
      for (int i = 0; i < fix.num_sats; ++i) {
        const receiver::SatInfo& si = fix.sats[i];
        if (!si.above_mask) continue;
        blocked += si.blocked;
        if (si.tracked && si.nlos) {
          ++nlos;
          delay_m += si.nlos_delay_m;
        }
      }
      visible_sum += fix.num_visible;
      nlos_sum += nlos;
      blocked_sum += blocked;
      if (errors) {
        fmt::format_to(std::back_inserter(row), ",{},{},{},{},{:.3f}", fix.num_visible, fix.num_tracked, nlos, blocked,
                       nlos > 0 ? delay_m / nlos : 0.0);
      }
    }
    if (errors) {
      row.push_back('\n');
      errors->write(row.data(), static_cast<std::streamsize>(row.size()));
    }
    for (BatchObserver* o : observers) o->on_raw(t, rx->receiver().raw(), truth);
    for (BatchObserver* o : observers) o->on_epoch(t, fix, truth);
  }
  if (sum.epochs > 0) {
    sum.mean_visible = static_cast<double>(visible_sum) / sum.epochs;
    sum.mean_nlos = static_cast<double>(nlos_sum) / sum.epochs;
    sum.mean_blocked = static_cast<double>(blocked_sum) / sum.epochs;
  }
  sum.h_rms_m = statistics::rms(h_err);
  sum.h_95_m = statistics::percentile_nearest_rank(h_err, 0.95);
  sum.h_max_m = statistics::max_abs(h_err);
  sum.v_rms_m = statistics::rms(v_err);
  sum.mean_e_m = statistics::mean(e_err);
  sum.mean_n_m = statistics::mean(n_err);
  sum.mean_u_m = statistics::mean(v_err);
  for (double& v : v_err) v = std::fabs(v);
  sum.v_95_m = statistics::percentile_nearest_rank(v_err, 0.95);
  sum.v_max_m = statistics::max_abs(v_err);
  return sum;
}

void write_summary(const BatchSummary& s, std::ostream& out) {
  const double avail = s.epochs > 0 ? 100.0 * s.fixes / s.epochs : 0.0;
  out << fmt::format("epochs {}  fixes {} ({:.1f}%)  3D {}\n", s.epochs, s.fixes, avail, s.fixes_3d);
  if (s.scene) {
    out << fmt::format("scene: per epoch {:.2f} above mask, {:.2f} NLOS (reflections only), {:.2f} blocked\n",
                       s.mean_visible, s.mean_nlos, s.mean_blocked);
    if (!s.mesh_report.empty()) out << "scene " << s.mesh_report << '\n';
  }
  if (s.fixes == 0) {
    out << "no fix: no error statistics\n";
    return;
  }
  out << fmt::format("horizontal error  rms {:.3f} m  95% {:.3f} m  max {:.3f} m\n", s.h_rms_m, s.h_95_m, s.h_max_m);
  out << fmt::format("vertical error    rms {:.3f} m  95% {:.3f} m  max {:.3f} m\n", s.v_rms_m, s.v_95_m, s.v_max_m);
  out << fmt::format("mean error (e, n, u) {:.3f} {:.3f} {:.3f} m\n", s.mean_e_m, s.mean_n_m, s.mean_u_m);
}

}  // namespace gnssemu::cli
