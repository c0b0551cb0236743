#!/usr/bin/python3
"""benchmarks/cylinder/run.py -- the confined-cylinder benchmark: the drag
coefficient K of an Oldroyd-B fluid (β = 0.59, blockage 0.5, creeping flow)
against the published values, on three meshes.

Usage:  benchmarks/cylinder/run.py --study [--levels L,...] [--wi W,...] [--np N] [--doc]
        benchmarks/cylinder/run.py [--levels 1,2,3] [--wi 0,0.1,...,0.7]
            [--graded B [--distance D] [--wake W]]
            [--time-step K] [--refine-time-step] [--order 1|2] [--picard N] [--log-feet]
            [--np N] [--work DIR] [--tolerance T] [--doc] [--quick] [--table-only]

Runs prm/cylinder.prm once per mesh level (Geometry/Initial global
refinement) and Weissenberg number, each on N MPI ranks (default 2), and
takes K = force_x_Cylinder (ηs + ηp = 1, mean inflow velocity 1, R = 1, per
unit depth, so K = F/(μU)). Wi = 0 is the Newtonian fluid of viscosity 1
(Model/Viscoelastic = false, one steady Stokes solve). For Wi > 0 the time
step is K on every level (with --refine-time-step: K on the coarsest level,
halved with each level); the steady K depends on k by 0.12 % between k =
0.04 and 0.02 at level 2, Wi = 0.5, against a mesh error of −2.6 % there
(doc/verification.md), so the default keeps k. A run is stopped as soon
as it is steady: the mean of K over the last max(1, 2 Wi) time units
differs from the mean over the same time before by less than T (relative,
default 1e-5; read from statistics.csv while it runs), and K is that last
mean. A run that reaches its last step unsteady is marked in the table.

--study runs the table of the issue's target: the meshes, Picard cap and
tolerance of STUDY and, per Wi, the time step and Order chosen by
measurement (doc/benchmarks.md, "The time step at small Wi"); --wi and
--levels pick rows and columns of it.

Every run directory is named by its mesh, Wi, k and Order
(runs/levelL[-gradedB-dD-wW]-WiW-kK-oO, runs/levelL[...]-Wi0 for the
Newtonian solve), so that any call that needs a case reuses it: a finished
run (result.json next to an unchanged case.prm) is skipped, and an
interrupted one resumes from its last checkpoint (every 50 steps).

--graded B makes the meshes graded instead of uniform: level L is the
uniform level B (Geometry/Initial global refinement) refined L − B more
times near the cylinder and its wake (Geometry/Cylinder refinement: bands
of width D/2^(n-1) around the cylinder and the first W of the wake's
centreline, --distance D, --wake W), so that its cells at the cylinder and
in the wake are those of the uniform level L.

--log-feet interpolates log c at the departure feet (Stress/Foot
interpolation = logarithm): at Wi = 0.7 it removes the cycle of K that the
wake's strand drives with c interpolated (doc/verification.md).

--picard N caps the Picard loop at N iterations per step (Time
stepping/Maximum Picard iterations): with the implicit elastic viscosity of
prm/cylinder.prm the steps converge to the same steady state with 3 as with
the 20 iterations that reach the tolerance, in a quarter of the time
(doc/verification.md).

Prints the table of K per mesh, the published K, the relative error of the
finest mesh, the observed order p = log2(|K1 − K2| / |K2 − K3|) of the last
three levels and the Richardson extrapolation with that order. --doc also
writes doc/figures/cylinder_drag.png (K(Wi)) and the table as markdown to
benchmarks/cylinder/results.md (pasted into doc/verification.md).
--work keeps the runs in DIR (default benchmarks/cylinder/runs) and reuses
every finished run whose case.prm is unchanged. --quick: the coarsest level,
Wi = 0 and 0.1 only (checks the set-up in a few minutes). --table-only runs
nothing: the table (and with --doc the figure) of the finished runs, "–"
where a case has not run or did not finish (a long study can be run level by
level, Wi by Wi, and tabulated at the end).
"""

import argparse
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time

SCRIPT_DIR = os.path.dirname(os.path.realpath(__file__))
sys.path.insert(0, os.path.dirname(SCRIPT_DIR))
from benchlib import (REPO, die, ensure_binary, log, machine_description,  # noqa: E402
                      mpi_environment, read_csv, source_of)

