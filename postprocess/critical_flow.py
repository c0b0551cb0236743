#!/usr/bin/python3
"""Critical flow (issue 14): for each biofilm profile, the smallest inflow
strength U_max that detaches a given fraction of the biofilm, by bisection.

Each run is the thesis' case (prm/thesis.prm: Table 4.1, Poiseuille inflow
U_max 4y(1-y) ramped up over T_ramp) with the profile as initial φ, the inflow
held at U_max after the ramp, on a coarse mesh for a short time, and
Detachment/Release on (doc/detachment.md). Its detached fraction is
detached_mass_total / ∫φ(0) at the end. Bracketing: U_max doubles from
--start until the fraction reaches --fraction; then bisection until the
bracket is within --tolerance (relative). The critical U_max is the upper end
of the final bracket (a flow known to detach the fraction).

Runs are cached: WORK/<profile>/umax-<U_max>/ is reused when its
statistics.csv reaches the last step, so a second call (or one with more
profiles, a tighter tolerance) only runs what is new.

Writes WORK/critical_flow.md (the table) and WORK/critical_flow.png (the
figure: detached fraction against U_max per profile, and each profile's
outline before and after the critical run, one panel per profile).

    /usr/bin/python3 postprocess/critical_flow.py --viscofilm build/viscofilm \\
        --work critical-flow
"""
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import viscofilm_io as vio  # noqa: E402
from plot_run import draw_outline  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

REPOSITORY = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROFILES = ["bulb", "flat", "short", "tall", "fat", "thin"]
STRESS_UNIT_PA = 0.0167  # ηs U0/L0 with Table 4.1 (doc/loads.md)

RUN_PRM = """include {default}
subsection Geometry
  set Initial global refinement = {refinement}
end
subsection Time stepping
  set Time step       = {time_step!r}
  set Number of steps = {steps}
end
subsection Boundary conditions
  subsection Inlet
    set Function constants = Umax={umax!r}, Tramp=0.15625, Toff=1e10
  end
end
subsection Initial conditions
  set Volume fraction = {profile}
end
subsection Detachment
  set Release          = true
  set Criterion        = {criterion}
  set Stress threshold = {strength!r}
  set Duration         = {duration!r}
end
subsection Output
  set Directory    = output
  set Interval     = {steps}
  set Probe points =
end
"""


def parse_arguments():
    parser = vio.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--viscofilm", default=os.path.join(REPOSITORY, "build", "viscofilm"))
    parser.add_argument("--work", default="critical-flow",
                        help="directory of the runs (the cache) and results")
    parser.add_argument("--profiles", nargs="+", default=PROFILES,
                        help="Initial conditions/Volume fraction values (default: the thesis' six)")
    parser.add_argument("--fraction", type=float, default=0.1,
                        help="detached fraction of ∫φ(0) that counts as detached (default 0.1)")
    parser.add_argument("--criterion", default="von Mises",
                        choices=["von Mises", "interface traction"])
    parser.add_argument("--strength", type=float, default=10.0,
                        help="Detachment/Stress threshold in ηs U0/L0 (default 10 ≈ 0.17 Pa)")
    parser.add_argument("--duration", type=float, default=0.0,
                        help="Detachment/Duration in T0 (default 0)")
    parser.add_argument("--refinement", type=int, default=4,
                        help="Geometry/Initial global refinement (default 4: Δx = 1/16)")
    parser.add_argument("--steps", type=int, default=60,
                        help="time steps of k = 0.1 Δx (default 60: t = 0.375 at Δx = 1/16, "
                             "the ramp is 0.156)")
    parser.add_argument("--start", type=float, default=0.1,
                        help="first U_max of the bracketing (default 0.1, the thesis' flow)")
    parser.add_argument("--tolerance", type=float, default=0.05,
                        help="relative width of the final bracket (default 0.05)")
    parser.add_argument("--max-doublings", type=int, default=10)
    options = parser.parse_args()
    if not os.access(options.viscofilm, os.X_OK):
        raise vio.UserError(f"--viscofilm: {options.viscofilm} is not an executable")
    if not 0 < options.fraction < 1:
        raise vio.UserError(f"--fraction must be in (0, 1), got {options.fraction}")
    if options.strength <= 0 or options.start <= 0 or not 0 < options.tolerance < 1:
        raise vio.UserError("--strength and --start must be > 0, --tolerance in (0, 1)")
    if options.refinement < 1 or options.steps < 1:
        raise vio.UserError("--refinement and --steps must be >= 1")
    return options


