#!/usr/bin/python3
"""Slices of a 3D viscofilm run: the fields of one snapshot on planes x, y or
z = const, drawn as colour maps with the biofilm outline φ = 0.05.

    plot_slices.py RUN_DIR [--step N] [--plane z=0.25 --plane y=0.14 ...]
                   [--fields volume_fraction,speed,tau_xy] [--out DIR]

Reads solution.xdmf and its solution-NNNNN.h5 (hexahedra, as a 3D run writes
them). Each hexahedron the plane crosses contributes the quadrilateral where
the plane cuts it, with the node values interpolated linearly along its edges
across the plane (exact for the trilinear patches DataOut writes when the
cells are boxes aligned with the axes). Fields: any dataset of the snapshot
(volume_fraction, pressure, tau_xx, ..., a vector's component as velocity_x)
and speed = |u|. Default planes: through the middle of the domain in z and
in y. Prints each field's range on each plane; writes
RUN_DIR/figures/slice-<axis><value>-<field>-NNNNN.png.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from viscofilm_io import (UserError, ArgumentParser, main_guard,  # noqa: E402
                          BIOFILM_LEVEL, parse_xdmf, np, h5py)
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402

AXES = "xyz"
LABELS = {"volume_fraction": "φ", "speed": "|u|", "pressure": "p"}


def read_hexahedra(info):
    """Nodes (N x 3), hexahedra (M x 8) and {name: N x k values} of a snapshot."""
    def read(location):
        file_name, dataset = location
        if not os.path.isfile(file_name):
            raise UserError(f"{file_name} (listed in solution.xdmf) not found")
        with h5py.File(file_name, "r") as h5:
            return np.asarray(h5[dataset])
    nodes = read(info.nodes).astype(float)
    cells = read(info.cells).astype(np.int64)
    if nodes.shape[1] != 3 or cells.shape[1] != 8:
        raise UserError(f"{info.h5_file} is not a 3D snapshot (nodes {nodes.shape[1]}D, "
                        f"{cells.shape[1]} vertices per cell): use plot_run.py for 2D runs")
    fields = {name: read(loc).reshape(len(nodes), -1).astype(float)
              for name, loc in info.attributes.items()}
    return nodes, cells, fields


def field_values(fields, name):
    """Node values of a named field: a dataset, a component velocity_y, or speed."""
    if name == "speed":
        return np.linalg.norm(fields["velocity"], axis=1)
    if name in fields and fields[name].shape[1] == 1:
        return fields[name][:, 0]
    base, _, component = name.rpartition("_")
    if base in fields and component in AXES:
        return fields[base][:, AXES.index(component)]
    available = sorted(fields) + ["speed"]
    raise UserError(f"no field \"{name}\"; available: {', '.join(available)} "
                    f"(vector components as velocity_x, ...)")


def slice_plane(nodes, cells, axis, value):
    """The quadrilaterals where the plane x_axis = value cuts the hexahedra:
    (points (4K x 3), weights w and the lower/upper node indices lo, hi
    (4K each) so that a field f on the cut is (1 − w) f[lo] + w f[hi])."""
    coords = nodes[cells]                                    # M x 8 x 3
    height = coords[:, :, axis]
    low, high = height.min(axis=1), height.max(axis=1)
    # Each plane point once: a plane on a cell face belongs to the cell above
    # (and to the one below at the domain's top).
    top = value >= nodes[:, axis].max()
    crossed = (low <= value) & ((value < high) if not top else (value <= high)) & (high > low)
    if not crossed.any():
        raise UserError(f"the plane {AXES[axis]} = {value:g} misses the mesh "
                        f"({AXES[axis]} from {nodes[:, axis].min():g} to "
                        f"{nodes[:, axis].max():g})")
    cells, coords = cells[crossed], coords[crossed]
    order = np.argsort(coords[:, :, axis], axis=1, kind="stable")
    lower, upper = order[:, :4], order[:, 4:]
    plane = [d for d in range(3) if d != axis]
    rows = np.arange(len(cells))[:, None]
    # Pair each lower vertex with the upper vertex above it (nearest in the plane).
    lp = coords[rows, lower][:, :, plane]
    up = coords[rows, upper][:, :, plane]
    distance = np.linalg.norm(lp[:, :, None, :] - up[:, None, :, :], axis=3)
    upper = np.take_along_axis(upper, distance.argmin(axis=2), axis=1)
    lo, hi = cells[rows, lower], cells[rows, upper]          # K x 4
    zl, zh = nodes[lo, axis], nodes[hi, axis]
    w = np.where(zh > zl, (value - zl) / np.where(zh > zl, zh - zl, 1), 0)
    points = nodes[lo] + w[..., None] * (nodes[hi] - nodes[lo])
    # Order each quadrilateral's corners around its centre.
    p2 = points[:, :, plane]
    centre = p2.mean(axis=1, keepdims=True)
    angle = np.arctan2(p2[:, :, 1] - centre[:, :, 1], p2[:, :, 0] - centre[:, :, 0])
    turn = np.argsort(angle, axis=1)
    take = lambda a: np.take_along_axis(a, turn, axis=1)      # noqa: E731
    points = np.take_along_axis(points, turn[..., None], axis=1)
    return points.reshape(-1, 3), take(w).ravel(), take(lo).ravel(), take(hi).ravel()


def parse_plane(text):
    axis, sep, value = text.partition("=")
    if not sep or axis.strip() not in AXES:
        raise UserError(f"--plane \"{text}\": write it as x=VALUE, y=VALUE or z=VALUE")
    try:
        return AXES.index(axis.strip()), float(value)
    except ValueError:
        raise UserError(f"--plane \"{text}\": \"{value}\" is not a number") from None


def main():
    parser = ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="the run's output directory")
    parser.add_argument("--step", type=int, help="snapshot step (default: the last)")
    parser.add_argument("--plane", action="append", default=[],
                        help="x=VALUE, y=VALUE or z=VALUE (repeatable)")
    parser.add_argument("--fields", default="volume_fraction,speed,tau_xy",
                        help="comma-separated fields (default: %(default)s)")
    parser.add_argument("--out", help="figure directory (default: RUN/figures)")
    args = parser.parse_args()

    snapshots = parse_xdmf(os.path.join(args.run, "solution.xdmf"), "Hexahedron")
    info = snapshots[-1]
    if args.step is not None:
        matches = [s for s in snapshots if s.step == args.step]
        if not matches:
            raise UserError(f"no snapshot at step {args.step}; steps: "
                            f"{', '.join(str(s.step) for s in snapshots)}")
        info = matches[0]
    nodes, cells, fields = read_hexahedra(info)
    if not args.plane:
        middle = 0.5 * (nodes.min(axis=0) + nodes.max(axis=0))
        args.plane = [f"z={middle[2]:.6g}", f"y={middle[1]:.6g}"]
    names = [n.strip() for n in args.fields.split(",") if n.strip()]
    values = {name: field_values(fields, name) for name in names}
    phi = field_values(fields, "volume_fraction") if "volume_fraction" in fields else None
    out = args.out or os.path.join(args.run, "figures")
    os.makedirs(out, exist_ok=True)

    print(f"{info.h5_file}: step {info.step}, t = {info.time:g}, "
          f"{len(cells)} hexahedra")
    for text in args.plane:
        axis, value = parse_plane(text)
        points, w, lo, hi = slice_plane(nodes, cells, axis, value)
        plane = [d for d in range(3) if d != axis]
        quads = np.arange(len(points)).reshape(-1, 4)
        triangles = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
        mesh = mtri.Triangulation(points[:, plane[0]], points[:, plane[1]], triangles)
        outline = None if phi is None else (1 - w) * phi[lo] + w * phi[hi]
        for name in names:
            on_plane = (1 - w) * values[name][lo] + w * values[name][hi]
            print(f"  {AXES[axis]} = {value:g}: {name} from {on_plane.min():.9g} "
                  f"to {on_plane.max():.9g}")
            extent = points[:, plane].max(axis=0) - points[:, plane].min(axis=0)
            figure, axes = plt.subplots(figsize=(7, 7 * extent[1] / extent[0] + 0.8))
            image = axes.tripcolor(mesh, on_plane, shading="gouraud", cmap="viridis")
            if outline is not None and outline.min() < BIOFILM_LEVEL < outline.max():
                axes.tricontour(mesh, outline, levels=[BIOFILM_LEVEL], colors="white",
                                linewidths=1)
            figure.colorbar(image, ax=axes, label=LABELS.get(name, name), shrink=0.8)
            axes.set_aspect("equal")
            axes.set_xlabel(AXES[plane[0]])
            axes.set_ylabel(AXES[plane[1]])
            axes.set_title(f"{LABELS.get(name, name)} on {AXES[axis]} = {value:g}, "
                           f"t = {info.time:g} (step {info.step})")
            file_name = os.path.join(out, f"slice-{AXES[axis]}{value:g}-{name}-"
                                          f"{info.step:05d}.png")
            figure.savefig(file_name, dpi=110, bbox_inches="tight")
            plt.close(figure)
    print(f"figures in {out}")


if __name__ == "__main__":
    main_guard(main)
