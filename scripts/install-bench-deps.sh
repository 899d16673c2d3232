#!/usr/bin/env bash
# Installs the optional benchmark dependencies (not needed by `make demo` or `make test`):
# Blender, whose Cycles renderer bench/vs_cycles/run.py compares Dermis against (and
# python3-openvdb, which writes the grid medium's twin as a .vdb for it), the
# Python modules the benchmark scripts use, and Chromium, in which the study report's
# browser test (python/tests/test_report_browser.py) opens the page headless.
# Idempotent and non-interactive: packages already present are not touched, and apt is
# only consulted when something is missing.
set -euo pipefail

packages=(
  blender python3-openvdb
  python3-numpy python3-pil python3-matplotlib
  python3-openimageio openimageio-tools
  chromium
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

echo "install-bench-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
