#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Install what is missing, build gnssemu in Release (build/), run the daemon.
#   tools/run.sh                  # the embedded default: demo trajectory, NMEA on /tmp/gnssemu/gps0
#   tools/run.sh --config my.toml # any gnssemud arguments are passed through
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

"$root/tools/install-deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$root/build" --target gnssemud gnssemu -j"$(nproc)"
exec "$root/build/daemon/gnssemud" "$@"
