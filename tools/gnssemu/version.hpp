// SPDX-License-Identifier: Apache-2.0
#pragma once
// `gnssemu version`: versions of gnssemu and the libraries its models rest on.
#include <ostream>

namespace gnssemu::cli {

/// Writes "gnssemu X (git C)", "Embree X", "GeographicLib X", one per line.
void write_version(std::ostream& out);

}  // namespace gnssemu::cli
