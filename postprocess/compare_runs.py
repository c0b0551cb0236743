#!/usr/bin/python3
"""Difference plots of fields between two viscofilm runs.

usage: compare_runs.py RUN_A RUN_B [--step N] [--field F ...] [--out DIR]

For the snapshot of RUN_A nearest step N (default: 100 if written, else the
last) and the snapshot of RUN_B nearest that step, draws A, B and A − B for each
field (default: u v pressure) and prints max |A − B|. If the meshes differ, B
is interpolated linearly onto A's nodes. PNGs go to RUN_A/figures by default.
"""

import os
import sys

sys.dont_write_bytecode = True  # keep postprocess/ free of __pycache__
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from viscofilm_io import np
from plot_run import colour_scale, describe, draw_field, save, snapshot_label

import matplotlib.pyplot as plt

B_OUTLINE = {"colors": "0.4", "linestyles": "dashed"}


def main():
    parser = vio.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_a", metavar="RUN_A")
    parser.add_argument("run_b", metavar="RUN_B")
    parser.add_argument("--step", type=int,
                        help="snapshot nearest this step (default: 100 if written, else last)")
    parser.add_argument("--field", nargs="+", default=["u", "v", "pressure"], metavar="F",
                        help="fields to compare (default: u v pressure; p and phi are "
                             "accepted for pressure and volume_fraction)")
    parser.add_argument("--out", help="output directory (default: RUN_A/figures)")
    args = parser.parse_args()

    run_a, run_b = vio.Run(args.run_a), vio.Run(args.run_b)
    step = args.step if args.step is not None else (
        100 if 100 in run_a.steps() else run_a.snapshots[-1].step)
    info_a = run_a.nearest_snapshot(step=step)
    info_b = run_b.nearest_snapshot(step=info_a.step)
    for run, info, wanted in [(run_a, info_a, step), (run_b, info_b, info_a.step)]:
        if info.step != wanted:
            print(f"note: {run.directory} has no snapshot at step {wanted}; "
                  f"using step {info.step}")
    if not np.isclose(info_a.time, info_b.time):
        print(f"note: the snapshots are at different times: "
              f"t = {info_a.time:g} (A) and t = {info_b.time:g} (B)")

    snap_a, snap_b = run_a.load(info_a), run_b.load(info_b)
    names = [vio.ALIASES.get(f, f) for f in args.field]
    for name in names:  # unknown field names stop us before any drawing
        snap_a.field(name), snap_b.field(name)
    fields_b = vio.interpolate_onto(snap_b, snap_a)
    if not vio.same_nodes(snap_a, snap_b):
        print(f"note: the meshes differ ({len(snap_a.nodes)} vs {len(snap_b.nodes)} "
              f"nodes): B is interpolated linearly onto A's nodes")
    outside = np.isnan(fields_b[names[0]]).sum()
    if outside:
        print(f"note: {outside} of A's nodes lie outside B's mesh: shown as 0, "
              f"left out of max|A - B|")

    out_dir = vio.output_directory(args.out or os.path.join(args.run_a, "figures"))

    print(f"A = {run_a.directory} ({snapshot_label(snap_a)}), "
          f"B = {run_b.directory} ({snapshot_label(snap_b)})")
    tri = snap_a.triangulation
    outlines = [(snap_a.fields.get("volume_fraction"), {}),
                (fields_b.get("volume_fraction"), B_OUTLINE)]
    for name in names:
        a, b = snap_a.fields[name], fields_b[name]
        difference = a - b
        index = np.nanargmax(np.abs(difference)) if np.isfinite(difference).any() else 0
        largest, scale = abs(difference[index]), np.nanmax(np.abs(a))
        x, y = snap_a.nodes[index]
        print(f"  {name:16s} max|A - B| = {largest:.6e} at ({x:.4f}, {y:.4f}), "
              f"relative to max|A|: {largest / scale if scale > 0 else np.nan:.3e}")

        fig, axes = plt.subplots(1, 3, figsize=(16, 4.6), layout="constrained")
        common = colour_scale(np.concatenate([a, b]))  # A and B share a colour bar
        for ax, values, title, scale in [
                (axes[0], a, f"A: {run_a.name}", common),
                (axes[1], b, f"B: {run_b.name}", common),
                (axes[2], difference, f"A − B, max|A − B| = {largest:.3g}", None)]:
            draw_field(fig, ax, tri, values, title, outlines, scale, length=run_a.units()[0])
        fig.suptitle(f"{describe(name)}, A at {snapshot_label(snap_a)}, "
                     f"B at {snapshot_label(snap_b)}   "
                     f"(biofilm φ = {vio.BIOFILM_LEVEL}: A solid, B dashed)")
        save(fig, out_dir, f"diff_{run_b.name}_step{snap_a.step:05d}_{name}.png")


if __name__ == "__main__":
    vio.main_guard(main)
