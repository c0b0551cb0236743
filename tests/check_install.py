#!/usr/bin/env python3
"""cmake --install into a fresh prefix, then use the installed tree from a
directory outside the repository and the build:

    check_install.py CMAKE BUILD_DIR SOURCE_DIR WORK_DIR

the installed program prints the build's --version line; every shipped
parameter file is installed, and the examples (which name meshes and images
relative to themselves, so the tree's layout must hold) and the default case
validate; and the installed
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
    cmake, build = sys.argv[1], pathlib.Path(sys.argv[2])
    source, work = pathlib.Path(sys.argv[3]), pathlib.Path(sys.argv[4])
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

    # Every file is there; the examples (meshes and images named relative to
    # themselves) and the default case, which includes another, validate.
    # (The validate_* tests check every file in the source tree.)
    installed_files = sorted(p.relative_to(share) for p in share.glob("prm/**/*.prm"))
    shipped = sorted(p.relative_to(source) for p in source.glob("prm/**/*.prm"))
    if installed_files != shipped:
        fail("installed parameter files %s differ from the shipped %s" % (installed_files, shipped))
    parameter_files = sorted(share.glob("prm/examples/*.prm")) + [share / "prm" / "default.prm"]
    for prm in parameter_files:
        run([str(program), "--validate", str(prm)], cwd=elsewhere)

    scripts = sorted((share / "postprocess").glob("*.py"))
    if not any(script.name == "plot_run.py" for script in scripts):
        fail("no postprocess/plot_run.py under %s" % share)
    for script in scripts:
        if script.read_text().startswith("#!") and not os.access(script, os.X_OK):
            fail("%s has a #! line but is not executable" % script)
    print("installed under %s: --version, %d parameter files (%d validated from %s), %d scripts"
          % (prefix, len(installed_files), len(parameter_files), elsewhere, len(scripts)))


main()
