#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds and runs the libFuzzer targets of tests/fuzz (docs/robustness.md).
#
#   fuzz.sh build [--build-dir DIR]                 clang build of the fuzz targets (default build/fuzz)
#   fuzz.sh run TARGET [--seconds N] [--build-dir DIR] [--jobs J] [--smoke] [--keep-going] [-- LIBFUZZER_ARGS...]
#   fuzz.sh all [--seconds N] [--build-dir DIR] [--keep-going]   every target in turn, a summary at the end
#   fuzz.sh list                                    the targets
#
# A run starts from the target's seeds (seeds/TARGET.txt, corpus/TARGET,
# regressions/TARGET) and the corpus it grew before (DIR/corpus/TARGET); a
# crash, leak, oracle failure, timeout (10 s for one input) or memory blow-up
# (1.5 GB RSS, or 512 MB in one allocation: inputs are at most 64 KB) leaves
# the input in DIR/artifacts/TARGET/ and exits non-zero (--keep-going:
# runs the whole time in libFuzzer's fork mode, keeping every failing
# input, and lists them at the end). --smoke (ctest):
# the seeds only and a fixed random seed, so a run explores the same inputs
# on every machine, as far as its time allows. Exit 77 (ctest: skipped)
# when clang or its libFuzzer runtime is missing.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
readonly kSkip=77

# Largest input per target, bytes: a datagram (plus a little, to reach
# "too large"), a host's burst of commands, a file prefix that holds
# headers and a few records.
max_len() {
  case "$1" in
    truth_packet) echo 4200 ;;
    ubx_device) echo 8192 ;;
    config|footprints) echo 16384 ;;
    *) echo 65536 ;;
  esac
}

# The targets: the rows of the table in CMakeLists.txt ("  name \"libs\"").
targets() { sed -n 's/^  \([a-z_]*\) "gnssemu_[a-z_ ]*")\{0,1\}$/\1/p' "$here/CMakeLists.txt"; }

usage() { sed -n '2,13p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

need_clang() {
  local cxx="${FUZZ_CXX:-clang++}"
  if ! command -v "$cxx" >/dev/null 2>&1; then
    echo "SKIP: $cxx not found: the fuzz targets need clang with libFuzzer (tools/install-deps.sh installs clang and libclang-rt-14-dev)" >&2
    exit $kSkip
  fi
  local probe
  probe="$(mktemp -d)"
  printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' >"$probe/p.cpp"
  if ! "$cxx" -fsanitize=fuzzer,address,undefined "$probe/p.cpp" -o "$probe/p" >/dev/null 2>&1; then
    rm -rf "$probe"
    echo "SKIP: $cxx cannot link -fsanitize=fuzzer,address,undefined: install libclang-rt-14-dev (tools/install-deps.sh)" >&2
    exit $kSkip
  fi
  rm -rf "$probe"
}

cmd="${1:-}"
[ -n "$cmd" ] || usage
shift
target=""
if [ "$cmd" = run ]; then
  target="${1:-}"
  [ -n "$target" ] || usage
  shift
fi
build_dir="$root/build/fuzz"
seconds=60
jobs=1
smoke=0
keep_going=0
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build_dir="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --smoke) smoke=1; shift ;;
    --keep-going) keep_going=1; shift ;;
    --) shift; extra=("$@"); break ;;
    *) usage ;;
  esac
done

build() {
  need_clang
  local cc="${FUZZ_CC:-clang}" cxx="${FUZZ_CXX:-clang++}"
  if [ ! -f "$build_dir/CMakeCache.txt" ]; then
    CC="$cc" CXX="$cxx" cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DGNSSEMU_FUZZ=ON \
      -DGNSSEMU_BUILD_TESTS=OFF >"$build_dir.configure.log" 2>&1 || {
      cat "$build_dir.configure.log" >&2
      exit 1
    }
  fi
  local t list=()
  for t in $(targets); do list+=("fuzz_$t"); done
  cmake --build "$build_dir" -j"${GNSSEMU_JOBS:-2}" --target "${list[@]}"
}

