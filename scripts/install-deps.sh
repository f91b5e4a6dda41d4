#!/usr/bin/env bash
# Installs the Debian packages SimbodyReeving needs, if any is missing. Idempotent.
set -euo pipefail
packages=(cmake g++ make ninja-build libsimbody-dev libeigen3-dev googletest libgtest-dev libbenchmark-dev gnuplot-nox libcli11-dev nlohmann-json3-dev xvfb libx11-dev libyaml-cpp-dev libopenmpi-dev openmpi-bin doxygen python3-dev python3-pybind11 python3-numpy python3-pytest)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "SimbodyReeving: installing missing Debian packages: ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  sudo DEBIAN_FRONTEND=noninteractive apt-get update -qq
  sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "SimbodyReeving: missing packages: ${missing[*]}" >&2
  echo "Run as root (or with sudo): apt-get install ${missing[*]}" >&2
  exit 1
fi