class Runner:
    """Runs (or reuses) one case per (profile, U_max) and reports progress."""

    def __init__(self, options):
        self.options = options
        self.run_times = []
        self.expected_runs = 0
        self.done_runs = 0
        self.started = time.monotonic()

    def directory(self, profile, umax):
        return os.path.join(self.options.work, profile, f"umax-{umax:.6g}")

    def statistics(self, directory):
        """statistics.csv of a finished run, else None."""
        path = os.path.join(directory, "output", "statistics.csv")
        if not os.path.exists(path):
            return None
        table = vio.read_csv(path)
        if len(table["step"]) == 0 or table["step"][-1] != self.options.steps:
            return None
        return table

    def run(self, profile, umax):
        """The finished run's statistics (running it if it is not cached)."""
        directory = self.directory(profile, umax)
        table = self.statistics(directory)
        cached = table is not None
        if not cached:
            os.makedirs(directory, exist_ok=True)
            o = self.options
            k = 0.1 / 2 ** o.refinement
            with open(os.path.join(directory, "run.prm"), "w") as f:
                f.write(RUN_PRM.format(default=os.path.join(REPOSITORY, "prm", "thesis.prm"),
                                       refinement=o.refinement, time_step=k, steps=o.steps,
                                       umax=umax, profile=profile, criterion=o.criterion,
                                       strength=o.strength, duration=o.duration))
            start = time.monotonic()
            with open(os.path.join(directory, "log"), "w") as log:
                result = subprocess.run([os.path.abspath(o.viscofilm), "run.prm"],
                                        cwd=directory, stdout=log, stderr=subprocess.STDOUT)
            if result.returncode != 0:
                raise vio.UserError(f"viscofilm failed in {directory} (see its log)")
            self.run_times.append(time.monotonic() - start)
            table = self.statistics(directory)
        self.done_runs += 1
        fraction = detached_fraction(table)
        mean = np.mean(self.run_times) if self.run_times else 0
        left = max(self.expected_runs - self.done_runs, 0) * mean
        print(f"  {profile:6s} U_max = {umax:<10.6g} detached {100 * fraction:6.2f} %"
              f"{'  (cached)' if cached else ''}   {time.monotonic() - self.started:6.0f} s,"
              f" ~{left:.0f} s left", flush=True)
        return table


def detached_fraction(table):
    return table["detached_mass_total"][-1] / table["volume_fraction_integral"][0]


def critical_flow(runner, profile):
    """Bracket, then bisect; returns (the runs {U_max: table}, the bracket)."""
    o = runner.options
    runs = {}

    def fraction(umax):
        runs[umax] = runner.run(profile, umax)
        return detached_fraction(runs[umax])

    low, high = 0.0, o.start
    doublings = 0
    while fraction(high) < o.fraction:
        low, high = high, 2 * high
        doublings += 1
        if doublings > o.max_doublings:
            print(f"  {profile}: not detached up to U_max = {low:.6g}; giving up")
            return runs, (low, math.inf)
    while high - low > o.tolerance * high:
        middle = 0.5 * (low + high)
        if fraction(middle) >= o.fraction:
            high = middle
        else:
            low = middle
    return runs, (low, high)


