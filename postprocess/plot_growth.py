#!/usr/bin/python3
"""Figures of a growing biofilm (Growth/Enable): the substrate of the last
snapshot with the biofilm's outline at every snapshot, coloured by time, and
the biomass and the thickness on the walls against time.

    /usr/bin/python3 postprocess/plot_growth.py RUN_DIR [--out DIR] [--hours]

Writes growth_outlines.png and growth_statistics.png into DIR (default:
RUN_DIR/figures). Needs numpy, h5py and matplotlib (Debian's python3-*
packages: run it with /usr/bin/python3).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from viscofilm_io import np

import matplotlib.pyplot as plt
from matplotlib import cm, colors

from plot_run import draw_field, save


def time_scale(hours, time_unit):
    """Divisor and label of the time axis: hours for SI runs if asked."""
    return (3600.0, "h") if hours and time_unit == "s" else (1.0, time_unit)


def plot_outlines(run, out_dir, length, divisor, unit):
    snaps = [run.load(info) for info in run.snapshots]
    last = snaps[-1]
    if "substrate" not in last.fields:
        raise vio.UserError(f"{run.directory}: the snapshots have no substrate "
                            "(Substrate/Enable = false?)")
    fig, ax = plt.subplots(figsize=(7, 5.5))
    norm = colors.Normalize(snaps[0].time / divisor, last.time / divisor)
    outlines = [(vio.interpolate_onto(snap, last)["volume_fraction"],
                 {"colors": [cm.plasma(norm(snap.time / divisor))], "linewidths": 1.2})
                for snap in snaps]
    draw_field(fig, ax, last.triangulation, last.fields["substrate"],
               f"substrate S at t = {last.time / divisor:.3g} {unit}; outlines φ = "
               f"{vio.BIOFILM_LEVEL} from t = 0 (dark) on", outlines, length=length)
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap="plasma"), ax=ax, shrink=0.85,
                 label=f"outline at t [{unit}]")
    save(fig, out_dir, "growth_outlines.png")


def plot_statistics(stats, out_dir, length, divisor, unit):
    needed = ["volume_fraction_integral", "biofilm_thickness_mean", "biofilm_thickness_max"]
    missing = [name for name in needed if name not in stats]
    if missing:
        raise vio.UserError("statistics.csv lacks " + ", ".join(missing) +
                            " (Growth/Enable = false?)")
    t = stats["time"] / divisor
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
    left.plot(t, stats["volume_fraction_integral"], label="∫φ")
    if "biomass_produced" in stats:
        left.plot(t, stats["biomass_produced"], "--", label="produced")
        left.plot(t, stats["biomass_decayed"], ":", label="decayed")
    left.set(xlabel=f"t [{unit}]", ylabel=f"[{length}^2 or ^3]", title="biomass (volume fraction)")
    left.legend()
    right.plot(t, stats["biofilm_thickness_mean"], label="mean")
    right.plot(t, stats["biofilm_thickness_max"], label="max")
    right.set(xlabel=f"t [{unit}]", ylabel=f"[{length}]", title="thickness on the walls")
    right.legend()
    save(fig, out_dir, "growth_statistics.png")


def main():
    parser = vio.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", metavar="RUN_DIR")
    parser.add_argument("--out", help="output directory (default: RUN_DIR/figures)")
    parser.add_argument("--hours", action="store_true", help="time in hours (SI runs)")
    args = parser.parse_args()
    run = vio.Run(args.run_dir)
    stats = run.statistics()
    out_dir = vio.output_directory(args.out or os.path.join(args.run_dir, "figures"))
    length, time_unit = run.units()
    divisor, unit = time_scale(args.hours, time_unit)
    plot_outlines(run, out_dir, length, divisor, unit)
    plot_statistics(stats, out_dir, length, divisor, unit)


if __name__ == "__main__":
    vio.main_guard(main)
