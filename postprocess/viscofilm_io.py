"""Read a viscofilm run directory: solution.xdmf + solution-NNNNN.h5 snapshots,
statistics.csv and probes.csv.

    run = Run("output-thesis")
    snap = run.load(run.nearest_snapshot(step=100))
    snap.fields["u"], snap.triangulation, snap.step, snap.time
    stats = run.statistics()          # {"time": array, "max_velocity": array, ...}

Importing this module also checks for numpy, h5py and matplotlib (Agg backend)
and exits with a clear message if they are missing.
"""

import argparse
import csv
import os
import re
import sys
import xml.etree.ElementTree as ET

try:
    import numpy as np
    import h5py
    import matplotlib
except ImportError as error:
    sys.exit(f"error: {error}.\nThe viscofilm postprocessing scripts need numpy, h5py and "
             f"matplotlib: run them with /usr/bin/python3, or install them with\n"
             f"  apt-get install python3-numpy python3-h5py python3-matplotlib\n"
             f"(this interpreter is {sys.executable}).")

matplotlib.use("Agg")
import matplotlib.tri as mtri  # noqa: E402

# Fields that are drawn first, in this order; other scalar fields follow sorted.
PREFERRED_ORDER = ["u", "v", "pressure", "volume_fraction", "divergence",
                   "vorticity", "inertia"]
ALIASES = {"p": "pressure", "phi": "volume_fraction", "div": "divergence"}
BIOFILM_LEVEL = 0.05  # φ contour drawn as the biofilm outline


class UserError(Exception):
    """A problem with the user's input: reported without a traceback."""


def main_guard(main):
    """Run main(), turning UserError (and Ctrl-C) into a message and exit status 1."""
    try:
        main()
    except UserError as error:
        sys.exit(f"error: {error}")
    except KeyboardInterrupt:
        sys.exit(1)


class ArgumentParser(argparse.ArgumentParser):
    """argparse, but exiting with status 1 on bad command lines like other user errors."""

    def error(self, message):
        self.print_usage(sys.stderr)
        sys.exit(f"{self.prog}: error: {message}")


class SnapshotInfo:
    """One <Grid> of the temporal collection, before its HDF5 data is read."""

    def __init__(self, index, time, h5_file, nodes, cells, attributes):
        self.index, self.time, self.h5_file = index, time, h5_file
        self.nodes, self.cells, self.attributes = nodes, cells, attributes
        match = re.search(r"(\d+)\.h5$", h5_file)
        self.step = int(match.group(1)) if match else index

    def __repr__(self):
        return f"<snapshot step {self.step}, t = {self.time:g}, {self.h5_file}>"


class Snapshot:
    """Loaded data: nodes (N x 2), triangles (2M x 3), triangulation and
    fields {name: N array}; vector attributes are split into components
    (velocity -> u, v; any other vector w -> w_x, w_y)."""

    def __init__(self, info, nodes, quads, fields):
        self.info, self.step, self.time = info, info.step, info.time
        self.nodes, self.quads, self.fields = nodes, quads, fields
        # deal.II writes the quadrilateral vertices counter-clockwise.
        self.triangles = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
        self.triangulation = mtri.Triangulation(nodes[:, 0], nodes[:, 1], self.triangles)

    def field_names(self):
        """Scalar field names, the usual ones first."""
        names = list(self.fields)
        return ([n for n in PREFERRED_ORDER if n in names] +
                sorted(n for n in names if n not in PREFERRED_ORDER))

    def field(self, name):
        name = ALIASES.get(name, name)
        if name not in self.fields:
            raise UserError(f"no field \"{name}\" in {self.info.h5_file}; "
                            f"available: {', '.join(self.field_names())}")
        return self.fields[name]


def _data_path(item, directory, what):
    """'solution-00010.h5:/nodes' -> (absolute h5 file, dataset)."""
    if item is None or item.get("Format", "HDF") != "HDF":
        raise UserError(f"solution.xdmf: {what} is not stored in an HDF5 file")
    file_name, _, dataset = (item.text or "").strip().rpartition(":")
    if not file_name:
        raise UserError(f"solution.xdmf: cannot read the HDF5 location of {what}")
    return os.path.join(directory, file_name), dataset