def main():
    o = parse_arguments()
    os.makedirs(o.work, exist_ok=True)
    runner = Runner(o)
    # Per profile: bracketing from --start (about 1–3 runs) and the bisection.
    bisections = math.ceil(math.log2(1 / o.tolerance))
    runner.expected_runs = len(o.profiles) * (2 + bisections)
    print(f"Critical flow for {len(o.profiles)} profile(s): fraction {o.fraction}, "
          f"{o.criterion} > {o.strength:g}, Δx = 1/{2 ** o.refinement}, {o.steps} steps")
    results = {}
    for profile in o.profiles:
        results[profile] = critical_flow(runner, profile)
        runner.expected_runs = runner.done_runs + (
            len(o.profiles) - len(results)) * (runner.done_runs / len(results))

    lines = [f"Smallest inflow U_max (Poiseuille, held after the ramp) that detaches "
             f"{100 * o.fraction:g} % of the biofilm by t = {o.steps * 0.1 / 2 ** o.refinement:g} "
             f"T0; {o.criterion} strength {o.strength:g} ηs U0/L0 "
             f"(≈ {o.strength * STRESS_UNIT_PA:.3g} Pa), Duration {o.duration:g}; "
             f"Δx = 1/{2 ** o.refinement}, k = 0.1 Δx. The bracket is [U_low, U_crit]; "
             f"wall shear and von Mises: the largest over the critical run.",
             "",
             "| profile | ∫φ(0) | U_low | U_crit | detached at U_crit | max wall shear stress | max von Mises | runs |",
             "|---|---|---|---|---|---|---|---|"]
    for profile, (runs, (low, high)) in results.items():
        table = runs.get(high)
        if table is None:
            lines.append(f"| {profile} | | {low:.4g} | > {low:.4g} | | | | {len(runs)} |")
            continue
        lines.append(f"| {profile} | {table['volume_fraction_integral'][0]:.4g} | {low:.4g} | "
                     f"{high:.4g} | {100 * detached_fraction(table):.1f} % | "
                     f"{np.max(table['wall_shear_stress_max']):.3g} | "
                     f"{np.max(table['von_mises_max']):.3g} | {len(runs)} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(o.work, "critical_flow.md"), "w") as f:
        f.write(text)
    print(text)

    fig = plt.figure(figsize=(13, 5.5))
    grid = fig.add_gridspec(3, 4)
    curves = fig.add_subplot(grid[:, :2])
    for profile, (runs, (low, high)) in results.items():
        umax = sorted(runs)
        line, = curves.plot(umax, [100 * detached_fraction(runs[u]) for u in umax], "o-",
                            ms=3, label=profile)
        if high in runs:
            curves.axvline(high, color=line.get_color(), lw=0.6, ls=":")
    curves.axhline(100 * o.fraction, color="k", lw=0.8, ls="--")
    curves.set(xlabel="inflow U_max [U0 = 1 cm/min]", ylabel="detached [% of ∫φ(0)]",
               title=f"{o.criterion} > {o.strength:g} ηs U0/L0 (≈ {o.strength * STRESS_UNIT_PA:.2g}"
                     f" Pa), Δx = 1/{2 ** o.refinement}, t = {o.steps * 0.1 / 2 ** o.refinement:g} T0")
    curves.legend(fontsize=8)
    # One small panel per profile: the outline before and after its critical run.
    for index, (profile, (runs, (low, high))) in enumerate(results.items()):
        if index >= 6:
            break
        ax = fig.add_subplot(grid[index // 2, 2 + index % 2])
        colour = f"C{index}"
        if high in runs:
            run = vio.Run(os.path.join(runner.directory(profile, high), "output"))
            for snapshot, style in ((run.snapshots[0], dict(colors="k", linewidths=0.8,
                                                            linestyles="dashed")),
                                    (run.snapshots[-1], dict(colors=colour, linewidths=1.5))):
                snap = run.load(snapshot)
                draw_outline(ax, snap.triangulation, snap.fields["volume_fraction"], **style)
        ax.set(aspect="equal", xlim=(0.2, 0.8), ylim=(0, 0.35), xticks=[], yticks=[],
               title=f"{profile}: U_crit = {high:.3g}")
        ax.title.set_fontsize(9)
    fig.text(0.75, 0.01, "outline φ = 0.05 at t = 0 (dashed) and at the end of the critical "
             "run; x in [0.2, 0.8], y in [0, 0.35] cm", ha="center", fontsize=8)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    figure = os.path.join(o.work, "critical_flow.png")
    fig.savefig(figure, dpi=120)
    print(f"wrote {figure} and {os.path.join(o.work, 'critical_flow.md')}")


if __name__ == "__main__":
    vio.main_guard(main)
