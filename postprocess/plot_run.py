#!/usr/bin/python3
"""Figures and a numeric summary of one viscofilm run.

usage: plot_run.py RUN_DIR [--step N] [--out DIR]

Draws colour maps of every scalar field (with the biofilm outline φ = 0.05),
3D surfaces of u, v and p for the snapshot nearest step N (default: step 100
if written, else the last snapshot) and for the initial one, time series of
statistics.csv and probes.csv. PNGs go to RUN_DIR/figures unless --out is given.
"""

import os
import sys

sys.dont_write_bytecode = True  # keep postprocess/ free of __pycache__
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from viscofilm_io import np

import matplotlib.pyplot as plt

DESCRIPTIONS = {"u": "horizontal velocity u", "v": "vertical velocity v",
                "pressure": "pressure p", "volume_fraction": "volume fraction φ",
                "substrate": "substrate S",
                "divergence": "divergence ∇·u", "vorticity": "vorticity ∂v/∂x − ∂u/∂y",
                "inertia": "inertia |u·∇u|"}
SURFACE_FIELDS = ["u", "v", "pressure"]


def describe(name):
    return DESCRIPTIONS.get(name, name.replace("_", " "))


def colour_scale(values):
    """Diverging map symmetric about 0 for fields of both signs, else viridis."""
    finite = values[np.isfinite(values)]
    top = np.abs(finite).max() if finite.size else 0.0
    lo, hi = (finite.min(), finite.max()) if finite.size else (0.0, 0.0)
    if lo < -0.01 * top and hi > 0.01 * top:
        return dict(cmap="RdBu_r", vmin=-top, vmax=top)
    if lo == hi:  # constant field: centre it in the colour bar
        lo, hi = lo - 0.5 * (abs(lo) or 1), hi + 0.5 * (abs(hi) or 1)
    return dict(cmap="viridis", vmin=lo, vmax=hi)


def draw_outline(ax, triangulation, phi, **style):
    """The biofilm outline φ = BIOFILM_LEVEL, if φ crosses it."""
    if phi is not None and np.nanmin(phi) < vio.BIOFILM_LEVEL < np.nanmax(phi):
        ax.tricontour(triangulation, np.nan_to_num(phi), levels=[vio.BIOFILM_LEVEL],
                      **{"colors": "k", "linewidths": 1.0, **style})


def draw_field(fig, ax, triangulation, values, title, outlines=(), scale=None, length="cm"):
    """Colour map of node values on ax, with colour bar and biofilm outlines
    (a sequence of (phi, style) pairs); scale: colour_scale() of other values;
    length: the unit of x and y."""
    mesh = ax.tripcolor(triangulation, np.nan_to_num(values), shading="gouraud",
                        **(scale or colour_scale(values)))
    for phi, style in outlines:
        draw_outline(ax, triangulation, phi, **style)
    fig.colorbar(mesh, ax=ax, shrink=0.85, format="%.3g")
    ax.set(aspect="equal", xlabel=f"x [{length}]", ylabel=f"y [{length}]", title=title)
    x, y = triangulation.x, triangulation.y
    ax.set(xlim=(x.min(), x.max()), ylim=(y.min(), y.max()))


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    print(path)


def snapshot_label(snap):
    return f"step {snap.step}, t = {snap.time:.5g}"


def plot_snapshot(snap, out_dir, length):
    prefix = f"step{snap.step:05d}"
    phi = snap.fields.get("volume_fraction")
    names = snap.field_names()
    tri = snap.triangulation
    for name in names:
        fig, ax = plt.subplots(figsize=(6, 5))
        draw_field(fig, ax, tri, snap.fields[name],
                   f"{describe(name)}, {snapshot_label(snap)}", [(phi, {})], length=length)
        save(fig, out_dir, f"{prefix}_{name}.png")

    ncols = 4
    nrows = -(-len(names) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.4 * ncols, 3.6 * nrows),
                             squeeze=False, layout="constrained")
    for ax, name in zip(axes.flat, names):
        draw_field(fig, ax, tri, snap.fields[name], name, [(phi, {})], length=length)
    for ax in axes.flat[len(names):]:
        ax.set_visible(False)
    fig.suptitle(snapshot_label(snap))
    save(fig, out_dir, f"{prefix}_overview.png")

    for name in [n for n in SURFACE_FIELDS if n in snap.fields]:
        fig = plt.figure(figsize=(7, 5.5))
        ax = fig.add_subplot(projection="3d")
        surface = ax.plot_trisurf(tri, snap.fields[name], linewidth=0, antialiased=False,
                                  **colour_scale(snap.fields[name]))
        fig.colorbar(surface, ax=ax, shrink=0.6, format="%.3g")
        ax.set(xlabel=f"x [{length}]", ylabel=f"y [{length}]", zlabel=name,
               title=f"{describe(name)}, {snapshot_label(snap)}")
        save(fig, out_dir, f"{prefix}_{name}_surface.png")


