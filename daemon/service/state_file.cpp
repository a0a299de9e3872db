// SPDX-License-Identifier: Apache-2.0
#include "daemon/service/state_file.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace gnssemu::daemon {

bool load_state_file(const std::string& path, protocol::ubx::Device& device) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream text;
  text << in.rdbuf();
  protocol::ubx::DeviceConfig saved = protocol::ubx::DeviceConfig::factory_defaults(device.outputs(), device.generation());
  saved.read_text(text.str(), path);
  device.load_saved(saved);
  return true;
}

std::string save_state_file(const std::string& path, const protocol::ubx::Device& device) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return "cannot write " + tmp;
    out << device.saved().to_text();
    if (!out.flush()) return "cannot write " + tmp;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) return "cannot rename " + tmp + " to " + path;
  return {};
}

}  // namespace gnssemu::daemon
