#!/usr/bin/env bash
# Install what is missing (Debian 12 packages only) and build viscofilm in
# build/ (Release). Sourced by run-default.sh and run-tests.sh; runnable alone.
set -euo pipefail

VISCOFILM_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
VISCOFILM_BUILD=${VISCOFILM_BUILD:-$VISCOFILM_ROOT/build}
export VISCOFILM_ROOT VISCOFILM_BUILD

packages=(cmake make g++ libdeal.ii-dev libpng-dev libtiff-dev openmpi-bin numdiff
          python3 python3-numpy python3-h5py python3-matplotlib)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "viscofilm setup: installing ${missing[*]}"
  if [[ $(id -u) -ne 0 ]]; then
    echo "viscofilm setup: these Debian packages are missing and installing them needs root:" >&2
    echo "  apt-get install ${missing[*]}" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Open MPI refuses to run as root unless told; CI runs as root.
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

cmake -S "$VISCOFILM_ROOT" -B "$VISCOFILM_BUILD" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$VISCOFILM_BUILD" -- -j"$(nproc)"