def parse_xdmf(path, cell_type="Quadrilateral"):
    """List of SnapshotInfo, one per time in the temporal collection, whose
    cells must be of cell_type (a 2D run's Quadrilateral, a 3D run's
    Hexahedron)."""
    if not os.path.isfile(path):
        raise UserError(f"{path} not found (was the run written with Output/Interval > 0?)")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as error:
        raise UserError(f"cannot parse {path}: {error}") from None
    directory = os.path.dirname(os.path.abspath(path))
    snapshots = []
    for grid in root.iter("Grid"):
        if grid.get("GridType") != "Uniform":
            continue
        what = f"grid {len(snapshots)}"
        time = grid.find("Time")
        nodes = _data_path(grid.find("Geometry/DataItem"), directory, f"{what} geometry")
        cells = _data_path(grid.find("Topology/DataItem"), directory, f"{what} topology")
        if grid.find("Topology").get("TopologyType") != cell_type:
            raise UserError(f"{path}: {what} does not have {cell_type.lower()} cells"
                            + (" (a 3D run: use plot_slices.py)"
                               if cell_type == "Quadrilateral" else
                               " (a 2D run: use plot_run.py)"))
        attributes = {a.get("Name"): _data_path(a.find("DataItem"), directory,
                                                f"{what} attribute {a.get('Name')}")
                      for a in grid.findall("Attribute")}
        snapshots.append(SnapshotInfo(len(snapshots),
                                      float(time.get("Value")) if time is not None else 0.0,
                                      nodes[0], nodes, cells, attributes))
    if not snapshots:
        raise UserError(f"{path} contains no snapshots")
    return snapshots


def read_csv(path):
    """CSV with a header row -> {column: numpy array}; numeric columns become
    float arrays, others stay strings. A partly written last line is dropped."""
    if not os.path.isfile(path):
        raise UserError(f"{path} not found")
    with open(path, newline="") as file:
        rows = list(csv.reader(file))
    if not rows:
        raise UserError(f"{path} is empty")
    header = [name.strip() for name in rows[0]]
    body = [row for row in rows[1:] if len(row) == len(header)]
    columns = {}
    for name, values in zip(header, zip(*body) if body else [()] * len(header)):
        try:
            columns[name] = np.array(values, dtype=float)
        except ValueError:
            columns[name] = np.array(values, dtype=str)
    return columns


def output_directory(path):
    """Create path if needed and return it."""
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as error:
        raise UserError(f"cannot create {path}: {error}") from None
    return path


def numeric_columns(table, skip=("step", "time")):
    return [name for name, values in table.items()
            if name not in skip and values.dtype.kind == "f"]


