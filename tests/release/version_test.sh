#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# gnssemud --version, gnssemu version and gnssemu --version name the project
# version and the git commit of the source; CHANGELOG.md has the version; and
# cmake/git_commit.cmake finds the commit in a checkout, a `git archive`
# tarball, an override, and says "unknown" outside a checkout.
# Usage: version_test.sh GNSSEMUD GNSSEMU SOURCE_DIR VERSION
set -euo pipefail
gnssemud="$1"; gnssemu="$2"; src="$3"; version="$4"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
check() {  # NAME GOT WANTED_REGEX
  if [[ "$2" =~ ^$3$ ]]; then echo "ok   $1: $2"; else echo "FAIL $1: '$2' does not match '$3'"; fail=1; fi
}

# The binaries: the version, and the commit git names for the source (a build
# may have been made before or after tracked files changed: -dirty either way).
if git -C "$src" rev-parse --show-toplevel >/dev/null 2>&1 &&
   [ "$(cd "$(git -C "$src" rev-parse --show-toplevel)" && pwd -P)" = "$(cd "$src" && pwd -P)" ]; then
  commit="$(git -C "$src" rev-parse --short=12 HEAD)(-dirty)?"
else
  commit="[0-9a-f]{12}|unknown"  # not a checkout: a tarball's recorded commit or unknown
fi
v="${version//./\\.}"
check "gnssemud --version" "$("$gnssemud" --version)" "gnssemud $v \\(git $commit\\)"
check "gnssemu version" "$("$gnssemu" version | head -1)" "gnssemu $v \\(git $commit\\)"
check "gnssemu --version" "$("$gnssemu" --version | head -1)" "gnssemu $v \\(git $commit\\)"
check "CHANGELOG.md" "$(grep -c "^## \[$version\] - " "$src/CHANGELOG.md")" "1"

# cmake/git_commit.cmake on trees of each kind.
script="$src/cmake/git_commit.cmake"
run() {  # SOURCE_DIR [OVERRIDE] -> the recorded commit
  cmake -DSOURCE_DIR="$1" -DOUTPUT="$tmp/out.inc" -DOVERRIDE="${2:-}" -P "$script" >/dev/null
  tr -d '"\n' < "$tmp/out.inc"
}
mkdir -p "$tmp/plain/cmake"
check "not a checkout" "$(run "$tmp/plain")" "unknown"
printf '$Format:%%H$\n' > "$tmp/plain/cmake/git_commit.txt"
check "not a checkout, unfilled git_commit.txt" "$(run "$tmp/plain")" "unknown"
check "override" "$(run "$tmp/plain" 0123456789ab)" "0123456789ab"

repo="$tmp/repo"
mkdir -p "$repo/cmake" "$repo/sub"
git -C "$repo" init -q
printf '$Format:%%H$\n' > "$repo/cmake/git_commit.txt"
printf 'cmake/git_commit.txt export-subst\n' > "$repo/.gitattributes"
echo a > "$repo/sub/file"
git -C "$repo" add -A
git -C "$repo" -c user.name=t -c user.email=t@example.org commit -qm one
head=$(git -C "$repo" rev-parse HEAD)
check "checkout" "$(run "$repo")" "${head:0:12}"
echo b > "$repo/sub/file"
check "checkout with a changed file" "$(run "$repo")" "${head:0:12}-dirty"
echo untracked > "$repo/new"
git -C "$repo" checkout -q sub/file
check "checkout with an untracked file" "$(run "$repo")" "${head:0:12}"
check "a folder inside another repository" "$(run "$repo/sub")" "unknown"
mkdir "$tmp/archive"
git -C "$repo" archive HEAD | tar -x -C "$tmp/archive"
check "git archive tarball" "$(run "$tmp/archive")" "${head:0:12}"

[ $fail -eq 0 ] && echo "1 passed, 0 failed" || echo "0 passed, 1 failed"
exit $fail
