// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu sky` and `gnssemu dop`: what a receiver at a fixed site sees at one
// instant, through the receiver module's own geometry and DOP code.
#include <ostream>

#include "core/common/sat_id.hpp"
#include "core/common/vec3.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/scene/propagator.hpp"
#include "core/time/gps_time.hpp"

namespace gnssemu::cli {

struct SkyRequest {
  time::GpsTime t;        ///< receive time, GPS
  Lla rx_lla;             ///< receiver (lat/lon rad, ellipsoidal height m)
  double mask_rad = 0.0;  ///< elevation mask, rad [0, pi/2)
  orbit::KlobucharParams klobuchar;  ///< nav header's broadcast iono (invalid: RTKLIB defaults)
  const scene::Scene* scene = nullptr;  ///< buildings (built in the ENU frame of scene_origin), optional
  Lla scene_origin;                     ///< origin of the scene's local frame
  scene::SearchConfig search;           ///< reflection search effort
  SystemSet systems = SystemSet::all();  ///< the systems whose satellites count (--systems)
};

/// Writes `sat,prn,az_deg,el_deg,range_m,iono_klobuchar_m,tropo_zhd_m,
/// nmf_hydro,nmf_wet,atten_db,cn0_dbhz` (sat: RINEX name, G05) per healthy
/// satellite of req.systems at or above the mask, in SatId order:
/// satellite at its transmit time, rotated for Earth rotation during the
/// signal flight (Sagnac), geometric range; then the broadcast Klobuchar delay
/// at L1 (req.klobuchar), the receiver's standard-atmosphere zenith
/// hydrostatic delay (Saastamoinen), the Niell mapping functions at that
/// elevation and day of year, and the default world's attenuation (gases over
/// the shells; no clouds or rain) and C/N0 (default link budget, countryside).
/// With req.scene, also `los,bounces,nlos_delay_m,path_loss_db` (los 1 direct,
/// 0 blocked; a blocked satellite without a reflection path has empty delay
/// and loss: not received).
/// Returns the number of rows.
int write_sky(const orbit::EphemerisStore& store, const SkyRequest& req, std::ostream& out);

/// An error-free receiver that tracks every satellite of systems at or above
/// mask_rad (rad), so its fix sits on the truth and its DOP is the
/// geometry's (the world's atmosphere and the receiver's corrections stay at
/// their defaults).
pipeline::PipelineConfig geometry_config(double mask_rad, SystemSet systems = SystemSet::all());

struct DopResult {
  int nsat = 0;          ///< satellites at or above the mask
  bool defined = false;  ///< false: fewer than 4 or singular geometry (DOP fields empty)
};

/// Writes `gdop,pdop,hdop,vdop,tdop,nsat` (one row) for the satellites of
/// req.systems at or above the mask, from the receiver's own solution (errors off, every
/// satellite tracked) at the site.
DopResult write_dop(const orbit::EphemerisStore& store, const SkyRequest& req, std::ostream& out);

}  // namespace gnssemu::cli
