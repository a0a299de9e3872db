#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Install what is missing, then three timed stages (docs/robustness.md §CI):
#   1. build/       Release, gcc, warnings as errors; and build/fuzz, the clang
#                   libFuzzer build (tests/fuzz/fuzz.sh build)
#   2. build/       every test: unit, golden, integration, fuzz replays and a
#                   5 s libFuzzer run per target (ctest label fuzz)
#   3. build-asan/  GNSSEMU_SANITIZE=address,undefined: what ctest -L unit runs
#                   (target unit_tests: unit tests, fuzz replays), under ASan+UBSan;
#                   built during stage 2 at the lowest CPU and I/O priority
# Options: --no-asan skips stage 3. Exit status: the first failing stage's.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"
asan=1
for arg in "$@"; do
  case "$arg" in
    --no-asan) asan=0 ;;
    *) echo "usage: tools/test.sh [--no-asan]" >&2; exit 2 ;;
  esac
done

# Wall and CPU time of each stage: CPU (user + system of every child) tells
# what a stage costs on an idle machine when others share the cores.
stage_start=0
stage_cpu=0
times_file="$(mktemp)"
asan_pid=""
cleanup() {
  rm -f "$times_file"
  if [ -n "$asan_pid" ]; then kill -- "-$asan_pid" 2>/dev/null || kill "$asan_pid" 2>/dev/null || true; fi
}
trap cleanup EXIT
# Sets cpu: user + system seconds of every child so far. `times` runs in
# this shell: in a $(...) subshell it would count that subshell's children.
cpu=0
cpu_now() {
  times >"$times_file"
  cpu=$(awk 'NR == 2 { split($0, f, /[ ms]+/); print int(f[1] * 60 + f[2] + f[3] * 60 + f[4]) }' "$times_file")
}
stage() { stage_start=$(date +%s); cpu_now; stage_cpu=$cpu; echo "== test.sh: $*" >&2; }
stage_done() {
  cpu_now
  echo "== test.sh: $1 took $(( $(date +%s) - stage_start )) s wall, $(( cpu - stage_cpu )) s CPU" >&2
}

"$root/tools/install-deps.sh"

stage "build (gcc, Release, -Werror) and the fuzz build (clang)"
# Fuzz smoke 5 s per target (default 10): the first cut docs/robustness.md §CI names for the 20-minute budget.
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DGNSSEMU_BUILD_TESTS=ON -DGNSSEMU_WERROR=ON \
  -DGNSSEMU_FUZZ_SMOKE_S=5
cmake --build "$root/build" -j"$jobs"
GNSSEMU_JOBS="$jobs" "$root/tests/fuzz/fuzz.sh" build --build-dir "$root/build/fuzz" || [ $? -eq 77 ]
stage_done build

if [ "$asan" -eq 1 ]; then
  # Stage 3's build runs beside stage 2: the tests mostly wait on daemons, gpsd
  # and wall-clock epochs (about 100 s of CPU in 360 s), so a compile at nice
  # 19 / idle I/O takes the idle core time and yields whenever a test wants
  # the CPU. Warnings are errors in stage 1; here GCC's -Wmaybe-uninitialized
  # gives false positives on instrumented code (std::regex's std::function).
  # -O1, as the sanitizers advise: 40 % less compile time than -O3. Only what
  # the unit tests run: stage 1 builds and runs the tools and benchmarks.
  mkdir -p "$root/build-asan"
  asan_log="$root/build-asan/build.log"
  low=(nice -n 19)
  if command -v ionice >/dev/null; then low+=(ionice -c 3); fi
  set -m
  (
    set +e
    t0=$(date +%s)
    "${low[@]}" cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DGNSSEMU_BUILD_TESTS=ON -DGNSSEMU_WERROR=OFF \
      -DGNSSEMU_SANITIZE=address,undefined -DGNSSEMU_FUZZ_SMOKE_S=0 &&
      "${low[@]}" cmake --build "$root/build-asan" -j"$jobs" --target unit_tests
    rc=$?
    echo "== test.sh: ASan+UBSan build (beside stage 2) took $(( $(date +%s) - t0 )) s wall, exit $rc"
    exit $rc
  ) >"$asan_log" 2>&1 &
  asan_pid=$!
  set +m
fi

stage "all tests (ctest)"
ctest --test-dir "$root/build" -j"$jobs" --output-on-failure
stage_done tests

if [ "$asan" -eq 1 ]; then
  stage "ASan+UBSan unit tests (build-asan/)"
  asan_rc=0
  wait "$asan_pid" || asan_rc=$?
  asan_pid=""
  if [ "$asan_rc" -ne 0 ]; then
    cat "$asan_log" >&2
    exit "$asan_rc"
  fi
  tail -n 1 "$asan_log" >&2
  ctest --test-dir "$root/build-asan" -L unit -j"$jobs" --output-on-failure
  stage_done asan
fi
