// SPDX-License-Identifier: Apache-2.0
#include "daemon/service/config_locator.hpp"

#include <filesystem>

namespace gnssemu::daemon {

std::vector<std::string> default_config_candidates(const std::string& exe_path) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  if (!exe_path.empty()) {
    const fs::path dir = fs::path(exe_path).parent_path();
    out.push_back((dir / "default.toml").string());
    out.push_back((dir / "config" / "default.toml").string());
    out.push_back((dir / ".." / "share" / "gnssemu" / "default.toml").lexically_normal().string());
  }
  out.push_back(std::string(GNSSEMU_INSTALL_DATADIR) + "/default.toml");
  out.push_back(std::string(GNSSEMU_SOURCE_CONFIG_DIR) + "/default.toml");
  return out;
}

std::string find_default_config(const std::string& exe_path) {
  std::error_code ec;
  for (const auto& p : default_config_candidates(exe_path)) {
    if (std::filesystem::is_regular_file(p, ec)) return p;
  }
  return {};
}

}  // namespace gnssemu::daemon
