#!/usr/bin/env bash
# Set up, build and run the whole test suite (ctest, 1 and 2 MPI ranks).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

cd "$VISCOFILM_BUILD"
ctest --output-on-failure -j"$(nproc)" "$@"