# Published drag coefficients K = F/(μU), rounded to 0.01: the values of
# Alves, Pinho & Oliveira 2001 (J. Non-Newt. Fluid Mech. 97, 207-232) and
# Hulsen, Fattal & Kupferman 2005 (J. Non-Newt. Fluid Mech. 127, 27-39),
# which agree to 0.03 %. doc/verification.md says which could be checked
# against a copy of the table and which against secondary sources only.
PUBLISHED = {0.0: 132.36, 0.1: 130.36, 0.2: 126.62, 0.3: 123.19, 0.4: 120.59,
             0.5: 118.83, 0.6: 117.78, 0.7: 117.32}
# The parameter that lists the boundaries whose forces statistics.csv gets
# (helper "forces"; must match prm/cylinder.prm).
FORCE_ENTRY = ("Forces", "Boundaries")
FORCE_COLUMN = "force_x_cylinder"  # matched case-insensitively
ETA_P = 0.41
POLL_SECONDS = 2.0
# A run writes a checkpoint every this many steps, from which an interrupted
# study resumes it.
CHECKPOINT_STEPS = 50

# The study (--study): the meshes, and per Wi the time step and Order chosen
# by the measurements of doc/benchmarks.md ("The time step at small Wi"):
# Order 2 removes the O(k/λ) steady-state error of Order 1's relaxation
# (Wi = 0.1: 0.01 % from k = 0.04 to 0.02), and from level 3 on K hardly
# depends on k (Wi = 0.3: 0.003 %), so k = 0.04 at every Wi.
STUDY = {"graded": 1, "distance": 2.0, "wake": 0.0, "levels": "2,3,4", "picard": 3,
         "tolerance": 1e-4,
         "schedule": {0.0: (None, None), 0.1: (0.04, 2), 0.2: (0.04, 2), 0.3: (0.04, 2),
                      0.4: (0.04, 2), 0.5: (0.04, 2), 0.6: (0.04, 2), 0.7: (0.04, 2)}}


def case_prm(directory, mesh, wi, time_step, steps, order, picard=None, log_feet=False):
    """The parameters of one run: prm/cylinder.prm with the mesh (uniform
    level, Cylinder refinement, its distance, the wake's length), Wi, the
    time step, its order (the Picard cap, if given; log c interpolated at
    the feet, if log_feet), the checkpoints and the output directory
    replaced."""
    if wi == 0:
        model = """subsection Model
  set Viscoelastic = false
  subsection Water
    set Solvent viscosity = 1
    set Polymer viscosity = 0
  end
  subsection Biofilm
    set Solvent viscosity = 1
    set Polymer viscosity = 0
  end
end
"""
        constants = "Wi=0, etap=0"
    else:
        model = """subsection Model
  subsection Water
    set Relaxation time = %r
  end
  subsection Biofilm
    set Relaxation time = %r
  end
end
""" % (wi, wi)
        constants = "Wi=%r, etap=%r" % (wi, ETA_P)
        if log_feet:
            model += "subsection Stress\n  set Foot interpolation = logarithm\nend\n"
    return """include %s
subsection Geometry
  set Initial global refinement    = %d
  set Cylinder refinement          = %d
  set Cylinder refinement distance = %r
  set Wake refinement length       = %r
end
%ssubsection Boundary conditions
  subsection Inlet
    set Function constants = %s
  end
end
subsection Initial conditions
  set Function constants = %s
end
subsection Time stepping
  set Time step       = %r
  set Number of steps = %d
  set Order           = %d
%send
subsection Output
  set Directory = %s
  set Interval  = 0
end
subsection Checkpointing
  set Interval = %d
end
""" % ((os.path.join(REPO, "prm", "cylinder.prm"),) + mesh + (model, constants, constants,
       time_step, steps, order,
       "" if picard is None else "  set Maximum Picard iterations = %d\n" % picard,
       directory, 0 if wi == 0 else CHECKPOINT_STEPS))


def force_column(row):
    for key in row:
        if key.lower() == FORCE_COLUMN:
            return key
    die("statistics.csv has no column %s (is %s/%s = Cylinder set?); columns: %s"
        % (FORCE_COLUMN, FORCE_ENTRY[0], FORCE_ENTRY[1], ", ".join(row)))


def steadiness(rows, window):
    """(K, t, change, wobble): K the mean over the last @p window time units,
    change the relative difference of that mean from the window's before
    (None if the run is not that long yet), wobble the relative range of K
    in the last window. Means, not the last value: at Wi = 0.5 with three
    Picard iterations K cycles with period 4 steps by ±4e-4 about a steady
    mean (doc/benchmarks.md, "The time step at small Wi")."""
    key = force_column(rows[-1])
    t_end = rows[-1]["time"]
    if window == 0:
        return rows[-1][key], t_end, None, 0.0
    last = [row[key] for row in rows if row["time"] > t_end - window]
    mean = sum(last) / len(last)
    wobble = (max(last) - min(last)) / abs(mean)
    if t_end < 2 * window:
        return mean, t_end, None, wobble
    before = [row[key] for row in rows if t_end - 2 * window < row["time"] <= t_end - window]
    return mean, t_end, abs(mean - sum(before) / len(before)) / abs(mean), wobble


