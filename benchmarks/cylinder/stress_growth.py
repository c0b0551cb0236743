#!/usr/bin/python3
"""benchmarks/cylinder/stress_growth.py -- where the elastic stress of a
cylinder run changes between two of its HDF5 snapshots (doc/benchmarks.md,
"Wi ≥ 0.6: the stagnation points and the wake's strand").

Usage:  benchmarks/cylinder/stress_growth.py RUN_DIRECTORY [--from STEP] [--to STEP]
                                             [--count N]

RUN_DIRECTORY holds a run's snapshots (solution.xdmf and solution-NNNNN.h5,
Output/Interval > 0) and its statistics.csv. Printed: K (force_x_Cylinder)
at the snapshots; the N nodes
(default 8) where a component of tau changes most from snapshot --from
(default: the second) to --to (default: the last), with their distance r
from the cylinder's centre (the origin) and angle; and per snapshot the
largest tau_xx on the wake's centreline (y = 0, x > 1) and the largest tau_yy
on the upstream centreline (x < -1), the two stagnation streamlines.
Needs Debian's python3-numpy, python3-h5py and python3-matplotlib (run with
/usr/bin/python3).
"""

import argparse
import csv
import math
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir,
                                os.pardir, "postprocess"))
# says which packages are missing, if any
from viscofilm_io import Run, UserError, main_guard, np  # noqa: E402

COMPONENTS = ("tau_xx", "tau_xy", "tau_yy")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory")
    parser.add_argument("--from", dest="first", type=int, default=None)
    parser.add_argument("--to", dest="last", type=int, default=None)
    parser.add_argument("--count", type=int, default=8)
    arguments = parser.parse_args()

    run = Run(arguments.directory)
    infos = {info.step: info for info in run.snapshots}
    if len(infos) < 2:
        sys.exit("%s: fewer than two snapshots in its solution.xdmf (set Output/Interval > 0)"
                 % arguments.directory)
    steps = sorted(infos)
    first = arguments.first if arguments.first is not None else steps[1]
    last = arguments.last if arguments.last is not None else steps[-1]
    for step in (first, last):
        if step not in infos:
            sys.exit("no snapshot of step %d (there are: %s)"
                     % (step, " ".join(map(str, steps))))

    statistics = os.path.join(arguments.directory, "statistics.csv")
    rows = {int(row["step"]): row for row in csv.DictReader(open(statistics))}
    force = next((key for key in next(iter(rows.values())) if key.startswith("force_x_")),
                 None)

    # A snapshot lists its nodes in the order of the ranks that wrote it, and
    # a resumed run may partition the mesh otherwise: so each snapshot's
    # nodes are sorted by their coordinates.
    snapshots, nodes = {}, None
    for step in steps:
        snapshot = run.load(infos[step])
        order = np.lexsort(np.round(snapshot.nodes, 9).T[::-1])
        if nodes is None:
            nodes = snapshot.nodes[order]
        elif (snapshot.nodes.shape != nodes.shape or
              not np.allclose(snapshot.nodes[order], nodes, atol=1e-9)):
            raise UserError("%s: its mesh is not that of %s (the snapshots of one run on "
                            "one fixed mesh are compared)"
                            % (infos[step].h5_file, infos[steps[0]].h5_file))
        snapshots[step] = {name: snapshot.field(name)[order] for name in COMPONENTS}
    x, y = nodes[:, 0], nodes[:, 1]
    r, angle = np.hypot(x, y), np.degrees(np.arctan2(y, x))
    wake = (np.abs(y) < 1e-9) & (x > 1)
    upstream = (np.abs(y) < 1e-9) & (x < -1)

    print("# step time K max_tau_xx_wake_centreline(x) max_tau_yy_upstream_centreline(x)")
    for step in steps:
        s = snapshots[step]
        i = np.flatnonzero(wake)[np.argmax(s["tau_xx"][wake])]
        j = np.flatnonzero(upstream)[np.argmax(s["tau_yy"][upstream])]
        row = rows.get(step, {})
        print("%5d %7.3f %9.3f %8.2f (%.3f) %8.2f (%.3f)"
              % (step, float(row.get("time", math.nan)),
                 float(row.get(force, math.nan)) if force else math.nan,
                 s["tau_xx"][i], x[i], s["tau_yy"][j], x[j]))

    change = np.max([np.abs(snapshots[last][c] - snapshots[first][c]) for c in COMPONENTS],
                    axis=0)
    print("# the %d largest changes of a component of tau from step %d to %d"
          % (arguments.count, first, last))
    print("# x y r angle " + " ".join("%s(%d) %s(%d)" % (c, first, c, last) for c in COMPONENTS))
    for i in np.argsort(-change)[:arguments.count]:
        print("%7.3f %7.3f %6.3f %7.2f " % (x[i], y[i], r[i], angle[i]) +
              " ".join("%8.2f %8.2f" % (snapshots[first][c][i], snapshots[last][c][i])
                       for c in COMPONENTS))


if __name__ == "__main__":
    main_guard(main)
