// SPDX-License-Identifier: Apache-2.0
#pragma once
// The status page and report assets (web/), and Chart.js from Debian's
// libjs-chart.js, compiled into the binaries (web/embed_assets.cmake), so
// gnssemud and `gnssemu batch --report` need no files at run time.
#include <span>
#include <string_view>

namespace gnssemu::web {

struct Asset {
  std::string_view url;           ///< served path, e.g. "/status.js"
  std::string_view content_type;  ///< HTTP Content-Type
  std::string_view text;          ///< the file
};

/// Every embedded asset.
std::span<const Asset> assets() noexcept;

/// The asset served at url ("/" is "/index.html"); nullptr when there is none.
const Asset* find_asset(std::string_view url) noexcept;

}  // namespace gnssemu::web