def read_rows(path):
    try:
        rows = read_csv(path)
    except (OSError, ValueError, TypeError):  # not written yet, or a line half written
        return []
    return rows


def run_to_steady_state(binary, ranks, directory, prm_text, window, tolerance):
    """Run one case (or reuse its result.json) and return its result. With
    @p window None the run is one steady Stokes solve (steady by definition).
    A run interrupted before (the same case.prm, no result.json) resumes from
    its last checkpoint."""
    os.makedirs(directory, exist_ok=True)
    prm = os.path.join(directory, "case.prm")
    result_file = os.path.join(directory, "result.json")
    same_case = os.path.exists(prm) and open(prm).read() == prm_text
    if same_case and os.path.exists(result_file):
        return json.load(open(result_file))
    statistics = os.path.join(directory, "statistics.csv")
    command = prm
    if same_case and os.path.exists(os.path.join(directory, "checkpoint")):
        command = os.path.join(directory, "resume.prm")
        with open(command, "w") as f:
            f.write("include %s\nsubsection Checkpointing\n  set Resume = true\nend\n" % prm)
        log("resuming %s from its checkpoint" % directory)
    else:
        with open(prm, "w") as f:
            f.write(prm_text)
        for stale in ("statistics.csv", "checkpoint", "checkpoint.old"):
            shutil.rmtree(os.path.join(directory, stale), ignore_errors=True)
            if os.path.isfile(os.path.join(directory, stale)):
                os.remove(os.path.join(directory, stale))
    start = time.time()
    with open(os.path.join(directory, "run.log"), "a") as output:
        # its own session, so that stopping it stops mpirun and its ranks only
        process = subprocess.Popen(["mpirun", "-np", str(ranks), binary, command], stdout=output,
                                   stderr=subprocess.STDOUT, env=mpi_environment(),
                                   start_new_session=True)
        steady = False
        while process.poll() is None:
            time.sleep(POLL_SECONDS)
            rows = read_rows(statistics) if window else []
            if len(rows) > 1:
                change = steadiness(rows, window)[2]
                if change is not None and change < tolerance:
                    steady = True
                    os.killpg(process.pid, signal.SIGTERM)
                    process.wait()
                    break
    wall = time.time() - start
    rows = read_rows(statistics)
    if not steady and process.returncode != 0:
        die("the run in %s failed (exit %d); see its run.log" % (directory, process.returncode))
    if not rows:
        die("the run in %s wrote no statistics.csv" % directory)
    k, t, change, wobble = steadiness(rows, window or 0.0)
    result = {"K": k, "time": t, "steps": len(rows) - 1, "wall": wall, "change": change,
              "wobble": wobble, "tolerance": tolerance,
              "steady": window is None or steady or (change is not None and change < tolerance)}
    with open(result_file, "w") as f:
        json.dump(result, f, indent=1)
    return result


def order_and_extrapolation(values):
    """Observed order and Richardson extrapolation from the last three
    values of a sequence on meshes refined by 2 (None where undefined)."""
    if len(values) < 3:
        return None, None
    k1, k2, k3 = values[-3:]
    if k2 == k3 or (k1 - k2) / (k2 - k3) <= 0:
        return None, None
    p = math.log2(abs(k1 - k2) / abs(k2 - k3))
    return p, k3 + (k3 - k2) / (2 ** p - 1)


def table(levels, wis, results, schedule):
    """The markdown table; @p schedule(level, wi) gives a case's (k, Order)."""
    header = ("| Wi | k | Order | " + " | ".join("K, level %d" % level for level in levels)
              + " | published K | error of the finest | order p | extrapolated K |")
    lines = [header, "|" + "---|" * (len(levels) + 7)]
    for wi in wis:
        steps = sorted({schedule(level, wi) for level in levels}, reverse=True)
        k_cell = ", ".join("%g" % k for k, _ in steps) if wi > 0 else "–"
        order_cell = ", ".join(sorted({"%d" % o for _, o in steps})) if wi > 0 else "–"
        runs = [results.get((level, wi)) for level in levels]
        cells = ["–" if run is None else
                 "%.3f%s" % (run["K"], "" if run["steady"] else " (unsteady)") for run in runs]
        finished = [run["K"] for run in runs if run is not None]
        published = PUBLISHED.get(wi)
        error = ("%+.2f %%" % (100 * (finished[-1] - published) / published)
                 if published and finished else "–")
        # the order needs three consecutive meshes
        p, extrapolated = (order_and_extrapolation(finished) if None not in runs[-3:]
                           else (None, None))
        lines.append("| %g | %s | %s | %s | %s | %s | %s | %s |" % (
            wi, k_cell, order_cell, " | ".join(cells), published or "–", error,
            "%.2f" % p if p is not None else "–",
            "%.3f" % extrapolated if extrapolated is not None else "–"))
    return "\n".join(lines)


