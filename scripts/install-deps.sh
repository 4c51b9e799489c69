#!/usr/bin/env bash
# Installs the Debian packages uavplan builds and tests with. Idempotent: packages already
# present are skipped, so a second run does nothing but check.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev          # core: Vec3 and linear algebra
  libyaml-cpp-dev        # io: scenario YAML
  nlohmann-json3-dev     # io: scenario JSON, plan JSON
  libcli11-dev           # apps: command line
  libboost-dev           # graph / polygon algorithms used by planners
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present" >&2
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
