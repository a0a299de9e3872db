// SPDX-License-Identifier: Apache-2.0
#pragma once
// One receiver of a file's vehicles as gnssemud runs it, for the daemon and
// gnssemu batch --vehicle alike.
#include "config/config.hpp"

namespace gnssemu::config {

/// The configuration receiver r of vehicle v runs on: top with r's merged
/// settings (the sky's seed stays top's), r's outputs as its [[output]]s and
/// v's id as its [truth] vehicle, without vehicles of its own.
Config receiver_config(const Config& top, const VehicleConfig& v, const VehicleReceiverConfig& r);

}  // namespace gnssemu::config
