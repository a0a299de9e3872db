#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the Debian packages gnssemu needs to build, run and test.
# Only packages that are missing are installed; needs root (or sudo) when any is.
set -euo pipefail

PKGS=(
  build-essential cmake pkg-config
  libgeographiclib-dev libembree-dev libboost-dev libserialport-dev
  libspdlog-dev libfmt-dev libgtest-dev libgmock-dev libtomlplusplus-dev libcli11-dev
  nlohmann-json3-dev zlib1g-dev libsystemd-dev
  gpsd gpsd-clients rtklib socat python3
  systemd dpkg-dev  # systemd-analyze (unit tests), dpkg-shlibdeps (cpack -G DEB)
  lintian           # Debian's package checker on the built .deb (tools/package-deb-check.sh)
  libjs-chart.js chromium fonts-dejavu-core nodejs
  # gnssemu sweep's Slurm test: a one-node cluster on loopback (tools/slurm-local.sh)
  slurmctld slurmd slurm-client munge
  # fuzzing and sanitizers (docs/robustness.md): clang's libFuzzer, symbolized reports
  clang libclang-rt-14-dev llvm
)
# The browser test installs its driver (playwright-core, from
# tests/integration/browser/package-lock.json) into build/browser-driver.

missing=()
for p in "${PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# npm may come with nodejs (NodeSource) or as Debian's own package.
command -v npm >/dev/null 2>&1 || missing+=(npm)

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
# The gpsd package may start a system gpsd on its socket; tests run their own.
if command -v systemctl >/dev/null 2>&1 && [ -d /run/systemd/system ]; then
  $SUDO systemctl stop gpsd.socket gpsd.service >/dev/null 2>&1 || true
  # Slurm's packages enable their services; the sweep test runs its own cluster.
  $SUDO systemctl stop slurmctld.service slurmd.service >/dev/null 2>&1 || true
fi
