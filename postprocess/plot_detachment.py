#!/usr/bin/python3
"""Detachment of a run with Detachment/Release = true (doc/detachment.md) on
one page: φ + φ_d at the first snapshot, the first after the largest release
and the last, with the initial outline dashed, the attached φ's outline black
and the detached fraction φ_d's red, and the detached mass against time: released, still in the
flow and carried out through the outlet, with each release coloured by its
centroid's height (squares: releases by connectivity).

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
    released = stats["detached_mass"] > 0
    largest = stats["time"][np.argmax(stats["detached_mass"])]
    after = next((info for info in snapshots if info.time >= largest), snapshots[-1])
    chosen = [snapshots[0], after, snapshots[-1]]
    first = run.load(chosen[0])

    top = np.nanmax(first.fields["volume_fraction"])
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    for ax, info in zip(axes.flat[:3], chosen):
        snap = run.load(info)
        # All the biofilm, attached or carried: φ + φ_d.
        total = np.nan_to_num(snap.fields["volume_fraction"]) + np.nan_to_num(
            snap.fields.get("phi_detached", 0))
        mesh = ax.tripcolor(snap.triangulation, total, shading="gouraud", cmap="viridis",
                            vmin=0, vmax=top)
        draw_outline(ax, first.triangulation, first.fields["volume_fraction"], colors="w",
                     linewidths=0.8, linestyles="dashed")
        draw_outline(ax, snap.triangulation, snap.fields["volume_fraction"], linewidths=1.2)
        draw_outline(ax, snap.triangulation, snap.fields.get("phi_detached"), colors="r",
                     linewidths=1.2)
        ax.set(aspect="equal", ylim=(0, 0.5), xlabel=f"x [{length}]", ylabel=f"y [{length}]",
               title=f"φ + φ_d at t = {snap.time:.3g} ({time_unit})")
        fig.colorbar(mesh, ax=ax, shrink=0.7)

    ax = axes.flat[3]
    scale = 100 / stats["volume_fraction_integral"][0]
    fraction = scale * stats["detached_mass_total"]
    ax.plot(stats["time"], fraction, "k-", label="released (% of ∫φ(0))")
    if "detached_mass_in_flow" in stats:
        ax.plot(stats["time"], scale * stats["detached_mass_in_flow"], "r--",
                label="in the flow (∫φ_d)")
        ax.plot(stats["time"], scale * stats["detached_mass_outflow"], "b-.",
                label="carried out through the outlet")
    by_connectivity = released & (stats.get("detached_by_connectivity",
                                            np.zeros_like(fraction)) > 0)
    by_strength = released & ~by_connectivity
    colours = dict(cmap="plasma", vmin=0, vmax=max(stats["detached_centroid_y"].max(), 1e-12))
    scatter = ax.scatter(stats["time"][by_strength], fraction[by_strength],
                         c=stats["detached_centroid_y"][by_strength], s=18,
                         label="a release, coloured by its centroid's y", **colours)
    ax.scatter(stats["time"][by_connectivity], fraction[by_connectivity],
               c=stats["detached_centroid_y"][by_connectivity], s=40, marker="s",
               edgecolors="k", label="a release cutting a piece off the wall", **colours)
    fig.colorbar(scatter, ax=ax, shrink=0.7, label=f"centroid y [{length}]")
    ax.set(xlabel=f"t ({time_unit})", ylabel="detached [%]", title="detached biofilm")
    ax.legend(fontsize=8, loc="center left")
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
