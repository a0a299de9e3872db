#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# systemd-analyze verify and security of the shipped units, the binary of
# this build in ExecStart. Usage: systemd_units.sh UNIT_DIR GNSSEMUD MAX_EXPOSURE
set -eu
units="$1"; gnssemud="$2"; max="$3"
command -v systemd-analyze >/dev/null 2>&1 || { echo "systemd-analyze missing: skipped"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
for u in gnssemud.service gnssemud@.service; do
  sed "s|/usr/bin/gnssemud|$gnssemud|" "$units/$u" > "$tmp/$u"
  inst="$u"; [ "$u" = "gnssemud@.service" ] && { cp "$tmp/$u" "$tmp/gnssemud@rig1.service"; inst="gnssemud@rig1.service"; }
  # --man=no: the man pages are checked by the package test, not installed here.
  if ! out=$(systemd-analyze verify --man=no "$tmp/$inst" 2>&1) || [ -n "$out" ]; then
    echo "$u: systemd-analyze verify:"; echo "$out"; fail=1
  fi
  score=$(systemd-analyze security --offline=true "$tmp/$inst" 2>&1 | sed -n 's/.*Overall exposure level for .*: \([0-9.]*\) .*/\1/p')
  echo "$u: exposure $score (max $max)"
  [ -n "$score" ] && awk -v s="$score" -v m="$max" 'BEGIN { exit !(s <= m) }' || fail=1
done
[ $fail -eq 0 ] && echo "1 passed, 0 failed" || echo "0 passed, 1 failed"
exit $fail
