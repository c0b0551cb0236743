#!/usr/bin/python3
"""The image a run's initial φ was read from, beside that φ.

usage: plot_image.py RUN_DIR [--out FILE]

Reads Initial conditions/Image (File, Pixel size, Origin, Threshold) from
RUN_DIR/parameters.prm (File relative to the parameter file, so run this from
where the run was started with the .prm's path as given: RUN_DIR/parameters.prm
records the File as written; --image overrides it) and draws three panels: the
image placed at its origin and pixel size, the initial φ (the first snapshot,
after softening) on the adapted mesh with its cell edges, and the image's
threshold contour over the outline φ = 0.05.
"""

import os
import sys

sys.dont_write_bytecode = True  # keep postprocess/ free of __pycache__
import viscofilm_io as vio  # first: checks for numpy, h5py, matplotlib
from viscofilm_io import np

import matplotlib.image as mpimg
import matplotlib.pyplot as plt


def image_settings(run):
    """File, pixel size (dx, dy), origin and threshold from parameters.prm."""
    settings, section = {}, []
    with open(run.path("parameters.prm")) as f:
        for line in f:
            words = line.split("#")[0].split()
            if words[:1] == ["subsection"]:
                section.append(" ".join(words[1:]))
            elif words[:1] == ["end"]:
                section.pop()
            elif words[:1] == ["set"] and section == ["Initial conditions", "Image"]:
                name, value = " ".join(words[1:]).split("=", 1)
                settings[name.strip()] = value.strip()
    if not settings.get("File"):
        raise vio.UserError(f"{run.path('parameters.prm')}: no Initial conditions/Image/File")
    size = [float(v) for v in settings.get("Pixel size", "0.01").split(",")]
    return (settings["File"], size * 2 if len(size) == 1 else size,
            [float(v) for v in settings.get("Origin", "0, 0").split(",")],
            float(settings.get("Threshold", "0.5")))


def main():
    parser = vio.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--image", help="the image file (default: as parameters.prm says)")
    parser.add_argument("--out", help="output PNG (default RUN_DIR/figures/image_to_phi.png)")
    args = parser.parse_args()
    run = vio.Run(args.run_dir)
    file, size, origin, threshold = image_settings(run)
    file = args.image or file
    if not os.path.isfile(file):
        raise vio.UserError(f"image {file} not found; give it with --image")
    pixels = mpimg.imread(file)  # PNG: floats in [0, 1], rows from the top
    if pixels.ndim != 2:
        raise vio.UserError(f"{file} is not grayscale")
    height, width = pixels.shape
    extent = (origin[0], origin[0] + width * size[0], origin[1], origin[1] + height * size[1])
    snap = run.load(run.snapshots[0])
    tri, phi = snap.triangulation, snap.fields["volume_fraction"]

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2), layout="constrained")
    axes[0].imshow(pixels, cmap="gray", extent=extent, origin="upper", vmin=0, vmax=1)
    axes[0].set(title=f"{os.path.basename(file)}: {width} × {height} pixels of {size[0]:g}")
    mesh = axes[1].tripcolor(tri, phi, shading="gouraud", cmap="viridis")
    axes[1].triplot(tri, color="w", linewidth=0.1, alpha=0.5)
    fig.colorbar(mesh, ax=axes[1], shrink=0.8, format="%.3g")
    axes[1].set(title="φ at t = 0 (after softening) on the adapted mesh")
    x = origin[0] + (np.arange(width) + 0.5) * size[0]
    y = origin[1] + (np.arange(height)[::-1] + 0.5) * size[1]
    axes[2].contour(x, y, pixels, levels=[threshold], colors="r", linewidths=1.5)
    axes[2].tricontour(tri, phi, levels=[vio.BIOFILM_LEVEL], colors="k", linewidths=1)
    axes[2].plot([], [], "r", label=f"image, intensity = {threshold:g}")
    axes[2].plot([], [], "k", label=f"φ = {vio.BIOFILM_LEVEL:g}")
    axes[2].legend(loc="upper right")
    axes[2].set(title="outlines")
    x_nodes, y_nodes = tri.x, tri.y
    for ax in axes:
        ax.set(aspect="equal", xlim=(x_nodes.min(), x_nodes.max()),
               ylim=(y_nodes.min(), min(y_nodes.max(), extent[3] + 0.1)), xlabel="x", ylabel="y")
    out = args.out or os.path.join(args.run_dir, "figures", "image_to_phi.png")
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=120)
    print("wrote", out)


if __name__ == "__main__":
    vio.main_guard(main)
