#!/usr/bin/python3
"""The biofilm on an obstacle, close up: φ and the elastic stress near it.

usage: plot_pillar.py RUN_DIR --centre X,Y --half-width W [--steps N,M,...]
                      [--field von_mises] [--out FILE]

For each snapshot nearest the given steps (default: the first and the last)
draws φ and one stress field (default von_mises; any field of the snapshot,
e.g. tau_xx) in the square of half-width W around the centre, in the run's
length unit, with the biofilm outline (φ = 0.05) on both, one row per step.
Writes FILE (default RUN_DIR/figures/pillar.png). For prm/examples/
pillar-streamer.prm: --centre 0,1e-4 --half-width 5e-5.
"""

import argparse
import os
import sys

sys.dont_write_bytecode = True  # keep postprocess/ free of __pycache__
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from viscofilm_io import np
from plot_run import describe, draw_field, save, snapshot_label

import matplotlib.pyplot as plt
from matplotlib.tri import Triangulation


def close_up(snap, centre, half_width):
    """The snapshot's triangulation with the triangles outside the window masked."""
    tri = snap.triangulation
    x, y = tri.x[tri.triangles].mean(axis=1), tri.y[tri.triangles].mean(axis=1)
    outside = (np.abs(x - centre[0]) > half_width) | (np.abs(y - centre[1]) > half_width)
    return Triangulation(tri.x, tri.y, tri.triangles, mask=outside)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--centre", required=True, help="x,y of the window's centre")
    parser.add_argument("--half-width", type=float, required=True)
    parser.add_argument("--steps", help="comma-separated steps (nearest snapshots)")
    parser.add_argument("--field", default="von_mises")
    parser.add_argument("--out")
    arguments = parser.parse_args()
    centre = [float(c) for c in arguments.centre.split(",")]
    if len(centre) != 2:
        raise vio.UserError("--centre takes two coordinates x,y, got " + arguments.centre)
    run = vio.Run(arguments.run_dir)
    length, _ = run.units()
    steps = ([int(s) for s in arguments.steps.split(",")] if arguments.steps
             else [run.steps()[0], run.steps()[-1]])
    snaps = [run.load(run.nearest_snapshot(step=step)) for step in steps]
    fig, axes = plt.subplots(len(snaps), 2, figsize=(10, 4.2 * len(snaps)), squeeze=False,
                             layout="constrained")
    for row, snap in zip(axes, snaps):
        if arguments.field not in snap.fields:
            raise vio.UserError("%s has no field %s; it has %s" % (
                arguments.run_dir, arguments.field, ", ".join(snap.field_names())))
        tri = close_up(snap, centre, arguments.half_width)
        phi = snap.fields.get("volume_fraction")
        for ax, name in zip(row, ["volume_fraction", arguments.field]):
            inside = ~tri.mask
            values = snap.fields[name]
            window = values[np.unique(tri.triangles[inside])]
            scale = dict(cmap="viridis", vmin=window.min(), vmax=window.max() or 1)
            draw_field(fig, ax, tri, values, "%s, %s" % (describe(name), snapshot_label(snap)),
                       [(phi, {"colors": "w" if name == "volume_fraction" else "k"})],
                       scale, length)
            ax.set(xlim=(centre[0] - arguments.half_width, centre[0] + arguments.half_width),
                   ylim=(centre[1] - arguments.half_width, centre[1] + arguments.half_width))
    out = arguments.out or os.path.join(arguments.run_dir, "figures", "pillar.png")
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    save(fig, os.path.dirname(os.path.abspath(out)), os.path.basename(out))


if __name__ == "__main__":
    vio.main_guard(main)