def plot(levels, wis, results, path, mesh):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    published = sorted(PUBLISHED.items())
    ax.plot([w for w, _ in published], [k for _, k in published], "ks--", mfc="none",
            label="Alves et al. 2001, Hulsen et al. 2005")
    for level in levels:
        # only steady runs: an unsteady K is no point of the curve
        done = [wi for wi in wis if results.get((level, wi)) is not None
                and results[(level, wi)]["steady"]]
        ax.plot(done, [results[(level, wi)]["K"] for wi in done], "o-",
                label="viscofilm, %s %d" % (mesh, level))
    ax.set(xlabel="Wi = λU/R", ylabel="K = F_x / (μU)",
           title="Confined cylinder, Oldroyd-B, β = 0.59, R/H = 0.5")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--levels", default=None,
                        help="mesh refinement levels (2^(L+3) cells around the cylinder; "
                        "default 1,2,3, with --study the study's)")
    parser.add_argument("--wi", default=None,
                        help="Weissenberg numbers (default 0, 0.1, ..., 0.7)")
    parser.add_argument("--study", action="store_true",
                        help="the study's table: its meshes, Picard cap and tolerance, and "
                        "per Wi its time step and Order (STUDY); --wi and --levels select "
                        "from it")
    parser.add_argument("--time-step", type=float, default=0.04,
                        help="time step (on the coarsest level with --refine-time-step)")
    parser.add_argument("--refine-time-step", action="store_true",
                        help="halve the time step with each level")
    parser.add_argument("--graded", type=int, default=None, metavar="B",
                        help="graded meshes: uniform level B, refined to level L near the "
                        "cylinder and its wake")
    parser.add_argument("--distance", type=float, default=1.0,
                        help="width of the first graded band (halved with each level)")
    parser.add_argument("--wake", type=float, default=0.0,
                        help="length of the wake's centreline graded like the cylinder")
    parser.add_argument("--picard", type=int, default=None, metavar="N",
                        help="Time stepping/Maximum Picard iterations (default: prm/cylinder.prm's)")
    parser.add_argument("--order", type=int, choices=(1, 2),
                        help="Time stepping/Order (default: prm/cylinder.prm's)")
    parser.add_argument("--log-feet", action="store_true",
                        help="Stress/Foot interpolation = logarithm (run directories "
                        "named ...-log)")
    parser.add_argument("--tolerance", type=float, default=1e-5)
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--work", default=os.path.join(SCRIPT_DIR, "runs"))
    parser.add_argument("--doc", action="store_true",
                        help="write doc/figures/cylinder_drag.png and results.md")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--table-only", action="store_true",
                        help="run nothing; tabulate the finished runs")
    arguments = parser.parse_args()
    if arguments.study:
        for name in ("graded", "distance", "wake", "picard", "tolerance"):
            setattr(arguments, name, STUDY[name])
        arguments.levels = arguments.levels or STUDY["levels"]
    arguments.levels = arguments.levels or "1,2,3"
    levels = sorted(int(level) for level in arguments.levels.split(","))
    base = arguments.graded
    if base is not None and not 0 <= base <= levels[0]:
        die("--graded %d: the uniform level must lie in [0, the coarsest of --levels]" % base)

    def mesh_of(level):
        """(uniform level, Cylinder refinement, its distance, wake length)"""
        if base is None:
            return (level, 0, 1.0, 0.0)
        return (base, level - base, arguments.distance, arguments.wake)

    def schedule(level, wi):
        """(time step, Order) of a case"""
        if arguments.study:
            return STUDY["schedule"][wi]
        return (arguments.time_step / (2 ** (level - levels[0]) if arguments.refine_time_step
                                       else 1), arguments.order or 1)

    def directory_of(level, wi):
        """named by everything that makes a case, so that any call reuses it"""
        name = ("level%d" % level if base is None else
                "level%d-graded%d-d%g-w%g" % (level, base, arguments.distance, arguments.wake))
        if wi > 0:
            name += "-Wi%g-k%g-o%d" % ((wi,) + schedule(level, wi))
            if arguments.log_feet:
                name += "-log"
        else:
            name += "-Wi0"
        return os.path.join(arguments.work, name)
    wis = sorted(float(wi) for wi in (arguments.wi or "0,0.1,0.2,0.3,0.4,0.5,0.6,0.7").split(","))
    if arguments.study:
        unknown = [wi for wi in wis if wi not in STUDY["schedule"]]
        if unknown:
            die("--study: no time step chosen for Wi = %s; accepted: %s" % (
                ", ".join("%g" % wi for wi in unknown),
                ", ".join("%g" % wi for wi in sorted(STUDY["schedule"]))))
    if arguments.quick:
        levels, wis = levels[:1], [0.0, 0.1]
    build, binary = ensure_binary()
    log("%s; viscofilm %s" % (machine_description(), source_of(build)[1]))

    cases = [(level, wi) for level in levels for wi in wis]
    results, walls = {}, {}
    if arguments.table_only:
        cases = []
        for level in levels:
            for wi in wis:
                directory = directory_of(level, wi)
                result_file = os.path.join(directory, "result.json")
                if os.path.exists(result_file):
                    results[(level, wi)] = json.load(open(result_file))
    start = time.time()
    for number, (level, wi) in enumerate(cases):
        # the Newtonian case is one steady Stokes solve at Order 1
        k, order = schedule(level, wi) if wi > 0 else (arguments.time_step, 1)
        window = max(1.0, 2 * wi) if wi > 0 else None
        end_time = 10 + 30 * wi  # far beyond steady state (3.2 s of relaxation at Wi = 0.7)
        steps = 1 if wi == 0 else math.ceil(end_time / k)
        directory = directory_of(level, wi)
        results[(level, wi)] = run_to_steady_state(
            binary, arguments.np, directory,
            case_prm(directory, mesh_of(level), wi, k, steps, order, arguments.picard,
                     arguments.log_feet),
            window,
            arguments.tolerance)
        result = results[(level, wi)]
        walls[(level, wi)] = result["wall"]
        # what is left: each remaining case costs what the same Wi cost one
        # level coarser times 4 (the cells; 8 with --refine-time-step: twice
        # the steps), or what the last case of its level cost
        factor = 8 if arguments.refine_time_step else 4
        left = 0.0
        for other in cases[number + 1:]:
            coarser = (other[0] - 1, other[1])
            same_level = [w for (lv, _), w in walls.items() if lv == other[0]]
            left += (factor * walls[coarser] if coarser in walls
                     else same_level[-1] if same_level else factor * result["wall"])
        log("case %d/%d: level %d, Wi %g: K = %.4f at t = %.2f (%d steps, %s) in %.0f s; "
            "elapsed %.1f min, about %.0f min left"
            % (number + 1, len(cases), level, wi, result["K"], result["time"], result["steps"],
               "steady" if result["steady"] else "NOT steady", result["wall"],
               (time.time() - start) / 60, left / 60))

    text = table(levels, wis, results, schedule)
    print(text)
    if arguments.doc:
        with open(os.path.join(SCRIPT_DIR, "results.md"), "w") as f:
            if arguments.study:
                f.write("<!-- benchmarks/cylinder/run.py --doc --study (levels %s, --graded %d "
                        "--distance %g --wake %g --picard %d --tolerance %g; k and Order per "
                        "row); %s -->\n%s\n"
                        % (arguments.levels, base, arguments.distance, arguments.wake,
                           arguments.picard, arguments.tolerance, machine_description(), text))
            else:
                f.write("<!-- benchmarks/cylinder/run.py --doc --levels %s%s --time-step %g%s%s"
                        " --tolerance %g; %s -->\n%s\n"
                        % (arguments.levels,
                           "" if base is None else " --graded %d --distance %g --wake %g"
                           % (base, arguments.distance, arguments.wake),
                           arguments.time_step,
                           " --refine-time-step" if arguments.refine_time_step else "",
                           (" --order %d" % arguments.order if arguments.order else "")
                           + (" --picard %d" % arguments.picard if arguments.picard else ""),
                           arguments.tolerance, machine_description(), text))
        plot(levels, wis, results, os.path.join(REPO, "doc", "figures", "cylinder_drag.png"),
             "refinement" if base is None else "graded level")
        log("wrote benchmarks/cylinder/results.md and doc/figures/cylinder_drag.png")


if __name__ == "__main__":
    main()
