"""Shared helpers of the benchmark scripts: the viscofilm binary, MPI runs as
root, the machine and source description, and reading a run's CSV files."""

import csv
import os
import re
import subprocess
import sys
import time

SCRIPT_DIR = os.path.dirname(os.path.realpath(__file__))
REPO = os.path.dirname(SCRIPT_DIR)


def die(message):
    print("%s: ERROR: %s" % (os.path.basename(sys.argv[0]), message), file=sys.stderr)
    sys.exit(1)


def log(message):
    print("%s: %s" % (os.path.basename(sys.argv[0]), message), file=sys.stderr, flush=True)


def ensure_binary():
    """$VISCOFILM_BUILD (default build/) and its viscofilm, built if missing."""
    build = os.path.abspath(os.environ.get("VISCOFILM_BUILD", os.path.join(REPO, "build")))
    binary = os.path.join(build, "viscofilm")
    if not os.access(binary, os.X_OK):
        log("no %s; building it with scripts/setup.sh" % binary)
        env = dict(os.environ, VISCOFILM_BUILD=build)
        result = subprocess.run(["bash", os.path.join(REPO, "scripts", "setup.sh")], env=env)
        if result.returncode != 0 or not os.access(binary, os.X_OK):
            die("scripts/setup.sh did not produce %s" % binary)
    return build, binary


def mpi_environment():
    env = dict(os.environ)
    if os.geteuid() == 0:
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    return env


def machine_description():
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "nproc = %d, CPU: %s" % (os.cpu_count() or 0, model)


def source_of(build):
    """The source tree the binary was configured from (CMakeCache) and its commit."""
    source = REPO
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as cache:
            for line in cache:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    source = line.split("=", 1)[1].strip()
    except OSError:
        pass
    try:
        head = subprocess.run(["git", "-C", source, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", source, "status", "--porcelain", "--", "source",
                                "include", "CMakeLists.txt"],
                               capture_output=True, text=True).stdout.strip()
        head += " (source modified)" if dirty else ""
    except (OSError, subprocess.CalledProcessError):
        head = "unknown commit"
    return source, "%s at %s" % (head, source)


def run_case(binary, prm_text, directory, ranks, reuse=False, threads=None):
    """Run viscofilm on @p ranks ranks with prm_text (its Output/Directory must
    be @p directory) and return wall time [s], peak memory per rank [MiB] and
    the log. With reuse, a finished run in directory (run.log with the timer
    table) is read instead of run again ("cached": True). With threads,
    viscofilm --threads threads, and the ranks unbound (Open MPI binds each
    rank to one core by default when there are at most two) and yielding
    while they wait: unbound ranks that poll can share one core on a loaded
    machine (doc/performance-implementation.md, "Unbound ranks on a loaded machine")."""
    os.makedirs(directory, exist_ok=True)
    log_file = os.path.join(directory, "run.log")
    cached = reuse and os.path.exists(log_file) and "Total wallclock" in open(log_file).read()
    if not cached:
        prm = os.path.join(directory, "case.prm")
        with open(prm, "w") as f:
            f.write(prm_text)
        start = time.time()
        command = ["mpirun", "-np", str(ranks)]
        if threads is not None:
            command += ["--bind-to", "none", "--mca", "mpi_yield_when_idle", "1",
                        binary, "--threads", str(threads)]
        else:
            command += [binary]
        result = subprocess.run(command + [prm],
                                capture_output=True, text=True, env=mpi_environment())
        wall = time.time() - start
        with open(log_file, "w") as f:
            f.write(result.stdout + result.stderr + "\nbenchmark wall time: %.3f s\n" % wall)
        if result.returncode != 0:
            die("the run in %s failed:\n%s" % (directory, result.stderr[-2000:]))
    text = open(log_file).read()
    wall = float(re.search(r"benchmark wall time: ([0-9.]+) s", text).group(1))
    peak = re.search(r"Peak memory \(VmHWM\): ([0-9.]+) MiB on the largest rank", text)
    return {"wall": wall, "peak_mib": float(peak.group(1)) if peak else float("nan"),
            "log": text, "cached": cached}


def settings_text(settings):
    """Parameter-file text of "Section/Subsection/Entry=value" strings (as the
    scripts' --set takes them), each in its nested subsections."""
    text = ""
    for item in settings:
        path, separator, value = item.partition("=")
        *sections, entry = [part.strip() for part in path.split("/")]
        if not separator or not sections:
            die("--set needs SECTION/ENTRY=VALUE, got %r" % item)
        text += ("".join("subsection %s\n" % s for s in sections) +
                 "  set %s = %s\n" % (entry, value.strip()) + "end\n" * len(sections))
    return text


def timer_section(log_text, section):
    """Wall time [s] of a TimerOutput section in a run's log (0 if absent)."""
    match = re.search(r"^\| %s\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s" % re.escape(section),
                      log_text, re.MULTILINE)
    return float(match.group(1)) if match else 0.0


def read_csv(path):
    """Rows of a viscofilm CSV file as dicts of floats."""
    with open(path) as f:
        return [{key: float(value) for key, value in row.items()} for row in csv.DictReader(f)]


def probes_at(probes, time, fields):
    """Probe rows of probes.csv (one per probe, in order) at @p time, each of
    @p fields linear in time between the two steps around it."""
    times = sorted({row["time"] for row in probes})
    after = next(t for t in times if t >= time - 1e-12)
    before = max([t for t in times if t <= time + 1e-12])
    weight = 0 if after == before else (time - before) / (after - before)
    rows_before = [row for row in probes if row["time"] == before]
    rows_after = [row for row in probes if row["time"] == after]
    return [{f: (1 - weight) * a[f] + weight * b[f] for f in fields}
            for a, b in zip(rows_before, rows_after)]
