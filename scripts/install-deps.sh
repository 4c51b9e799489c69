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
  libnanoflann-dev       # planning: nearest neighbours of the RRT trees
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
  libompl-dev            # bench: OMPL's RRT, RRTConnect and RRT* as the baselines of P1's local layer
  libgeographiclib-dev   # io: local frame <-> WGS84 (exports, OSM buildings)
  libtbb-dev             # experiments: a batch's runs on every core
  libopenmpi-dev openmpi-bin  # uavplan batch --mpi: a batch across machines
  python3-dev pybind11-dev python3-pybind11  # the Python module
  python3-numpy python3-pytest python3-matplotlib  #   its arrays, its tests, its example's plot
  libgdal-dev            # io: elevation models in any format and CRS (GDAL, PROJ), KML airspace
  gdal-bin               # tests: ogr2ogr reads the GeoJSON and KML exports back
  python3-yaml           # tests: an independent check of the MAPF solution files
  clang-14 libclang-rt-14-dev  # make asan, make fuzz: clang with AddressSanitizer, UBSan, libFuzzer
  clang-format clang-tidy      # scripts/lint.sh: the house style and static checks
  chromium               # tests: the HTML report in a headless browser
  fonts-dejavu-core      #   and a font for it
)
# The report's viewer is bundled from the npm registry at build time; Node.js and npm come
# with the machine where present (a newer Node.js than Debian's), else from Debian.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  PACKAGES+=(nodejs npm)
fi

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
