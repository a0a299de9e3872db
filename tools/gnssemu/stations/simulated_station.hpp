// SPDX-License-Identifier: Apache-2.0
#pragma once
// A station-day as the world makes it: for every epoch of a real
// observation file, the world's code pseudoranges and C/N0 at the station's
// antenna, written as observation data so the same single-point solver
// (cli::spp_error_series) runs on real and simulated observations
// (docs/validation.md, "An error model that holds on unseen stations").
#include "core/common/gnss_systems.hpp"
#include "core/common/vec3.hpp"
#include "core/observation/obs_data.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/world/world_config.hpp"

namespace gnssemu::cli {

/// The world's observations of a static antenna at antenna_m (ECEF m) at the
/// epochs of real (its receiver time tags taken as GPS time), with the
/// broadcast Klobuchar of nav shaping the world's ionosphere; per system of
/// systems its L1-band code and C/N0 (C1C S1C; BeiDou C2I S2I), satellites at
/// or above mask_rad. Deterministic for world.seed.
observation::ObsData simulate_station(const observation::ObsData& real, const orbit::NavData& nav,
                                      const orbit::EphemerisStore& store, const world::WorldConfig& world,
                                      const Ecef& antenna_m, double mask_rad,
                                      SystemSet systems = SystemSet::only(GnssSystem::kGps));

/// The antenna reference point of a RINEX header: APPROX POSITION XYZ plus
/// the ANTENNA: DELTA H/E/N eccentricity (up, east, north at the marker).
/// Throws gnssemu::Error when the header has no position.
Ecef antenna_reference_point(const observation::ObsHeader& h, const std::string& source);

}  // namespace gnssemu::cli
