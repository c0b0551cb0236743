#!/usr/bin/python3
"""tests/fuzz_parameters.py -- every parameter set, one at a time, to each of a
few bad values on a small run of prm/default.prm: what the program does with
each (not part of ctest: about 1100 runs, 5-10 minutes on 2 cores).

Usage:  tests/fuzz_parameters.py [--viscofilm build/viscofilm] [--jobs 2]
            [--values "-1,0,1e308,nan,abc,,1e-300,3.5"] [--keep DIR]

Each run (1 rank, Δx = 1/8, 2 steps, no snapshots, 120 s at most) is one of:
  clear     a non-zero exit status with a "viscofilm: ..." message;
  accepted  exit status 0 (a valid value, or a parameter this case ignores);
  suspect   exit status 0 with nan or inf on the terminal (but for the
            model's derived numbers, which only report);
  raw       a backtrace, an uncaught exception or a signal;
  timeout   still running after 120 s (a hang);
  other     a non-zero exit status without our message.
Prints the counts and every run that is not clear or accepted; exits 1 if
there is any. Found so far: CFL number = 1e-300 looped forever (now
tests/step_control/cfl_too_small.prm), Model/Length scale = 0 was accepted.
"""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
BASE = """include {repo}/prm/default.prm
subsection Geometry
  set Initial global refinement = 3
end
subsection Time stepping
  set Number of steps = 2
end
subsection Output
  set Interval = 0
end
"""


def entries(viscofilm):
    """(subsections, name, default) of every parameter, from --print-parameters."""
    text = subprocess.run([viscofilm, "--print-parameters"], capture_output=True,
                          text=True, check=True).stdout
    path, found = [], []
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("subsection "):
            path.append(line[len("subsection "):])
        elif line == "end":
            path.pop()
        elif line.startswith("set "):
            name, default = re.match(r"set (.+?)\s*=\s*(.*)$", line).groups()
            found.append((list(path), name, default))
    return found


def run(viscofilm, directory, path, name, value):
    os.makedirs(directory)
    with open(os.path.join(directory, "case.prm"), "w") as f:
        f.write(BASE.format(repo=REPO) + "".join("subsection %s\n" % s for s in path)
                + "  set %s = %s\n" % (name, value) + "end\n" * len(path))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_odls_base_sigkill_timeout="0")
    what = "%s = %r" % ("/".join(path + [name]), value)
    try:
        result = subprocess.run(["mpirun", "-np", "1", "--bind-to", "none", viscofilm,
                                 "case.prm"], cwd=directory, env=env,
                                capture_output=True, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        return "timeout", what, ""
    ours = [l for l in result.stderr.splitlines() if l.startswith("viscofilm")]
    if re.search(r"Stacktrace|terminate called|An error occurred in line|Segmentation|"
                 r"signal \d|core dumped|Exception on processing", result.stderr + result.stdout):
        return "raw", what, result.stderr[:300]
    if result.returncode == 0:
        # The model's "derived" line only reports: U = 1e308 gives Wi = inf.
        shown = [l for l in result.stdout.splitlines() if not l.startswith("  derived")]
        if re.search(r"\bnan\b|\binf\b", "\n".join(shown), re.IGNORECASE):
            return "suspect", what, ""
        return "accepted", what, ""
    return ("clear", what, ours[0]) if ours else ("other", what, result.stderr[:300])


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--viscofilm", default=os.path.join(REPO, "build", "viscofilm"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--values", default="-1,0,1e308,nan,abc,,1e-300,3.5")
    parser.add_argument("--keep", help="run in DIR and keep it (default: a temporary one)")
    arguments = parser.parse_args()
    if not os.access(arguments.viscofilm, os.X_OK):
        sys.exit("fuzz_parameters.py: no program %s (build it: bash scripts/setup.sh)"
                 % arguments.viscofilm)
    values = arguments.values.split(",")
    workdir = arguments.keep or tempfile.mkdtemp(prefix="viscofilm-fuzz-")
    cases = [(path, name, value) for path, name, default in entries(arguments.viscofilm)
             for value in values if value != default]
    counts, findings = {}, []
    with concurrent.futures.ThreadPoolExecutor(arguments.jobs) as pool:
        futures = [pool.submit(run, arguments.viscofilm, os.path.join(workdir, "%04d" % i),
                               *case) for i, case in enumerate(cases)]
        for future in futures:
            kind, what, message = future.result()
            counts[kind] = counts.get(kind, 0) + 1
            if kind not in ("clear", "accepted"):
                findings.append("%s: %s %s" % (kind, what, message))
    print("%d runs: %s" % (len(cases), ", ".join("%s %d" % item for item in sorted(counts.items()))))
    for finding in findings:
        print(finding)
    if not arguments.keep:
        subprocess.run(["rm", "-rf", workdir])
    sys.exit(1 if findings else 0)


if __name__ == "__main__":
    main()
