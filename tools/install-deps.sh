#!/usr/bin/env bash
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
)

missing=()
for p in "${PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
# The gpsd package may start a system gpsd on its socket; tests run their own.
if command -v systemctl >/dev/null 2>&1 && [ -d /run/systemd/system ]; then
  $SUDO systemctl stop gpsd.socket gpsd.service >/dev/null 2>&1 || true
fi
