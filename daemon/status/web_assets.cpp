// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/web_assets.hpp"

namespace gnssemu::web {

const Asset* find_asset(std::string_view url) noexcept {
  if (url == "/") url = "/index.html";
  for (const Asset& a : assets())
    if (a.url == url) return &a;
  return nullptr;
}

}  // namespace gnssemu::web
