#!/usr/bin/env bash
# Installs the optional fuzzing dependencies (not needed by `make demo` or `make test`):
# clang and its compiler runtime, whose libclang_rt.fuzzer, .asan and .ubsan libraries
# `make fuzz` links the libFuzzer targets of fuzz/ with (docs/robustness.md).
# Idempotent and non-interactive: packages already present are not touched, and apt is
# only consulted when something is missing.
set -euo pipefail

packages=(
  clang
  libclang-rt-14-dev
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

echo "install-fuzz-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
