#!/usr/bin/env python3
"""Run one viscofilm test case and compare what it produced with a reference.

Modes
  run          run FILE.prm; extract the --compare columns of the CSV files the
               run wrote and numdiff them against --reference.
  convergence  run FILE.prm once per value of --vary "Name=v1,v2,..." (several
               --vary are zipped; each halves the error scale, e.g. the mesh
               size or the time step); tabulate the errors in the last row of
               statistics.csv and the observed rates, check the rates against
               --min-rates, and numdiff the table.
  error        run FILE.prm (or the --args command line), expect a non-zero
               exit status, the message in --reference on stderr, and no
               output directory.
  restart      run FILE.prm (which sets Checkpointing/Interval) to its end, and
               again stopped after --stop-after steps and resumed from its
               checkpoint: the --compare columns of both must agree to
               --numdiff (the reference is the uninterrupted run).
  hdf5         run FILE.prm and list the datasets of every snapshot named in
               solution.xdmf (needs h5py), numdiff the listing.

In modes run and convergence, --bound "file.csv:column<value" (or >) must hold
in every row of the run(s), and "file.csv:max(column)<value" (or sum) for the
largest value or the sum over the rows: a check against a stated limit,
whatever the reference says. "file.csv[step>0]:..." checks only the rows
after the initial state.

Set VISCOFILM_BLESS=1 to write the reference instead of comparing (only after
checking the output against the analytic answer by hand).
Only the standard library is used, except h5py in mode hdf5.
"""
import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


def mpi_environment():
    env = dict(os.environ)
    if os.geteuid() == 0:  # Open MPI refuses root unless told
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    return env


def run_viscofilm(opts, args, workdir):
    command = [opts.mpiexec, "-np", str(opts.ranks)] + opts.mpiexec_flags.split()
    command += [opts.viscofilm] + args
    result = subprocess.run(command, cwd=workdir, env=mpi_environment(),
                            capture_output=True, text=True, timeout=opts.timeout)
    with open(os.path.join(workdir, "screen.log"), "w") as log:
        log.write(result.stdout + "\n--- stderr ---\n" + result.stderr)
    return result


def read_prm_setting(prm_text, name):
    match = re.search(r"^\s*set\s+" + re.escape(name) + r"\s*=\s*(.*?)\s*(#.*)?$",
                      prm_text, re.MULTILINE)
    return match.group(1) if match else None


def output_directory(workdir, prm):
    with open(prm) as f:
        directory = read_prm_setting(f.read(), "Directory")
    return os.path.join(workdir, directory or "output")


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def extract_columns(directory, specs):
    """'statistics.csv:step,time,max_velocity' -> the selected columns."""
    lines = []
    for spec in specs:
        filename, columns = spec.split(":")
        columns = columns.split(",")
        rows = read_csv(os.path.join(directory, filename))
        missing = [c for c in columns if rows and c not in rows[0]]
        if missing:
            fail("%s has no column(s) %s" % (filename, ", ".join(missing)))
        lines.append("# " + filename + ": " + ",".join(columns))
        lines += [",".join(row[c] for c in columns) for row in rows]
    return "\n".join(lines) + "\n"


def compare(opts, text, workdir):
    produced = os.path.join(workdir, "test.output")
    with open(produced, "w") as f:
        f.write(text)
    if os.environ.get("VISCOFILM_BLESS") == "1" and opts.mode != "restart":
        shutil.copy(produced, opts.reference)
        print("blessed " + opts.reference)
        return
    command = ["numdiff", "-q", "-s", " \t\n,;:=()"] + opts.numdiff.split()
    command += [opts.reference, produced]
    if subprocess.run(command).returncode != 0:
        subprocess.run(["numdiff", "-s", " \t\n,;:=()"] + opts.numdiff.split()
                       + [opts.reference, produced])
        fail("output differs from %s beyond %s" % (opts.reference, opts.numdiff))
    print("output matches %s (%s)" % (opts.reference, opts.numdiff))


