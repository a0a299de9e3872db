#!/usr/bin/env bash
# Install what is missing, build everything with tests in Release (build/,
# warnings as errors), run all tests (unit, golden, integration). Exit status: ctest's.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

"$root/tools/install-deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DGNSSEMU_BUILD_TESTS=ON -DGNSSEMU_WERROR=ON
cmake --build "$root/build" -j"$(nproc)"
exec ctest --test-dir "$root/build" --output-on-failure
