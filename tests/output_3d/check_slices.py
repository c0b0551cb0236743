#!/usr/bin/env python3
"""Run tests/output_3d/stress_fields_3d.prm (the initial stress
τ = (x, y, z, 1 + x, 2 + y, 3 + z) on the unit cube, written at step 0) and
cut its snapshot with postprocess/plot_slices.py: on the plane z = 0.6 (inside
cells) tau_xz must be 0.6 and tau_zz 3.6 everywhere, tau_xx run from 0 to 1;
on y = 0.5 (a mesh plane) tau_xy = 0.5 and tau_yz = 2.5; to the single
precision of the snapshot (1e-6). The figures must exist.
usage: check_slices.py VISCOFILM SOURCE_DIR WORKDIR"""
import glob
import os
import re
import shutil
import subprocess
import sys

viscofilm, source, workdir = sys.argv[1:4]
shutil.rmtree(workdir, ignore_errors=True)
os.makedirs(workdir)
shutil.copy(os.path.join(source, "tests", "output_3d", "stress_fields_3d.prm"), workdir)
subprocess.run([viscofilm, "stress_fields_3d.prm"], cwd=workdir, check=True,
               stdout=subprocess.DEVNULL)
plot = subprocess.run(["/usr/bin/python3",
                       os.path.join(source, "postprocess", "plot_slices.py"), "output",
                       "--plane", "z=0.6", "--plane", "y=0.5",
                       "--fields", "tau_xx,tau_xy,tau_xz,tau_yz,tau_zz,speed"],
                      cwd=workdir, capture_output=True, text=True)
print(plot.stdout, plot.stderr)
if plot.returncode != 0:
    sys.exit("FAILED: plot_slices.py exited with %d" % plot.returncode)
ranges = {(axis, float(value), name): (float(low), float(high)) for axis, value, name, low, high
          in re.findall(r"(\w) = (\S+): (\w+) from (\S+) to (\S+)", plot.stdout)}
expected = {("z", 0.6, "tau_xz"): (0.6, 0.6), ("z", 0.6, "tau_zz"): (3.6, 3.6),
            ("z", 0.6, "tau_xx"): (0, 1), ("z", 0.6, "speed"): (0, 0),
            ("y", 0.5, "tau_xy"): (0.5, 0.5), ("y", 0.5, "tau_yz"): (2.5, 2.5),
            ("y", 0.5, "tau_xx"): (0, 1)}
failed = False
for key, (low, high) in expected.items():
    got = ranges.get(key)
    ok = got is not None and abs(got[0] - low) < 1e-6 and abs(got[1] - high) < 1e-6
    print("%s %s = %g: %s from %s (expected %g to %g)"
          % ("ok    " if ok else "FAILED", key[0], key[1], key[2], got, low, high))
    failed = failed or not ok
figures = glob.glob(os.path.join(workdir, "output", "figures", "slice-*.png"))
if len(figures) != 12:
    print("FAILED: %d figures, expected 12" % len(figures))
    failed = True
sys.exit(1 if failed else 0)
