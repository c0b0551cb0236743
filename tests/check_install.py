#!/usr/bin/env python3
"""cmake --install into a fresh prefix, then use the installed tree from a
directory outside the repository and the build:

    check_install.py CMAKE BUILD_DIR WORK_DIR

the installed program prints the build's --version line, validates every
installed parameter file (the examples name meshes and images relative to
themselves, so the tree's layout must hold), and the installed
post-processing scripts are there, those with a #! line executable. Prints FAILED and exits 1
on the first failure.
"""
import os
import pathlib
import shutil
import subprocess
import sys


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


def run(command, cwd):
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if result.returncode != 0:
        fail("%s exited with %d:\n%s%s" % (" ".join(map(str, command)), result.returncode,
                                          result.stdout, result.stderr))
    return result.stdout


def main():
    cmake, build, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    prefix, elsewhere = work / "prefix", work / "elsewhere"
    elsewhere.mkdir(parents=True)
    run([cmake, "--install", str(build), "--prefix", str(prefix)], cwd=work)

    program = prefix / "bin" / "viscofilm"
    share = prefix / "share" / "viscofilm"
    if not os.access(program, os.X_OK):
        fail("%s is not an executable" % program)
    installed = run([str(program), "--version"], cwd=elsewhere)
    built = run([str(build / "viscofilm"), "--version"], cwd=elsewhere)
    if installed != built:
        fail("the installed --version %r differs from the build's %r" % (installed, built))

    parameter_files = sorted(share.glob("prm/**/*.prm"))
    if len(parameter_files) < 10:
        fail("only %d parameter files under %s" % (len(parameter_files), share / "prm"))
    for prm in parameter_files:
        run([str(program), "--validate", str(prm)], cwd=elsewhere)

    scripts = sorted((share / "postprocess").glob("*.py"))
    if not any(script.name == "plot_run.py" for script in scripts):
        fail("no postprocess/plot_run.py under %s" % share)
    for script in scripts:
        if script.read_text().startswith("#!") and not os.access(script, os.X_OK):
            fail("%s has a #! line but is not executable" % script)
    print("installed under %s: --version, %d parameter files valid from %s, %d scripts"
          % (prefix, len(parameter_files), elsewhere, len(scripts)))


main()
