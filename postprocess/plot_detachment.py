#!/usr/bin/python3
"""Detachment of a run with Detachment/Release = true (doc/detachment.md) on
one page: φ at the first, a middle and the last snapshot with the initial
outline dashed, and the detached fraction of ∫φ(0) against time with the
height of each release's centroid.

    /usr/bin/python3 postprocess/plot_detachment.py output-detachment [--out FILE]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import viscofilm_io as vio  # noqa: E402
from plot_run import draw_outline  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    parser = vio.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", metavar="RUN_DIR")
    parser.add_argument("--out", help="figure file (default RUN_DIR/figures/detachment.png)")
    options = parser.parse_args()
    run = vio.Run(options.run_dir)
    stats = run.statistics()
    if "detached_mass_total" not in stats:
        raise vio.UserError(f"{options.run_dir} was run without Detachment/Release = true")
    length, time_unit = run.units()
    snapshots = run.snapshots
    chosen = [snapshots[0], snapshots[len(snapshots) // 2], snapshots[-1]]
    first = run.load(chosen[0])

    top = np.nanmax(first.fields["volume_fraction"])
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    for ax, info in zip(axes.flat[:3], chosen):
        snap = run.load(info)
        mesh = ax.tripcolor(snap.triangulation, np.nan_to_num(snap.fields["volume_fraction"]),
                            shading="gouraud", cmap="viridis", vmin=0, vmax=top)
        draw_outline(ax, first.triangulation, first.fields["volume_fraction"], colors="w",
                     linewidths=0.8, linestyles="dashed")
        draw_outline(ax, snap.triangulation, snap.fields["volume_fraction"], linewidths=1.2)
        ax.set(aspect="equal", ylim=(0, 0.5), xlabel=f"x [{length}]", ylabel=f"y [{length}]",
               title=f"φ at t = {snap.time:.3g} ({time_unit}); dashed: t = 0")
        fig.colorbar(mesh, ax=ax, shrink=0.7)

    ax = axes.flat[3]
    fraction = 100 * stats["detached_mass_total"] / stats["volume_fraction_integral"][0]
    ax.plot(stats["time"], fraction, "k-", label="detached (% of ∫φ(0))")
    released = stats["detached_mass"] > 0
    scatter = ax.scatter(stats["time"][released], fraction[released],
                         c=stats["detached_centroid_y"][released], cmap="plasma", s=18,
                         label="a release, coloured by its centroid's y")
    fig.colorbar(scatter, ax=ax, shrink=0.7, label=f"centroid y [{length}]")
    ax.set(xlabel=f"t ({time_unit})", ylabel="detached [%]",
           title="detached biofilm (taken away by the flow)")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    out = options.out or os.path.join(vio.output_directory(run.path("figures")),
                                      "detachment.png")
    fig.savefig(out, dpi=120)
    print(out)
    last = np.flatnonzero(released)
    print(f"detached {fraction[-1]:.2f} % of ∫φ(0) = {stats['volume_fraction_integral'][0]:.6g}"
          f" in {released.sum()} steps" +
          (f", first at t = {stats['time'][last[0]]:.4g}" if len(last) else ""))


if __name__ == "__main__":
    vio.main_guard(main)
