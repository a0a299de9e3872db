// SPDX-License-Identifier: Apache-2.0
#pragma once
// The emulated chip's state file: its saved configuration (BBR/flash) kept
// across gnssemud restarts ([receiver] state_file, docs/ubx.md "Saved
// configuration"). The text format is the core's (DeviceConfig::to_text).
#include <string>

#include "core/protocol/ubx/device/ubx_device.hpp"

namespace gnssemu::daemon {

/// Power the device up from path when the file exists (the saved
/// configuration becomes the current one); false when there is none yet.
/// Throws gnssemu::Error("path:line: reason") for a malformed file.
bool load_state_file(const std::string& path, protocol::ubx::Device& device);

/// Write device.saved() to path (a temporary file renamed over it, so a
/// crash never leaves half a file). Returns "" or the reason it failed.
std::string save_state_file(const std::string& path, const protocol::ubx::Device& device);

}  // namespace gnssemu::daemon
