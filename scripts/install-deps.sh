#!/usr/bin/env bash
# Installs the Debian packages Dermis builds and tests with. Idempotent and
# non-interactive: packages already present are not touched, and apt is only
# consulted when something is missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config clang-format
  libembree-dev libtbb-dev
  libopenimageio-dev openimageio-tools libopenexr-dev libpng-dev
  libassimp-dev zlib1g-dev
  libcli11-dev libfmt-dev libpcg-cpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-numpy python3-matplotlib python3-pil python3-openimageio
  python3-dev pybind11-dev python3-pytest
  libopenmpi-dev openmpi-bin
  libcpp-httplib-dev
  libnanovdb-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