def check_bounds(opts, directory):
    """Each bound holds at every row, or, for max(column) and sum(column), for
    the largest value or the sum over the rows."""
    for bound in opts.bound:
        match = re.fullmatch(r"([^[]+)(\[step>0\])?:(\w+|max\(\w+\)|sum\(\w+\))([<>])(.+)",
                             bound)
        if not match:
            fail("bad --bound " + bound)
        filename, after_start, column, relation, limit = match.groups()
        rows = read_csv(os.path.join(directory, filename))
        if after_start:
            rows = [row for row in rows if float(row["step"]) > 0]
        reduction = re.fullmatch(r"(max|sum)\((\w+)\)", column)
        if reduction:
            values = [float(row[reduction.group(2)]) for row in rows]
            value = max(values) if reduction.group(1) == "max" else sum(values)
            checks = [(value, "over all rows")]
        else:
            checks = [(float(row[column]), "at step " + row.get("step", "?")) for row in rows]
        for value, where in checks:
            if not (value < float(limit) if relation == "<" else value > float(limit)):
                fail("%s: %s = %s %s violates %s %s %s"
                     % (filename, column, value, where, column, relation, limit))
        print("bound holds: " + bound)


def mode_run(opts, workdir):
    prm = shutil.copy(opts.prm, workdir)
    result = run_viscofilm(opts, [os.path.basename(prm)], workdir)
    if result.returncode != 0:
        fail("viscofilm exited with %d:\n%s" % (result.returncode, result.stderr))
    directory = output_directory(workdir, prm)
    check_bounds(opts, directory)
    compare(opts, extract_columns(directory, opts.compare), workdir)


def mode_convergence(opts, workdir):
    with open(opts.prm) as f:
        template = f.read()
    varied = [(name, values.split(",")) for name, values in
              (item.split("=", 1) for item in opts.vary)]
    levels = list(zip(*[values for _, values in varied]))
    min_rates = dict(item.split("=") for item in opts.min_rates.split(","))
    errors = {name: [] for name in min_rates}
    for run, level in enumerate(levels):
        text = template
        for (name, _), value in zip(varied, level):
            pattern = r"(set\s+" + re.escape(name) + r"\s*=\s*)[^#\n]*"
            if not re.search(pattern, text):
                fail("%s does not set %s" % (opts.prm, name))
            text = re.sub(pattern, lambda m: m.group(1) + value, text)
        prm = os.path.join(workdir, "run-%d.prm" % run)
        with open(prm, "w") as f:
            f.write(text)
        result = run_viscofilm(opts, [os.path.basename(prm)], workdir)
        if result.returncode != 0:
            fail("viscofilm exited with %d for %s:\n%s"
                 % (result.returncode, ", ".join(level), result.stderr))
        check_bounds(opts, output_directory(workdir, prm))
        last = read_csv(os.path.join(output_directory(workdir, prm),
                                     "statistics.csv"))[-1]
        for name in errors:
            errors[name].append(float(last[name]))

    lines = [varied[0][0].replace(" ", "_") + "," +
             ",".join("%s,rate" % n for n in errors)]
    for i, level in enumerate(levels):
        row = [level[0]]
        for name, values in errors.items():
            rate = (math.log2(values[i - 1] / values[i]) if i > 0 else float("nan"))
            row += ["%.3e" % values[i], "%.2f" % rate if i > 0 else "-"]
            if i > 0 and rate < float(min_rates[name]):
                print("\n".join(lines + [",".join(row)]))
                fail("%s converges at rate %.2f between %s and %s, expected >= %s"
                     % (name, rate, levels[i - 1][0], level[0], min_rates[name]))
        lines.append(",".join(row))
    table = "\n".join(lines) + "\n"
    print(table)
    compare(opts, table, workdir)


