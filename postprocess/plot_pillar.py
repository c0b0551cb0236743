#!/usr/bin/python3
"""The biofilm on an obstacle, close up: φ and the elastic stress near it.

usage: plot_pillar.py RUN_DIR --centre X,Y --half-width W
                      [--steps N,M,... | --times T,S,...] [--field von_mises]
                      [--out FILE] [--shapes FILE]

For each snapshot nearest the given steps or times (default: the first and
the last) draws φ and one stress field (default von_mises; any field of the
snapshot, e.g. tau_xx) in the square of half-width W around the centre, in
the run's length unit, with the biofilm outline (φ = 0.05) on both, one row
per snapshot. Writes FILE (default RUN_DIR/figures/pillar.png). --shapes FILE
also draws the outlines of every snapshot of the run in that window in one
panel, coloured by time: the biofilm's shape over time. For prm/examples/
pillar-streamer.prm: --centre 0,1e-4 --half-width 5e-5.
"""

import argparse
import os
import sys

sys.dont_write_bytecode = True  # keep postprocess/ free of __pycache__
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from viscofilm_io import np
from plot_run import describe, draw_field, draw_outline, save, snapshot_label

import matplotlib.pyplot as plt
from matplotlib.tri import Triangulation


def close_up(snap, centre, half_width):
    """The snapshot's triangulation with the triangles outside the window masked."""
    tri = snap.triangulation
    x, y = tri.x[tri.triangles].mean(axis=1), tri.y[tri.triangles].mean(axis=1)
    outside = (np.abs(x - centre[0]) > half_width) | (np.abs(y - centre[1]) > half_width)
    return Triangulation(tri.x, tri.y, tri.triangles, mask=outside)


def plot_shapes(run, centre, half_width, length, time_unit, out):
    """The outline φ = BIOFILM_LEVEL of every snapshot, coloured by time."""
    infos = run.snapshots
    times = [info.time for info in infos]
    colours = plt.cm.viridis(np.linspace(0, 1, len(infos)))
    fig, ax = plt.subplots(figsize=(6, 5), layout="constrained")
    for info, colour in zip(infos, colours):
        snap = run.load(info)
        draw_outline(ax, close_up(snap, centre, half_width), snap.fields.get("volume_fraction"),
                     colors=[colour])
    scale = plt.cm.ScalarMappable(cmap="viridis",
                                  norm=plt.Normalize(min(times), max(times)))
    fig.colorbar(scale, ax=ax, shrink=0.85, label=f"t [{time_unit}]")
    ax.set(aspect="equal", xlabel=f"x [{length}]", ylabel=f"y [{length}]",
           title="biofilm outline (φ = %g) over time" % vio.BIOFILM_LEVEL,
           xlim=(centre[0] - half_width, centre[0] + half_width),
           ylim=(centre[1] - half_width, centre[1] + half_width))
    save(fig, os.path.dirname(os.path.abspath(out)), os.path.basename(out))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--centre", required=True, help="x,y of the window's centre")
    parser.add_argument("--half-width", type=float, required=True)
    selection = parser.add_mutually_exclusive_group()
    selection.add_argument("--steps", help="comma-separated steps (nearest snapshots)")
    selection.add_argument("--times", help="comma-separated times (nearest snapshots)")
    parser.add_argument("--field", default="von_mises")
    parser.add_argument("--out")
    parser.add_argument("--shapes", help="also write the outlines over time to this file")
    arguments = parser.parse_args()
    centre = [float(c) for c in arguments.centre.split(",")]
    if len(centre) != 2:
        raise vio.UserError("--centre takes two coordinates x,y, got " + arguments.centre)
    run = vio.Run(arguments.run_dir)
    length, time_unit = run.units()
    if arguments.times:
        infos = [run.nearest_snapshot(time=float(t)) for t in arguments.times.split(",")]
    else:
        steps = ([int(s) for s in arguments.steps.split(",")] if arguments.steps
                 else [run.steps()[0], run.steps()[-1]])
        infos = [run.nearest_snapshot(step=step) for step in steps]
    snaps = [run.load(info) for info in infos]
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
    if arguments.shapes:
        os.makedirs(os.path.dirname(os.path.abspath(arguments.shapes)), exist_ok=True)
        plot_shapes(run, centre, arguments.half_width, length, time_unit, arguments.shapes)


if __name__ == "__main__":
    vio.main_guard(main)
