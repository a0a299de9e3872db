// SPDX-License-Identifier: Apache-2.0
#pragma once
// The emulated u-blox's start-up settings from a configuration: every
// [[output]] is one UART1 of one chip (docs/ports.md), set up as its
// section says and saved as the chip's stored configuration.
#include <string>

#include "config/config.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/receiver/receiver.hpp"

namespace gnssemu::config {

/// UART1 of one output: baud, protocols, every message of message_rates(port),
/// NMEA version and course threshold.
protocol::ubx::OutputSetup output_setup(const OutputPortConfig& port);

/// Whether the chip flags the receiver's extrapolation as no fix
/// ([receiver.nav] coast_report; DeviceSetup::coast_as_no_fix).
bool coast_as_no_fix(const Config& config);

/// Every system the emulated chip can track (its generation's): the systems
/// in the sky when [receiver] constellations is not given, so that a host
/// enabling one by CFG-GNSS / CFG-SIGNAL finds its satellites there.
SystemSet chip_systems(const Config& config);

/// Signals the chip tracks per satellite by default ([receiver] bands when
/// not given): 1 for the single-band M8 and M9, 2 for the F9P.
int default_bands(protocol::ubx::Generation g) noexcept;
/// Why a chip that tracks one band cannot take bands = 2 (config errors);
/// empty for the F9P.
std::string single_band_reason(protocol::ubx::Generation g);

/// Whether the chip's standard firmware outputs raw data ([receiver] raw_data
/// when not given): the F9P's does, the NEO-M8N's and NEO-M9N's do not.
bool default_raw_data(protocol::ubx::Generation g) noexcept;

/// The chip behind config's outputs, at epoch period 1 / rate_hz. Its sky
/// is [receiver] constellations among nav_systems (the systems the nav data
/// holds: orbit::systems_of).
protocol::ubx::DeviceSetup device_setup(const Config& config, SystemSet nav_systems = SystemSet::all());

/// What the chip's configuration makes the receiver do, as the host set it:
/// CFG-NAV5 dynModel and static hold, the systems CFG-GNSS / CFG-SIGNAL-*
/// enable, and the solution's satellite cap at the CFG-RATE navigation rate
/// (NavRateLimits). The daemon and batch call it at start and after every
/// change of those settings.
void apply_chip_settings(const protocol::ubx::Device& device, receiver::Receiver& rx) noexcept;

}  // namespace gnssemu::config
