// SPDX-License-Identifier: Apache-2.0
#include "config/setup/nav_setup.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/common/error.hpp"
#include "core/orbit/almanac.hpp"
#include "core/orbit/rinex_nav.hpp"

namespace gnssemu::config {

namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool is_nav_file_name(const std::string& name) {
  std::string n = name;
  if (ends_with(n, ".gz")) n.resize(n.size() - 3);
  // RINEX 2: name.yyn / name.yyN
  if (n.size() >= 4 && n[n.size() - 4] == '.' && std::isdigit(static_cast<unsigned char>(n[n.size() - 3])) &&
      std::isdigit(static_cast<unsigned char>(n[n.size() - 2])) && (n.back() == 'n' || n.back() == 'N')) {
    return true;
  }
  // RINEX 3 long name: ..._GN.rnx, _MN.rnx, ...
  return n.size() >= 8 && ends_with(n, "N.rnx") && n[n.size() - 7] == '_' &&
         std::isupper(static_cast<unsigned char>(n[n.size() - 6]));
}

std::vector<std::string> nav_paths(const Config& c) {
  std::vector<std::string> paths;
  if (!c.nav_file.empty()) paths.push_back(c.nav_file);
  paths.insert(paths.end(), c.nav.files.begin(), c.nav.files.end());
  if (!c.nav.folder.empty()) {
    std::error_code ec;
    std::vector<std::string> found;
    for (const fs::directory_entry& e : fs::directory_iterator(c.nav.folder, ec)) {
      if (e.is_regular_file(ec) && is_nav_file_name(e.path().filename().string())) found.push_back(e.path().string());
    }
    if (ec) throw Error(c.nav.folder, 0, "nav folder cannot be listed: " + ec.message());
    if (found.empty()) throw Error(c.nav.folder, 0, "no RINEX nav files (*.yyn, *_xN.rnx, also .gz) in the nav folder");
    std::sort(found.begin(), found.end());
    paths.insert(paths.end(), found.begin(), found.end());
  }
  if (paths.empty()) throw Error(c.source, 0, "no nav file configured");
  return paths;
}

orbit::NavData load_nav(const Config& c) { return orbit::read_rinex_nav_files(nav_paths(c)); }

orbit::Constellation make_constellation(const Config& c, const orbit::NavData& nav, const time::GpsTime& start) {
  orbit::ConstellationRequest req;
  req.mode = c.nav.mode;
  req.start = start;
  if (c.nav.mode != orbit::NavMode::kAlmanac) return orbit::build_constellation(nav, req);
  if (c.nav.almanac_file.empty()) throw Error(c.source, 0, "nav mode \"almanac\" needs an almanac file (nav.almanac)");
  const std::string& path = c.nav.almanac_file;
  const std::vector<orbit::AlmanacEntry> alm = orbit::read_almanac(path, start.week());
  return orbit::build_constellation(alm, path, nav, req);
}

}  // namespace gnssemu::config
