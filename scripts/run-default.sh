#!/usr/bin/env bash
# Set up, build, run prm/default.prm (the thesis' bulb) on all cores, and draw
# its figures. Results: output-default/ in the current directory.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

prm=${1:-$VISCOFILM_ROOT/prm/default.prm}
mpirun -np "$(nproc)" "$VISCOFILM_BUILD/viscofilm" "$prm"

plot="$VISCOFILM_ROOT/postprocess/plot_run.py"
if [[ -f $plot ]]; then
  directory=$(sed -n 's/^ *set Directory *= *\([^ #]*\).*/\1/p' "$prm" | tail -n 1)
  /usr/bin/python3 "$plot" "${directory:-output}"
fi
