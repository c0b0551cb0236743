#!/usr/bin/python3
"""The initial volume fraction of several runs side by side (the profiles of
thesis Fig. 4.4 and doc/parameters.md).

usage: plot_profiles.py RUN_DIR [RUN_DIR ...] --out FILE.png

Each panel is φ at the first snapshot of a run (after softening), titled with
the run directory's name, with the biofilm outline φ = 0.05.
"""
import sys

sys.dont_write_bytecode = True
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from plot_run import draw_field

import matplotlib.pyplot as plt


def main():
    parser = vio.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="run directories")
    parser.add_argument("--out", required=True, help="PNG file to write")
    args = parser.parse_args()

    columns = min(3, len(args.runs))
    rows = (len(args.runs) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.6 * rows),
                             squeeze=False)
    for ax in axes.flat[len(args.runs):]:
        ax.axis("off")
    for ax, directory in zip(axes.flat, args.runs):
        run = vio.Run(directory)
        snap = run.load(run.snapshots[0])
        phi = snap.field("volume_fraction")
        draw_field(fig, ax, snap.triangulation, phi, run.name,
                   outlines=[(phi, {})], scale=dict(cmap="viridis", vmin=0, vmax=0.1),
                   length=run.units()[0])
    fig.tight_layout()
    try:
        fig.savefig(args.out, dpi=90)
    except OSError as error:
        raise vio.UserError(f"cannot write {args.out}: {error}")
    print(args.out)


if __name__ == "__main__":
    vio.main_guard(main)
