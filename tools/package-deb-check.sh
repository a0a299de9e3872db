#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds the .deb of a build tree (cpack -G DEB) and checks it without
# installing on the machine: dpkg-deb contents, the copyright file (Debian's
# machine-readable format, naming every third-party file installed), the
# changelog, lintian (an error fails; warnings are printed), dpkg -x into a
# temp root, --version, --check-config of the packaged /etc config and a 3 s
# run of the packaged daemon (SIGTERM, exit 0). Prints size and contents. Usage:
#   tools/package-deb-check.sh BUILD_DIR [--install]
# --install also runs dpkg -i, the same checks on /usr/bin, then dpkg -P.
set -euo pipefail
build="$1"; install="${2:-}"
command -v cpack >/dev/null && command -v dpkg-deb >/dev/null || { echo "cpack or dpkg-deb missing: skipped"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
(cd "$build" && cpack -G DEB -B "$tmp/pkg" >"$tmp/cpack.log" 2>&1) || { cat "$tmp/cpack.log"; exit 1; }
deb=$(ls "$tmp"/pkg/*.deb)
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) kB"
dpkg-deb -I "$deb" | sed -n 's/^ \(Package\|Version\|Depends\|Installed-Size\):/  \1:/p'
dpkg-deb -c "$deb" | awk '{print $6}' > "$tmp/contents"
for f in ./usr/bin/gnssemud ./usr/bin/gnssemu ./lib/systemd/system/gnssemud.service ./lib/systemd/system/gnssemud@.service \
         ./etc/gnssemu/gnssemud.toml ./usr/share/gnssemu/default.toml ./usr/share/gnssemu/nav/brdc0010.22n ./usr/share/gnssemu/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz \
         ./usr/share/man/man8/gnssemud.8.gz ./usr/share/man/man1/gnssemu.1.gz ./usr/share/man/man5/gnssemud.toml.5.gz \
         ./usr/share/doc/gnssemu/copyright ./usr/share/doc/gnssemu/changelog.gz ./usr/share/doc/gnssemu/CHANGELOG.md; do
  grep -qx "$f" "$tmp/contents" || { echo "missing in the package: $f"; exit 1; }
done
echo "contents: $(wc -l < "$tmp/contents") entries, all expected files present"
dpkg-deb --ctrl-tarfile "$deb" | tar -xO ./conffiles | grep -qx /etc/gnssemu/gnssemud.toml || { echo "no conffile"; exit 1; }
grep -q "ExecStart=/usr/bin/gnssemud " <(dpkg-deb --fsys-tarfile "$deb" | tar -xO ./lib/systemd/system/gnssemud.service) ||
  { echo "unit does not run /usr/bin/gnssemud"; exit 1; }

# The copyright file: DEP-5, and a Files paragraph for every installed file
# that gnssemu did not write (the data under /usr/share/gnssemu/nav).
dpkg-deb --fsys-tarfile "$deb" | tar -xO ./usr/share/doc/gnssemu/copyright > "$tmp/copyright"
head -1 "$tmp/copyright" | grep -qx "Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/" ||
  { echo "copyright: not in Debian's machine-readable format"; exit 1; }
for f in $(grep '^\./usr/share/gnssemu/nav/.' "$tmp/contents" | grep -v '/$'); do
  grep -q "^Files: .*config/nav/$(basename "$f")" "$tmp/copyright" ||
    { echo "copyright: no Files paragraph for $f"; exit 1; }
done
echo "copyright: DEP-5, $(grep -c '^Files:' "$tmp/copyright") Files paragraphs, every installed nav file listed"
lintian_status="lintian missing (tools/install-deps.sh installs it): not run"
if command -v lintian >/dev/null; then
  # Exit status 2 is lintian's own failure; errors are counted from its tags.
  lintian --tag-display-limit 0 "$deb" > "$tmp/lintian" 2>&1 || [ $? -eq 1 ] || { cat "$tmp/lintian"; exit 1; }
  sed 's/^/  /' "$tmp/lintian"
  errors=$(grep -c '^E: ' "$tmp/lintian" || true)
  lintian_status="lintian: $errors errors, $(grep -c '^W: ' "$tmp/lintian" || true) warnings"
  echo "$lintian_status"
  [ "$errors" -eq 0 ] || exit 1
fi

check_root() {  # ROOT PREFIX: the packaged binaries and config under ROOT
  local root="$1" conf="$tmp/run.toml"
  "$root/usr/bin/gnssemud" --version
  "$root/usr/bin/gnssemu" --version | head -1
  # The packaged config with paths moved under root and the pty into tmp.
  sed -e "s|\"/usr/share/gnssemu|\"$root/usr/share/gnssemu|" -e "s|/run/gnssemu/gps0|$tmp/gps0|" \
      "$root/etc/gnssemu/gnssemud.toml" > "$conf"
  "$root/usr/bin/gnssemud" --check-config -c "$conf" --truth-port 0 | tail -1
  "$root/usr/bin/gnssemud" -c "$conf" --truth-port 0 >"$tmp/run.out" 2>"$tmp/run.err" & local pid=$!
  # A hot start fixes in about 1 s; a loaded machine may take longer.
  local waited=0
  until grep -q "fix 3D with" "$tmp/run.err" || [ $waited -ge 30 ]; do sleep 0.5; waited=$((waited + 1)); done
  [ -L "$tmp/gps0" ] || { echo "no pty"; cat "$tmp/run.err"; kill $pid; exit 1; }
  kill -TERM $pid; wait $pid || { echo "exit $?"; cat "$tmp/run.err"; exit 1; }
  [ ! -e "$tmp/gps0" ] || { echo "symlink left"; exit 1; }
  grep -o "fix 3D with [0-9]* satellites" "$tmp/run.err" | head -1 || { echo "no 3D fix in 15 s"; cat "$tmp/run.err"; exit 1; }
}
dpkg -x "$deb" "$tmp/root"
echo "dpkg -x into a temp root:"
check_root "$tmp/root"
if [ "$install" = "--install" ]; then
  echo "dpkg -i:"
  dpkg -i "$deb" >/dev/null
  check_root /
  dpkg -P gnssemu >/dev/null  # purge: the conffile goes too
  echo "dpkg -P: removed"
fi
case "$lintian_status" in lintian\ missing*) echo "$lintian_status; the other checks passed: skipped"; exit 77 ;; esac
echo "1 passed, 0 failed"
