// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu batch`: the daemon's code path (config -> ephemeris store ->
// make_pipeline -> encoders) run over a truth trajectory faster than real time.
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "core/faults/fault_event.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/receiver/raw_measurements.hpp"
#include "core/world/truth_track.hpp"

namespace gnssemu::cli {

/// Fix statistics of a batch run. Errors are fix minus truth in local ENU at
/// the truth position; horizontal = hypot(e, n), vertical = |u|. The error
/// figures are NaN when no epoch had a fix.
struct BatchSummary {
  int epochs = 0;
  int fixes = 0;     ///< epochs with a 2D or 3D fix
  int fixes_3d = 0;
  double h_rms_m = 0.0, h_95_m = 0.0, h_max_m = 0.0;
  double v_rms_m = 0.0, v_95_m = 0.0, v_max_m = 0.0;
  double mean_e_m = 0.0, mean_n_m = 0.0, mean_u_m = 0.0;
  // With a [scene]: per-epoch means of satellites above the mask, received
  // via reflections only (NLOS), and blocked (not received).
  bool scene = false;
  double mean_visible = 0.0, mean_nlos = 0.0, mean_blocked = 0.0;
  int mesh_skipped = 0;  ///< mesh elements the reader skipped
  std::string mesh_report;  ///< scene::skip_report of the mesh, \"\" when nothing was skipped
};

/// Sees every epoch of run_batch after it ran (the --sats CSV, the report).
class BatchObserver {
public:
  virtual ~BatchObserver() = default;
  virtual void on_epoch(const time::GpsTime& t, const receiver::Fix& fix, const world::Truth& truth) = 0;
  /// The receiver's raw measurements of the epoch, before on_epoch.
  virtual void on_raw(const time::GpsTime& /*t*/, const receiver::RawEpoch& /*raw*/, const world::Truth& /*truth*/) {}
};

/// Run the receiver, set up as the daemon sets it up from the nav file (its
/// ephemerides, its header's leap seconds), at config.rate_hz on the GPS-time grid (multiples of
/// 1/rate s of week) from the first to the last truth time. nmea and ubx: the
/// NMEA and UBX streams of the first configured output port, under its
/// message rates (u-blox default NMEA set and no UBX when there is none);
/// the emulated receiver powers on at the first epoch. errors: CSV
/// `gps_week,tow_s,fix_type,nsat,e_m,n_m,u_m,hdop,vdop,pdop,hacc_m,vacc_m`
/// (hacc_m, vacc_m: what the receiver reports about itself), plus
/// `nvisible,ntracked,nlos,nblocked,nlos_delay_mean_m` when the config has a [scene].
/// Either may be null. Throws gnssemu::Error when the truth spans no epoch.
/// store: how the ephemeris store treats times past the data (the daemon's
/// constellation continues the orbits; orbit::Constellation::store_options).
/// observers: told of every epoch, in order. scenario: fault events (start
/// times from the first epoch) applied between world and receiver; null: no
/// fault stage.
BatchSummary run_batch(const config::Config& config, const orbit::NavData& nav, const world::TruthTrack& track,
                       std::ostream* nmea, std::ostream* errors, std::ostream* ubx = nullptr,
                       orbit::StoreOptions store = {}, std::span<BatchObserver* const> observers = {},
                       const std::vector<faults::FaultEvent>* scenario = nullptr);

/// Human-readable summary (for stderr).
void write_summary(const BatchSummary& summary, std::ostream& out);

}  // namespace gnssemu::cli