run() {
  local t="$1" secs="$2"
  need_clang
  local bin="$build_dir/tests/fuzz/fuzz_$t"
  if [ ! -x "$bin" ]; then
    echo "fuzz: $bin missing: run tests/fuzz/fuzz.sh build --build-dir $build_dir first" >&2
    return 1
  fi
  local work="$build_dir/corpus/$t" artifacts="$build_dir/artifacts/$t/" tmp
  if [ "$smoke" -eq 1 ]; then
    work="$build_dir/smoke/$t"
    rm -rf "$work"
  fi
  mkdir -p "$work" "$artifacts" "$build_dir/tmp"
  # Scratch files of this run only (libFuzzer's fork mode keeps its jobs here too).
  tmp="$(mktemp -d "$build_dir/tmp/$t.XXXXXX")"
  # Seed files as one comma-separated list (-seed_inputs=@file).
  local seeds="$build_dir/seeds-$t.txt" line p
  : >"$seeds.lines"
  while IFS= read -r line; do
    case "$line" in ''|'#'*) continue ;; esac
    p="$root/$line"
    if [ -d "$p" ]; then find "$p" -type f | sort >>"$seeds.lines"; else echo "$p" >>"$seeds.lines"; fi
  done <"$here/seeds/$t.txt"
  for p in "$here/corpus/$t" "$here/regressions/$t"; do
    if [ -d "$p" ]; then find "$p" -type f | sort >>"$seeds.lines"; fi
  done
  paste -sd, "$seeds.lines" >"$seeds"
  local args=(-max_total_time="$secs" -max_len="$(max_len "$t")" -timeout=10 -rss_limit_mb=1536 -malloc_limit_mb=512
    -error_exitcode=1 -timeout_exitcode=1
    -print_final_stats=1 -artifact_prefix="$artifacts")
  [ -s "$seeds" ] && args+=(-seed_inputs=@"$seeds")
  [ -f "$here/dict/$t.dict" ] && args+=(-dict="$here/dict/$t.dict")
  if [ "$keep_going" -eq 1 ]; then
    args+=(-fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  elif [ "$jobs" -gt 1 ]; then
    args+=(-fork="$jobs")
  fi
  if [ "$smoke" -eq 1 ]; then args+=(-seed=1); fi
  echo "fuzz: $t for ${secs} s: $bin ${args[*]} ${extra[*]} $work" >&2
  local rc=0 marker="$tmp.start"
  touch "$marker"
  TMPDIR="$tmp" ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}" \
    "$bin" "${args[@]}" "${extra[@]}" "$work" || rc=$?
  rm -rf "$tmp"
  local found
  found="$(find "$artifacts" -type f -newer "$marker" | sort)"
  rm -f "$marker"
  [ -z "$found" ] || rc=1
  if [ $rc -ne 0 ]; then
    echo "fuzz: $t FAILED (exit $rc); inputs kept:" >&2
    echo "${found:-  (none: see the log above)}" | sed 's/^/  /' >&2
    echo "fuzz: replay it with $bin <file>, or build/tests/fuzz/fuzz_replay_$t <file> (gcc build)" >&2
  fi
  return $rc
}

case "$cmd" in
  list) targets ;;
  build) build ;;
  run) run "$target" "$seconds" ;;
  all)
    need_clang
    failed=()
    for t in $(targets); do
      start=$(date +%s)
      if run "$t" "$seconds"; then r=clean; else r=FAILED; failed+=("$t"); fi
      echo "fuzz: $t $r after $(( $(date +%s) - start )) s" >&2
    done
    if [ ${#failed[@]} -gt 0 ]; then
      echo "fuzz: failed: ${failed[*]}" >&2
      exit 1
    fi
    echo "fuzz: all targets clean" >&2
    ;;
  *) usage ;;
esac
