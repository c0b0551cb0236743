#!/usr/bin/python3
"""benchmarks/mapping/run.py -- the curved meshes' mapping: MappingQ(2), which
asks the manifolds for every cell's support points at each reinit, against
the MappingQCache filled once per mesh (issue 12 items 4 and 5).

Usage:  nice -n 10 benchmarks/mapping/run.py --old BUILD [--new BUILD]
            [--repeat R] [--pillar-steps N] [--cylinder-steps N]
            [--pillar-2d-steps N] [--cases NAME,...] [--work DIR]

Runs each case R times (default 2) on one rank with the binary of each build
(--old: a build of the code before the cache, e.g. main at 944c1b4; --new:
$VISCOFILM_BUILD or build/), the builds alternating, and prints per case and
build the minimum over the repeats of the whole run's wall time and of the
TimerOutput section "departure feet", and the new/old ratios; then the other
sections that map cells, and the Stokes solve (which does not: its spread
between runs is the machine's load). The cases:

  pillar-3d     prm/pillar-streamer-3d.prm (3D, adaptive to level 3 at the
                coat, the transfinite manifold around the pillar), its first
                N steps (default 3) with the inflow ramped up within the
                first step (Tramp = k) so that the feet cross the cells at
                the full U_max = 0.1 from step 2, no output
  cylinder-2d   prm/cylinder.prm on the graded level 3 mesh of
                benchmarks/cylinder/run.py --study (uniform level 1, bands of
                width 2 around the cylinder), Wi = 0.5, k = 0.04, Order 2,
                3 Picard iterations, N steps (default 20)
  pillar-2d     prm/examples/pillar-streamer.prm (2D, the flat gmsh mesh:
                MappingQ1), Number of steps = N (default 30: t = 0.3 s, 45
                steps once CFL 2 shortens them), no output. Only in --cases:
                the example needs Mixture = geometric, so its old build is
                one of 95752ca (before the mapping was decided once per run,
                when the feet took 60 % of its time), not of 944c1b4.

--cases: the cases run (default pillar-3d,cylinder-2d).

Both builds must give the same forces: the force columns of the last row of
statistics.csv of each run are compared, "NO" beyond 1e-8 of the row's
largest force.
"""

import argparse
import os
import sys

SCRIPT_DIR = os.path.dirname(os.path.realpath(__file__))
sys.path.insert(0, os.path.dirname(SCRIPT_DIR))
sys.path.insert(0, os.path.join(os.path.dirname(SCRIPT_DIR), "cylinder"))
from benchlib import (REPO, die, log, machine_description, read_csv,  # noqa: E402
                      run_case, source_of, timer_section)
import run as cylinder  # noqa: E402  benchmarks/cylinder/run.py


# The TimerOutput sections tabulated besides the feet: the ones that map
# cells (φ's transport has feet of its own), and the solve, which does not
# and so shows the machine's load.
SECTIONS = ["volume fraction", "stress update", "assemble stokes", "solve stokes", "softening"]


def shipped_prm(prm, changes, directory, steps):
    """The shipped parameter file @p prm (path below the repository) with
    @p changes, N steps and no output into @p directory."""
    return """include %s
%ssubsection Time stepping
  set Number of steps = %d
end
subsection Output
  set Directory = %s
  set Interval  = 0
end
""" % (os.path.join(REPO, prm), changes, steps, directory)


def pillar_prm(directory, steps):
    return shipped_prm("prm/pillar-streamer-3d.prm", """subsection Boundary conditions
  subsection Inlet
    set Function constants = Umax=0.1, Tramp=0.0125, Toff=0.3125, H=1, W=0.5
  end
end
""", directory, steps)


def pillar_2d_prm(directory, steps):
    # Its mesh file is named relative to the example's directory.
    return shipped_prm("prm/examples/pillar-streamer.prm", """subsection Geometry
  set Mesh file = %s
end
""" % os.path.join(REPO, "geometry", "flow_cell.msh"), directory, steps)


def cylinder_prm(directory, steps):
    study = cylinder.STUDY
    # Level 3: the uniform level 1 refined twice more near the cylinder.
    mesh = (study["graded"], 3 - study["graded"], study["distance"], study["wake"])
    return cylinder.case_prm(directory, mesh, 0.5, 0.04, steps, 2, study["picard"])


