// SPDX-License-Identifier: Apache-2.0
#pragma once
// The project's layer table (docs/architecture.md draws it).
#include "include_rules.hpp"

namespace gnssemu::layering {

/// Layers, third-party confinement and exceptions of this project.
Rules project_rules();

}  // namespace gnssemu::layering