class Run:
    def __init__(self, directory):
        if not os.path.isdir(directory):
            raise UserError(f"run directory \"{directory}\" does not exist")
        self.directory = directory
        self.name = os.path.basename(os.path.normpath(os.path.abspath(directory)))
        self._snapshots = None

    def path(self, name):
        return os.path.join(self.directory, name)

    @property
    def snapshots(self):
        if self._snapshots is None:
            self._snapshots = parse_xdmf(self.path("solution.xdmf"))
        return self._snapshots

    def statistics(self):
        return read_csv(self.path("statistics.csv"))

    def units(self):
        """(length unit, time unit) of the run's output: Model/Units in its
        parameters.prm, SI (m, s) or dimensionless (L0 = 1 cm, T0 = 60 s, the
        default and what a run without parameters.prm is taken to be)."""
        section, units = [], "dimensionless"
        try:
            with open(self.path("parameters.prm")) as f:
                for line in f:
                    words = line.split("#", 1)[0].split()
                    if words[:1] == ["subsection"]:
                        section.append(" ".join(words[1:]))
                    elif words[:1] == ["end"] and section:
                        section.pop()
                    elif section == ["Model"] and words[:3] == ["set", "Units", "="]:
                        units = " ".join(words[3:])
        except OSError:
            pass
        return ("m", "s") if units == "SI" else ("cm", "T0 = 60 s")

    def probes(self):
        """{(x, y): {column: array}} with one entry per probe point."""
        table = read_csv(self.path("probes.csv"))
        if "x" not in table or "y" not in table:
            raise UserError(f"{self.path('probes.csv')} has no x, y columns")
        points = np.stack([table["x"], table["y"]], axis=1)
        unique, first = np.unique(points, axis=0, return_index=True)
        return {tuple(p): {k: v[(points == p).all(axis=1)] for k, v in table.items()}
                for p in unique[np.argsort(first)]}

    def steps(self):
        return [s.step for s in self.snapshots]

    def nearest_snapshot(self, step=None, time=None):
        """SnapshotInfo nearest to step (or time); the last one if neither is given.
        A step or time outside the run's snapshot range is a UserError."""
        snaps = self.snapshots
        if step is None and time is None:
            return snaps[-1]
        key, want = ("step", step) if step is not None else ("time", time)
        values = np.array([getattr(s, key) for s in snaps], dtype=float)
        if not values.min() <= want <= values.max():
            raise UserError(f"{self.directory}: no snapshot near {key} {want:g}; snapshots "
                            f"exist for {key}s {values.min():g} to {values.max():g} "
                            f"(steps {', '.join(map(str, self.steps()))})")
        return snaps[int(np.argmin(np.abs(values - want)))]

    def load(self, info):
        """Read one snapshot's mesh and fields."""
        def read(location, what):
            file_name, dataset = location
            if not os.path.isfile(file_name):
                raise UserError(f"{file_name} (listed in solution.xdmf) not found")
            try:
                with h5py.File(file_name, "r") as h5:
                    return np.asarray(h5[dataset])
            except (OSError, KeyError) as error:
                raise UserError(f"cannot read {what} ({dataset}) from {file_name}: "
                                f"{error}") from None

        nodes = read(info.nodes, "nodes")[:, :2].astype(float)
        quads = read(info.cells, "cells").astype(np.int64)
        fields = {}
        for name, location in info.attributes.items():
            data = read(location, name).reshape(len(nodes), -1).astype(float)
            if data.shape[1] == 1:
                fields[name] = data[:, 0]
            else:
                labels = ["u", "v"] if name == "velocity" else [f"{name}_x", f"{name}_y"]
                fields.update(zip(labels, data[:, :2].T))
        # Every cell writes its own copy of its vertices (a field that jumps
        # between cells keeps each cell's value there): merge the copies into
        # one node, in file order, with the mean of their values (the value
        # itself for a continuous field).
        _, first, inverse = np.unique(nodes.round(12), axis=0,
                                      return_index=True, return_inverse=True)
        if len(first) < len(nodes):
            order = np.argsort(first)
            renumber = np.empty_like(order)
            renumber[order] = np.arange(len(order))
            merged = renumber[inverse.ravel()]
            copies = np.bincount(merged)
            nodes, quads = nodes[first[order]], merged[quads]
            fields = {name: np.bincount(merged, weights=values) / copies
                      for name, values in fields.items()}
        return Snapshot(info, nodes, quads, fields)


def same_nodes(a, b):
    return len(a.nodes) == len(b.nodes) and np.allclose(a.nodes, b.nodes, atol=1e-12)


def interpolate_onto(source, target):
    """Fields of Snapshot source at the nodes of Snapshot target: copied when the
    nodes coincide, else linearly interpolated (NaN outside source's mesh)."""
    if same_nodes(source, target):
        return dict(source.fields)
    x, y = target.nodes.T
    try:
        find = source.triangulation.get_trifinder()
    except RuntimeError as error:
        raise UserError(f"cannot interpolate from {source.info.h5_file}: {error}") from None
    return {name: mtri.LinearTriInterpolator(source.triangulation, values, find)(x, y)
            .filled(np.nan) for name, values in source.fields.items()}
