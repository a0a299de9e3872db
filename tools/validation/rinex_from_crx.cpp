// SPDX-License-Identifier: Apache-2.0
// Compact RINEX (.crx, .crx.gz) to plain RINEX on stdout with the project's
// own decoder, for tools that read plain files only (RTKLIB's rnx2rtkp in
// tests/integration/offline/spp_vs_rtklib.py and docs/validation.md).
#include <cstdio>
#include <exception>
#include <memory>

#include "core/common/error.hpp"
#include "core/common/line_source.hpp"
#include "core/common/text_fields.hpp"
#include "core/observation/obs_lines.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: rinex_from_crx FILE.crx[.gz] > FILE.rnx\n");
    return 2;
  }
  try {
    gnssemu::text::LineSource src(argv[1], gnssemu::text::LineLimits{});
    const std::unique_ptr<gnssemu::observation::ObsLines> lines = gnssemu::observation::open_obs_lines(src);
    gnssemu::text::Line l;
    while (lines->next(l)) {
      std::fwrite(l.text.data(), 1, l.text.size(), stdout);
      std::fputc('\n', stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rinex_from_crx: %s\n", e.what());
    return 1;
  }
  return 0;
}