def plot_statistics(stats, out_dir, time_unit):
    columns = vio.numeric_columns(stats)
    if "time" not in stats or not columns or not len(stats["time"]):
        print("note: statistics.csv has no data to plot")
        return
    ncols = 2
    nrows = -(-len(columns) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(11, 2.6 * nrows), sharex=True,
                             squeeze=False)
    for ax, name in zip(axes.flat, columns):
        ax.plot(stats["time"], stats[name])
        ax.set_ylabel(name.replace("_", " "))
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(columns):]:
        ax.set_visible(False)
    for ax in axes.flat[max(0, len(columns) - ncols):len(columns)]:  # bottom of each column
        ax.tick_params(labelbottom=True)
        ax.set_xlabel(f"time [{time_unit}]")
    fig.tight_layout()
    save(fig, out_dir, "statistics.png")


def plot_probes(run, out_dir, time_unit):
    if not os.path.isfile(run.path("probes.csv")):
        print("note: no probes.csv (no Output/Probe points): probe plot skipped")
        return
    probes = run.probes()
    if not probes:
        print("note: probes.csv has no data rows")
        return
    columns = vio.numeric_columns(next(iter(probes.values())), skip=("step", "time", "x", "y"))
    fig, axes = plt.subplots(len(columns), 1, figsize=(8, 2.4 * len(columns)), sharex=True,
                             squeeze=False)
    for ax, name in zip(axes[:, 0], columns):
        for (x, y), table in probes.items():
            ax.plot(table["time"], table[name], label=f"({x:g}, {y:g})")
        ax.set_ylabel(name.replace("_", " "))
        ax.grid(alpha=0.3)
    axes[0, 0].legend(title="probe (x, y)", fontsize="small")
    axes[-1, 0].set_xlabel(f"time [{time_unit}]")
    fig.tight_layout()
    save(fig, out_dir, "probes.png")


def summary(snap):
    """Extrema of u, v, p with their locations, and the relative size of ∇·u, u·∇u."""
    print(f"\nsummary of {snapshot_label(snap)} ({os.path.basename(snap.info.h5_file)}, "
          f"{len(snap.nodes)} nodes):")

    def at(values, index):
        x, y = snap.nodes[index]
        return f"{values[index]: .6e} at ({x:.4f}, {y:.4f})"

    for name, label, kinds in [("u", "u", ["max"]), ("v", "v", ["min", "max"]),
                               ("pressure", "p", ["min", "max"])]:
        for kind in kinds if name in snap.fields else []:
            values = snap.fields[name]
            print(f"  {kind} {label:2s} = {at(values, getattr(np, 'arg' + kind)(values))}")
    if "u" in snap.fields and "v" in snap.fields:
        speed = np.hypot(snap.fields["u"], snap.fields["v"]).max()
        print(f"  max|u|  = {speed: .6e}  (velocity magnitude)")
        for name, label in [("divergence", "max|∇·u| / max|u|"),
                            ("inertia", "max|u·∇u| / max|u|")]:
            if name in snap.fields:
                ratio = np.abs(snap.fields[name]).max() / speed if speed > 0 else np.nan
                print(f"  {label} = {ratio:.3e}")


def main():
    parser = vio.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", metavar="RUN_DIR")
    parser.add_argument("--step", type=int,
                        help="snapshot nearest this step (default: 100 if written, else last)")
    parser.add_argument("--out", help="output directory (default: RUN_DIR/figures)")
    args = parser.parse_args()

    run = vio.Run(args.run_dir)
    stats = run.statistics()  # read now, so that a missing file stops us early
    if args.step is not None:
        chosen = run.nearest_snapshot(step=args.step)
        if chosen.step != args.step:
            print(f"note: no snapshot at step {args.step}; using step {chosen.step}")
    else:
        chosen = next((s for s in run.snapshots if s.step == 100), run.snapshots[-1])
    out_dir = vio.output_directory(args.out or os.path.join(args.run_dir, "figures"))

    length, time_unit = run.units()
    for info in dict.fromkeys([run.snapshots[0], chosen]):
        snap = run.load(info)
        plot_snapshot(snap, out_dir, length)
    plot_statistics(stats, out_dir, time_unit)
    plot_probes(run, out_dir, time_unit)
    summary(snap)  # the chosen snapshot is drawn last


if __name__ == "__main__":
    vio.main_guard(main)
