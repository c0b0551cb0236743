#!/usr/bin/python3
"""benchmarks/cylinder/time_average.py -- the drag of a cylinder run that
cycles instead of settling: K's mean over whole periods (doc/benchmarks.md,
"Wi ≥ 0.6: the stagnation points and the wake's strand").

Usage:  benchmarks/cylinder/time_average.py RUN_DIRECTORY... [--from T] [--published K]
                                              [--label NAME]... [--plot FILE.png]

For each RUN_DIRECTORY (its statistics.csv, column force_x_Cylinder) and the
rows with time >= T (default 10): K's range, the times at which K - mean
crosses zero upwards, and those at which it crosses downwards; of the two,
the set spanning more whole periods gives the period (the mean distance
between its crossings) and the mean of K over those whole periods (the mean
over all rows from T if neither set has two crossings). With --published the
relative errors are printed too. With --plot, K(t) of every run (labelled by --label, one per directory, or
by the directory's name) with its mean and the published K is drawn into
FILE.png; that needs Debian's python3-matplotlib (/usr/bin/python3).
"""

import argparse
import os
import sys

sys.dont_write_bytecode = True  # importing run.py leaves no __pycache__ here
from run import die, force_column, read_csv  # noqa: E402  benchmarks/cylinder/run.py


def read(directory):
    """(time, K) of every row of the run's statistics.csv."""
    path = os.path.join(directory, "statistics.csv")
    try:
        rows = read_csv(path)
    except (OSError, ValueError) as error:
        die("cannot read %s: %s" % (path, error))
    if not rows:
        die("%s has no rows" % path)
    key = force_column(rows[0])
    return [(row["time"], row[key]) for row in rows]


def crossings(series, level, sign):
    """The times at which sign * (K - level) changes from - to +,
    interpolated linearly between the two rows. A step-to-step wobble
    crosses the level many times; the period wanted is the slow cycle's, so
    crossings closer than one time unit are merged."""
    times = []
    for (t0, k0), (t1, k1) in zip(series, series[1:]):
        if sign * k0 < sign * level <= sign * k1:
            t = t0 + (t1 - t0) * (level - k0) / (k1 - k0)
            if not times or t - times[-1] > 1.0:
                times.append(t)
    return times


def mean_between(series, start, end):
    """The trapezoidal mean of K over [start, end]."""
    points = [(t, k) for t, k in series if start <= t <= end]
    area = sum(0.5 * (k0 + k1) * (t1 - t0) for (t0, k0), (t1, k1) in zip(points, points[1:]))
    return area / (points[-1][0] - points[0][0])


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directories", nargs="+")
    parser.add_argument("--from", dest="start", type=float, default=10.0)
    parser.add_argument("--published", type=float, default=None)
    parser.add_argument("--label", action="append", default=[])
    parser.add_argument("--plot", default=None)
    arguments = parser.parse_args()
    if arguments.label and len(arguments.label) != len(arguments.directories):
        die("give one --label per directory (%d directories, %d labels)"
            % (len(arguments.directories), len(arguments.label)))
    labels = arguments.label or [os.path.basename(os.path.normpath(d))
                                 for d in arguments.directories]
    curves = []

    print("# run  t_from t_end  K_min K_max  period  K_mean(whole periods) [error]")
    for directory, label in zip(arguments.directories, labels):
        whole = read(directory)
        series = [(t, k) for t, k in whole if t >= arguments.start]
        if len(series) < 3:
            print("%s: fewer than three rows from t = %g" % (directory, arguments.start))
            continue
        values = [k for _, k in series]
        level = mean_between(series, series[0][0], series[-1][0])
        times = max(crossings(series, level, +1), crossings(series, level, -1),
                    key=lambda c: (len(c), c[-1] - c[0] if c else 0.0))
        if len(times) >= 2:
            period = (times[-1] - times[0]) / (len(times) - 1)
            mean = mean_between(series, times[0], times[-1])
            window = "%d whole periods, t = %.1f-%.1f" % (len(times) - 1, times[0], times[-1])
        else:
            period, mean, window = float("nan"), level, "no whole period"
        error = ("  %+.2f %%" % (100 * (mean / arguments.published - 1))
                 if arguments.published else "")
        print("%s  %.2f %.2f  %.3f %.3f  %.2f  %.3f (%s)%s"
              % (directory, series[0][0], series[-1][0], min(values), max(values), period,
                 mean, window, error))
        curves.append((label, whole, mean))
    if arguments.plot:
        plot(curves, arguments.published, arguments.plot)


def plot(curves, published, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        die("--plot needs Debian's python3-matplotlib (run it with /usr/bin/python3): %s"
            % error)
    figure, axes = plt.subplots(figsize=(7, 4))
    for (label, series, mean), colour in zip(curves, plt.rcParams["axes.prop_cycle"].by_key()["color"]):
        axes.plot([t for t, _ in series], [k for _, k in series], color=colour,
                  label="%s (mean %.2f)" % (label, mean))
        axes.axhline(mean, color=colour, linestyle=":", linewidth=1)
    if published:
        axes.axhline(published, color="black", linewidth=1.5,
                     label="published %.2f" % published)
        axes.axhspan(published * 0.995, published * 1.005, color="grey", alpha=0.2,
                     label="published ± 0.5 %")
        axes.set_ylim(published * 0.985, published * 1.01)
    axes.set_xlabel("t (units of R/U)")
    axes.set_ylabel("K")
    axes.legend(fontsize=8, loc="lower right")
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    print("wrote %s" % path)


if __name__ == "__main__":
    main()
