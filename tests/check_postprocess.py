#!/usr/bin/env python3
"""Run a small bulb case, draw its figures with postprocess/plot_run.py and
check them: the figures exist (also plot_pillar.py's close-up and outlines over
time, selected by time, and plot_growth.py's of the bulb growing on a
substrate), and the peak speed the script reads from the
HDF5 snapshot equals max_velocity that the simulator wrote to statistics.csv
(both at the Q2 nodes), to the 7 digits it prints.
usage: check_postprocess.py VISCOFILM SOURCE_DIR WORKDIR"""
import csv
import glob
import os
import re
import shutil
import subprocess
import sys

viscofilm, source, workdir = sys.argv[1:4]
shutil.rmtree(workdir, ignore_errors=True)
os.makedirs(workdir)
with open(os.path.join(workdir, "small.prm"), "w") as f:
    f.write("include %s/prm/thesis.prm\n"
            "subsection Geometry\n  set Initial global refinement = 3\nend\n"
            "subsection Time stepping\n  set Number of steps = 3\nend\n"
            "subsection Output\n  set Directory = run\n  set Interval = 1\nend\n" % source)
subprocess.run([viscofilm, "small.prm"], cwd=workdir, check=True,
               stdout=subprocess.DEVNULL)
plot = subprocess.run(["/usr/bin/python3", os.path.join(source, "postprocess", "plot_run.py"),
                       "run", "--step", "3"], cwd=workdir, capture_output=True, text=True)
print(plot.stdout[-2000:], plot.stderr)
if plot.returncode != 0:
    print("FAILED: plot_run.py exited with %d" % plot.returncode)
    sys.exit(1)
figures = glob.glob(os.path.join(workdir, "run", "figures", "*.png"))
match = re.search(r"max\|u\|\s*=\s*(\S+)", plot.stdout)
rows = list(csv.DictReader(open(os.path.join(workdir, "run", "statistics.csv"))))
expected = float([r for r in rows if r["step"] == "3"][0]["max_velocity"])
if len(figures) < 10 or not match:
    print("FAILED: %d figures, summary %s" % (len(figures), "found" if match else "missing"))
    sys.exit(1)
if abs(float(match.group(1)) - expected) > 1e-6 * expected:
    print("FAILED: plot_run.py reads max|u| = %s, statistics.csv has %r"
          % (match.group(1), expected))
    sys.exit(1)
pillar = subprocess.run(["/usr/bin/python3", os.path.join(source, "postprocess", "plot_pillar.py"),
                         "run", "--centre", "0.5,0.2", "--half-width", "0.3", "--times", "0,0.006",
                         "--out", "close_up.png", "--shapes", "shapes.png"],
                        cwd=workdir, capture_output=True, text=True)
print(pillar.stdout, pillar.stderr)
missing = [f for f in ("close_up.png", "shapes.png") if not os.path.isfile(os.path.join(workdir, f))]
if pillar.returncode != 0 or missing:
    print("FAILED: plot_pillar.py exited with %d, missing %s" % (pillar.returncode, missing))
    sys.exit(1)
with open(os.path.join(workdir, "grow.prm"), "w") as f:
    f.write("include small.prm\n"
            "subsection Output\n  set Directory = grow\nend\n"
            "subsection Substrate\n  set Enable = true\n  set Maximum growth rate = 1\n"
            "  set Half saturation = 0.5\n  set Biomass density = 1\n  set Initial value = 1\n"
            "  set Fixed values = Inlet: 1\nend\n"
            "subsection Growth\n  set Enable = true\n  set Maximum volume fraction = 0.1\nend\n")
subprocess.run([viscofilm, "grow.prm"], cwd=workdir, check=True, stdout=subprocess.DEVNULL)
growth = subprocess.run(["/usr/bin/python3", os.path.join(source, "postprocess", "plot_growth.py"),
                         "grow"], cwd=workdir, capture_output=True, text=True)
print(growth.stdout, growth.stderr)
missing = [f for f in ("growth_outlines.png", "growth_statistics.png")
           if not os.path.isfile(os.path.join(workdir, "grow", "figures", f))]
if growth.returncode != 0 or missing:
    print("FAILED: plot_growth.py exited with %d, missing %s" % (growth.returncode, missing))
    sys.exit(1)
print("PASSED: %d figures; max|u| = %s as in statistics.csv" % (len(figures), match.group(1)))
