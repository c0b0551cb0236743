#!/usr/bin/env python3
"""Run one viscofilm test case and compare what it produced with a reference.

Modes
  run          run FILE.prm; extract the --compare columns of the CSV files the
               run wrote and numdiff them against --reference.
  convergence  run FILE.prm once per value of --vary "Name=v1,v2,..." (several
               --vary are zipped; each halves the error scale, e.g. the mesh
               size or the time step); tabulate the errors in the last row of
               statistics.csv and the observed rates, check the rates against
               --min-rates, and numdiff the table. A --min-rates name
               "file.csv:col1+col2" is those columns in the rows of the
               run's last step (every probe). --differences: no closed
               form; the error of run i is the largest difference between
               runs i and i+1 (Richardson: its rate is the scheme's order).
  error        run FILE.prm (after the --args options, or the --args command
               line alone), expect a non-zero
               exit status, the message in --reference on stderr, and no
               output directory; with --valid-steps N, a run stopped in step
               N + 1: its statistics.csv must hold steps 0 … N, whole.
  restart      run FILE.prm (which sets Checkpointing/Interval) to its end, and
               again stopped after --stop-after steps and resumed from its
               checkpoint: the --compare columns of both must agree to
               --numdiff (the reference is the uninterrupted run). The
               resumed run sets each --resume-set "Subsection/Name=value"
               (entries that may change on resume). --interrupt-commit: leave
               the checkpoint as a kill between the two renames of a commit
               would (checkpoint.old whole, no checkpoint/, a checkpoint.new).
  refused      run FILE.prm stopped after --stop-after steps, then resume it
               once with each --resume-set changed: each resume must fail with
               a non-zero exit status, leave statistics.csv as it was, and
               print the messages in --reference (one per --resume-set).
  hdf5         run FILE.prm and list the datasets of every snapshot named in
               solution.xdmf (needs h5py), numdiff the listing.
  fields       run FILE.prm and check the node values of the last snapshot
               against --exact "dataset=expression in x, y (, z)" (dataset[i] for a
               component; a Python expression) to --tolerance: at every corner
               of every cell the value must be the limit of the expression
               from inside that cell, so a field that jumps between cells must
               be written with both one-sided values (needs h5py).

In modes run and convergence, --bound "file.csv:column<value" (or >) must hold
in every row of the run(s), and "file.csv:max(column)<value" (or sum) for the
largest value or the sum over the rows: a check against a stated limit,
whatever the reference says. "file.csv[step>N]:..." checks only the rows
after step N ([step>0]: after the initial state); any column and < work
alike ("statistics.csv[time<0.1]:time_step<0.01"). A bound that selects no
row fails (in mode convergence: no row of any run). "file.csv:a+b-c<value"
bounds the sum of columns a and b minus column c in each row (a balance).

--data FILE (repeatable) copies FILE into the work directory before the run:
the images a .prm names relative to itself.

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
    # After a rank's non-zero exit (every bad-input test) Open MPI's mpirun
    # waits 2 s to kill ranks that have already ended; the suite has over a
    # hundred such runs.
    env.setdefault("OMPI_MCA_odls_base_sigkill_timeout", "0")
    return env


def run_viscofilm(opts, args, workdir):
    flags = opts.mpiexec_flags.split()
    # Open MPI binds a single rank to the first core: two 1-rank tests run
    # side by side by ctest -j2 would share it and leave the other idle.
    if opts.ranks == 1 and "--bind-to" not in flags:
        flags += ["--bind-to", "none"]
    command = [opts.mpiexec, "-np", str(opts.ranks)] + flags
    command += [opts.viscofilm] + args
    result = subprocess.run(command, cwd=workdir, env=mpi_environment(),
                            capture_output=True, text=True, timeout=opts.timeout)
    with open(os.path.join(workdir, "screen.log"), "w") as log:
        log.write(result.stdout + "\n--- stderr ---\n" + result.stderr)
    return result


def read_prm_setting(prm_text, name):
    """The value of the last "set name = ..." (the one ParameterHandler keeps)."""
    matches = re.findall(r"^\s*set\s+" + re.escape(name) + r"\s*=\s*(.*?)\s*(?:#.*)?$",
                         prm_text, re.MULTILINE)
    return matches[-1] if matches else None


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


def check_bounds(opts, directory, selected=None):
    """Each bound holds at every row, or, for max(column) and sum(column), for
    the largest value or the sum over the rows. A bound whose row filter
    selects no row fails, unless @p selected (a set) collects the bounds that
    selected rows, for the caller to check over several runs."""
    for bound in opts.bound:
        match = re.fullmatch(r"([^[]+)(?:\[(\w+)([<>])([^]]+)\])?:"
                             r"(\w+(?:[+-]\w+)*|max\(\w+\)|sum\(\w+\))([<>])(.+)", bound)
        if not match:
            fail("bad --bound " + bound)
        filename, row_column, row_relation, row_limit, column, relation, limit = match.groups()
        rows = read_csv(os.path.join(directory, filename))
        if row_column:
            rows = [row for row in rows
                    if (float(row[row_column]) > float(row_limit) if row_relation == ">"
                        else float(row[row_column]) < float(row_limit))]
        if not rows:
            if selected is None:
                fail("%s: the bound %s selects no row (a check of nothing)" % (filename, bound))
            continue
        if selected is not None:
            selected.add(bound)
        reduction = re.fullmatch(r"(max|sum)\((\w+)\)", column)
        if reduction:
            values = [float(row[reduction.group(2)]) for row in rows]
            value = max(values) if reduction.group(1) == "max" else sum(values)
            checks = [(value, "over all rows")]
        else:
            terms = re.findall(r"([+-]?)(\w+)", column)
            checks = [(sum((-1 if sign == "-" else 1) * float(row[c]) for sign, c in terms),
                       "at step " + row.get("step", "?")) for row in rows]
        for value, where in checks:
            if not (value < float(limit) if relation == "<" else value > float(limit)):
                fail("%s: %s = %s %s violates %s %s %s"
                     % (filename, column, value, where, column, relation, limit))
        print("bound holds: " + bound)


def run_case(opts, workdir):
    """Run --prm in workdir; returns the output directory."""
    prm = shutil.copy(opts.prm, workdir)
    result = run_viscofilm(opts, [os.path.basename(prm)], workdir)
    if result.returncode != 0:
        fail("viscofilm exited with %d:\n%s" % (result.returncode, result.stderr))
    return output_directory(workdir, prm)


def snapshot_files(directory):
    """The HDF5 files solution.xdmf names, in the order it names them."""
    with open(os.path.join(directory, "solution.xdmf")) as f:
        files = list(dict.fromkeys(re.findall(r"(solution-\d+\.h5):", f.read())))
    if not files:
        fail("solution.xdmf names no HDF5 file")
    return files


def mode_run(opts, workdir):
    directory = run_case(opts, workdir)
    check_bounds(opts, directory)
    compare(opts, extract_columns(directory, opts.compare), workdir)


def observed_values(directory, name):
    """What a --min-rates name observes in one run's output, a list.
    "file.csv:col1+col2": those columns in every row of the last step;
    "column@value": |column − value| in statistics.csv's last row (the
    error against a published value); "column": that column there."""
    if ":" in name:
        filename, columns = name.split(":")
        rows = read_csv(os.path.join(directory, filename))
        last_step = max(int(row["step"]) for row in rows)
        return [float(row[c]) for row in rows if int(row["step"]) == last_step
                for c in columns.split("+")]
    column, _, reference = name.partition("@")
    value = float(read_csv(os.path.join(directory, "statistics.csv"))[-1][column])
    return [abs(value - float(reference)) if reference else value]


def mode_convergence(opts, workdir):
    with open(opts.prm) as f:
        template = f.read()
    varied = [(name, values.split(",")) for name, values in
              (item.split("=", 1) for item in opts.vary)]
    levels = list(zip(*[values for _, values in varied]))
    min_rates = dict(item.split("=") for item in opts.min_rates.split(","))
    errors = {name: [] for name in min_rates}
    selected = set()  # the bounds that selected rows in some run
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
        directory = output_directory(workdir, prm)
        check_bounds(opts, directory, selected)
        for name in errors:
            errors[name].append(observed_values(directory, name))
    for bound in opts.bound:
        if bound not in selected:
            fail("the bound %s selects no row in any run (a check of nothing)" % bound)
    for name, values in errors.items():
        if opts.differences:
            errors[name] = [max(abs(a - b) for a, b in zip(values[i], values[i + 1]))
                            for i in range(len(values) - 1)]
        else:
            errors[name] = [value[0] for value in values]
    if opts.differences:
        levels = levels[:-1]  # a difference belongs to the coarser run of its pair

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
        args = opts.args.split() + [os.path.basename(opts.prm)]
        directory = output_directory(workdir, opts.prm)
    else:
        args = opts.args.split()
        directory = None
    result = run_viscofilm(opts, args, workdir)
    if result.returncode == 0:
        fail("viscofilm accepted bad input (exit status 0)")
    if "Stacktrace" in result.stderr or "----" in result.stderr.split("\n")[0]:
        fail("the error message carries a backtrace:\n" + result.stderr)
    if opts.valid_steps is None:
        if directory and os.path.exists(directory):
            fail("an output directory was written for bad input: " + directory)
    else:
        # What the stopped run wrote before the failing step: every row whole.
        rows = read_csv(os.path.join(directory, "statistics.csv"))
        steps = [row["step"] for row in rows]
        if steps != [str(i) for i in range(opts.valid_steps + 1)] or \
           any(None in row.values() or None in row for row in rows):
            fail("statistics.csv holds steps %s, not 0 ... %d, whole"
                 % (",".join(steps), opts.valid_steps))
    # Open MPI adds its own banner (a line of dashes) after our message.
    ours = []
    for line in result.stderr.splitlines():
        if line.startswith("-----"):
            break
        ours.append(line)
    compare(opts, "exit status %d\n" % min(result.returncode, 2) + "\n".join(ours)
            + "\n", workdir)


def prm_setting(setting):
    """'Subsection/Name=value' -> the parameter file lines that set it."""
    path, value = setting.split("=", 1)
    *subsections, name = path.split("/")
    return ("".join("subsection %s\n" % s for s in subsections)
            + "set %s = %s\n" % (name, value) + "end\n" * len(subsections))


def checkpointed_run(opts, workdir, base):
    """run(name, directory, n_steps, resume, settings=[]) runs base with
    those settings; it returns the result and fails unless expect_failure."""
    def run(name, directory, n_steps, resume, settings=(), expect_failure=False):
        with open(os.path.join(workdir, name + ".prm"), "w") as f:
            f.write(base + "\nsubsection Output\n  set Directory = %s\nend\n"
                    "subsection Time stepping\n  set Number of steps = %s\nend\n"
                    "subsection Checkpointing\n  set Resume = %s\nend\n"
                    % (directory, n_steps, resume)
                    + "".join(prm_setting(s) for s in settings))
        result = run_viscofilm(opts, [name + ".prm"], workdir)
        if result.returncode != 0 and not expect_failure:
            fail("viscofilm exited with %d in the %s run:\n%s"
                 % (result.returncode, name, result.stderr))
        return result
    return run


def mode_restart(opts, workdir):
    with open(opts.prm) as f:
        base = f.read()
    steps = read_prm_setting(base, "Number of steps")
    run = checkpointed_run(opts, workdir, base)
    run("uninterrupted", "full", steps, "false")
    run("stopped", "part", opts.stop_after, "false")
    if opts.interrupt_commit:
        checkpoint = os.path.join(workdir, "part", "checkpoint")
        shutil.copytree(checkpoint, checkpoint + ".new")
        os.rename(checkpoint, checkpoint + ".old")
    run("resumed", "part", steps, "true", opts.resume_set)
    opts.reference = os.path.join(workdir, "uninterrupted.output")
    with open(opts.reference, "w") as f:
        f.write(extract_columns(os.path.join(workdir, "full"), opts.compare))
    compare(opts, extract_columns(os.path.join(workdir, "part"), opts.compare),
            workdir)


def mode_refused(opts, workdir):
    with open(opts.prm) as f:
        base = f.read()
    run = checkpointed_run(opts, workdir, base)
    run("stopped", "part", opts.stop_after, "false")
    statistics = os.path.join(workdir, "part", "statistics.csv")
    with open(statistics) as f:
        before = f.read()
    messages = []
    for setting in opts.resume_set:
        result = run("resumed", "part", opts.stop_after, "true", [setting],
                     expect_failure=True)
        if result.returncode == 0:
            fail("resumed with %s changed" % setting)
        with open(statistics) as f:
            if f.read() != before:
                fail("the refused resume with %s changed statistics.csv" % setting)
        messages.append(result.stderr.splitlines()[0])
    compare(opts, "\n".join(messages) + "\n", workdir)


def mode_hdf5(opts, workdir):
    import h5py  # Debian's python3-h5py

    directory = run_case(opts, workdir)
    lines = []
    for name in sorted(snapshot_files(directory)):
        with h5py.File(os.path.join(directory, name), "r") as h5:
            for key in sorted(h5.keys()):
                data = h5[key][()]
                lines.append("%s %s shape %s max|.| %.6e" % (
                    name, key, "x".join(map(str, data.shape)), abs(data).max()))
    compare(opts, "\n".join(lines) + "\n", workdir)


def mode_fields(opts, workdir):
    import h5py  # Debian's python3-h5py (and so numpy)
    import numpy as np

    directory = run_case(opts, workdir)
    last = snapshot_files(directory)[-1]
    with h5py.File(os.path.join(directory, last), "r") as h5:
        nodes, cells = h5["nodes"][()], h5["cells"][()].astype(int)
        datasets = {name: h5[name][()] for name in h5.keys()}
    # Each cell's corners, moved 1e-9 of the way to its centre: the exact
    # field there is its limit from inside that cell.
    corners = nodes[cells]
    inside = corners + 1e-9 * (corners.mean(axis=1, keepdims=True) - corners)
    for spec in opts.exact:
        name, expression = spec.split("=", 1)
        match = re.fullmatch(r"(\w+)(?:\[(\d)\])?", name.strip())
        values = datasets[match.group(1)].reshape(len(nodes), -1)
        values = values[:, int(match.group(2) or 0)][cells]
        exact = np.vectorize(lambda *xyz: eval(expression, dict(vars(math)),
                                               dict(zip("xyz", xyz))),
                             otypes=[float])(*np.moveaxis(inside, -1, 0))
        error = np.abs(values - exact)
        worst = np.unravel_index(np.argmax(error), error.shape)
        point = lambda p: "(" + ", ".join("%g" % c for c in p) + ")"
        if error[worst] > opts.tolerance:
            fail("%s: %s = %.10g at the corner %s of the cell around %s, "
                 "exact %.10g" % (last, name, values[worst], point(corners[worst]),
                                  point(corners[worst[0]].mean(axis=0)), exact[worst]))
        print("%s: %s equals %s at every cell's corners to %.1e (tolerance %g)"
              % (last, name, expression, error.max(), opts.tolerance))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mode", required=True,
                        choices=["run", "convergence", "error", "restart", "refused",
                                 "hdf5", "fields"])
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
    parser.add_argument("--differences", action="store_true")
    parser.add_argument("--timeout", type=float, default=600)
    parser.add_argument("--stop-after", default="4")
    parser.add_argument("--valid-steps", type=int)
    parser.add_argument("--interrupt-commit", action="store_true")
    parser.add_argument("--resume-set", action="append", default=[])
    parser.add_argument("--exact", action="append", default=[])
    parser.add_argument("--tolerance", type=float, default=0)
    parser.add_argument("--data", action="append", default=[])
    opts = parser.parse_args()

    shutil.rmtree(opts.workdir, ignore_errors=True)
    os.makedirs(opts.workdir)
    for data in opts.data:  # files the .prm names relative to itself
        shutil.copy(data, opts.workdir)
    {"run": mode_run, "convergence": mode_convergence, "error": mode_error,
     "restart": mode_restart, "refused": mode_refused, "hdf5": mode_hdf5,
     "fields": mode_fields}[opts.mode](opts, opts.workdir)
    print("PASSED")


if __name__ == "__main__":
    main()