def last_forces(directory):
    rows = read_csv(os.path.join(directory, "statistics.csv"))
    return {key: value for key, value in rows[-1].items() if key.startswith("force_")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--old", required=True, help="build directory of the code before")
    parser.add_argument("--new", default=os.environ.get("VISCOFILM_BUILD",
                                                        os.path.join(REPO, "build")))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--pillar-steps", type=int, default=3)
    parser.add_argument("--cylinder-steps", type=int, default=20)
    parser.add_argument("--pillar-2d-steps", type=int, default=30)
    parser.add_argument("--cases", default="pillar-3d,cylinder-2d")
    parser.add_argument("--work", default=os.path.join(SCRIPT_DIR, "runs"))
    arguments = parser.parse_args()

    builds = {"old": os.path.abspath(arguments.old), "new": os.path.abspath(arguments.new)}
    for name, build in builds.items():
        if not os.access(os.path.join(build, "viscofilm"), os.X_OK):
            die("--%s %s: no viscofilm there" % (name, build))
    known = {"pillar-3d": (pillar_prm, arguments.pillar_steps),
             "cylinder-2d": (cylinder_prm, arguments.cylinder_steps),
             "pillar-2d": (pillar_2d_prm, arguments.pillar_2d_steps)}
    names = arguments.cases.split(",")
    for case in names:
        if case not in known:
            die("--cases: unknown case '%s' (known: %s)" % (case, ", ".join(known)))
    cases = {case: known[case] for case in names}

    results = {}  # (case, build) -> {"wall": [...], "feet": [...], "forces": row}
    for case, (make_prm, steps) in cases.items():
        for repeat in range(arguments.repeat):
            for name, build in builds.items():
                directory = os.path.join(arguments.work, "%s-%s-%d" % (case, name, repeat))
                log("%s, %s build, run %d of %d" % (case, name, repeat + 1, arguments.repeat))
                run = run_case(os.path.join(build, "viscofilm"), make_prm(directory, steps),
                               directory, 1)
                entry = results.setdefault((case, name), {"wall": [], "feet": []})
                entry["wall"].append(run["wall"])
                entry["feet"].append(timer_section(run["log"], "departure feet"))
                for section in SECTIONS:
                    entry.setdefault(section, []).append(timer_section(run["log"], section))
                entry["forces"] = last_forces(directory)

    print("Mapping, one rank, minimum of %d runs each" % arguments.repeat)
    print("machine: %s" % machine_description())
    for name, build in builds.items():
        print("%s: %s" % (name, source_of(build)[1]))
    print()
    print("| case | steps | run old [s] | run new [s] | new/old | feet old [s] | "
          "feet new [s] | new/old | forces equal |")
    print("|---|---|---|---|---|---|---|---|---|")
    for case, (_, steps) in cases.items():
        old, new = results[(case, "old")], results[(case, "new")]
        keys = list(old["forces"])
        # relative to the largest force of the row: the SI pillar's are 1e-5
        # N/m, and a force that vanishes by symmetry is round-off in both
        scale = max((abs(old["forces"][k]) for k in keys), default=0.0)
        equal = all(abs(old["forces"][k] - new["forces"][k]) <= 1e-8 * scale for k in keys)
        wall = (min(old["wall"]), min(new["wall"]))
        feet = (min(old["feet"]), min(new["feet"]))
        print("| %s | %d | %.1f | %.1f | %.2f | %.1f | %.1f | %.2f | %s |"
              % (case, steps, wall[0], wall[1], wall[1] / wall[0], feet[0], feet[1],
                 feet[1] / feet[0] if feet[0] > 0 else float("nan"),
                 "yes" if equal and keys else "NO"))
    print()
    print("Sections [s], minimum over the runs:")
    print()
    print("| case | build | %s |" % " | ".join(SECTIONS))
    print("|---|---|%s" % ("---|" * len(SECTIONS)))
    for case in cases:
        for name in builds:
            entry = results[(case, name)]
            print("| %s | %s | %s |" % (case, name, " | ".join("%.1f" % min(entry[section])
                                                             for section in SECTIONS)))


if __name__ == "__main__":
    main()