def mode_error(opts, workdir):
    if opts.prm:
        shutil.copy(opts.prm, workdir)
        args = [os.path.basename(opts.prm)]
        directory = output_directory(workdir, opts.prm)
    else:
        args = opts.args.split()
        directory = None
    result = run_viscofilm(opts, args, workdir)
    if result.returncode == 0:
        fail("viscofilm accepted bad input (exit status 0)")
    if "Stacktrace" in result.stderr or "----" in result.stderr.split("\n")[0]:
        fail("the error message carries a backtrace:\n" + result.stderr)
    if directory and os.path.exists(directory):
        fail("an output directory was written for bad input: " + directory)
    # Open MPI adds its own banner (a line of dashes) after our message.
    ours = []
    for line in result.stderr.splitlines():
        if line.startswith("-----"):
            break
        ours.append(line)
    compare(opts, "exit status %d\n" % min(result.returncode, 2) + "\n".join(ours)
            + "\n", workdir)


def mode_restart(opts, workdir):
    with open(opts.prm) as f:
        base = f.read()
    steps = read_prm_setting(base, "Number of steps")

    def run(name, directory, n_steps, resume):
        with open(os.path.join(workdir, name + ".prm"), "w") as f:
            f.write(base + "\nsubsection Output\n  set Directory = %s\nend\n"
                    "subsection Time stepping\n  set Number of steps = %s\nend\n"
                    "subsection Checkpointing\n  set Resume = %s\nend\n"
                    % (directory, n_steps, resume))
        result = run_viscofilm(opts, [name + ".prm"], workdir)
        if result.returncode != 0:
            fail("viscofilm exited with %d in the %s run:\n%s"
                 % (result.returncode, name, result.stderr))

    run("uninterrupted", "full", steps, "false")
    run("stopped", "part", opts.stop_after, "false")
    run("resumed", "part", steps, "true")
    opts.reference = os.path.join(workdir, "uninterrupted.output")
    with open(opts.reference, "w") as f:
        f.write(extract_columns(os.path.join(workdir, "full"), opts.compare))
    compare(opts, extract_columns(os.path.join(workdir, "part"), opts.compare),
            workdir)


def mode_hdf5(opts, workdir):
    import h5py  # Debian's python3-h5py

    prm = shutil.copy(opts.prm, workdir)
    result = run_viscofilm(opts, [os.path.basename(prm)], workdir)
    if result.returncode != 0:
        fail("viscofilm exited with %d:\n%s" % (result.returncode, result.stderr))
    directory = output_directory(workdir, prm)
    with open(os.path.join(directory, "solution.xdmf")) as f:
        files = sorted(set(re.findall(r"(solution-\d+\.h5):", f.read())))
    if not files:
        fail("solution.xdmf names no HDF5 file")
    lines = []
    for name in files:
        with h5py.File(os.path.join(directory, name), "r") as h5:
            for key in sorted(h5.keys()):
                data = h5[key][()]
                lines.append("%s %s shape %s max|.| %.6e" % (
                    name, key, "x".join(map(str, data.shape)), abs(data).max()))
    compare(opts, "\n".join(lines) + "\n", workdir)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mode", required=True,
                        choices=["run", "convergence", "error", "restart", "hdf5"])
    parser.add_argument("--viscofilm", required=True)
    parser.add_argument("--mpiexec", default="mpirun")
    parser.add_argument("--mpiexec-flags", default="")
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("--workdir", required=True)
    parser.add_argument("--prm")
    parser.add_argument("--args", default="")
    parser.add_argument("--reference", required=True)
    parser.add_argument("--compare", action="append", default=[])
    parser.add_argument("--numdiff", default="-a 0 -r 0")
    parser.add_argument("--vary", action="append", default=[])
    parser.add_argument("--bound", action="append", default=[])
    parser.add_argument("--min-rates", default="")
    parser.add_argument("--timeout", type=float, default=600)
    parser.add_argument("--stop-after", default="4")
    opts = parser.parse_args()

    shutil.rmtree(opts.workdir, ignore_errors=True)
    os.makedirs(opts.workdir)
    {"run": mode_run, "convergence": mode_convergence, "error": mode_error,
     "restart": mode_restart, "hdf5": mode_hdf5}[opts.mode](opts, opts.workdir)
    print("PASSED")


if __name__ == "__main__":
    main()
