#!/usr/bin/python3
"""∫φ of an imaged half-disc against the mesh size h and the pixel size p.

usage: integral_study.py BUILD/viscofilm [WORKDIR]

The half-disc of radius 0.25 centred at (0.5, 0) on the bottom wall of the
unit square (geometry/make_images.py's test shape), drawn binary (a pixel is
biofilm where its centre is inside) on pixels of p = 0.02 ... 0.0025 over
y < 0.5, thresholded into φ = 0.1, interpolated on uniform meshes of
h = 1/16 ... 1/256 (no softening, no time step). Prints, per (p, h), ∫φ and
its relative errors against the pixels' own area (Σ φ_pixel p²: the mesh's
error) and against the closed form 0.1 πR²/2 (the mesh's and the pixels').
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "geometry"))
import make_images as mi  # noqa: E402

PRM = """subsection Geometry
  set Initial global refinement = {level}
end
subsection Time stepping
  set Number of steps = 0
end
subsection Model
  set Diffusion coefficient = 0
end
subsection Initial conditions
  set Volume fraction = image
  subsection Image
    set File       = {image}
    set Pixel size = {pixel}
  end
end
subsection Output
  set Interval  = 0
  set Directory = {output}
end
"""


def main():
    viscofilm = os.path.abspath(sys.argv[1])
    work = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="image-study-")
    os.makedirs(work, exist_ok=True)
    exact = 0.1 * math.pi * 0.25 ** 2 / 2
    print("p,h,integral,error_vs_pixels,error_vs_closed_form")
    for n in (25, 50, 100, 200):  # pixels across y < 0.5
        pixel = 0.5 / n
        rows = mi.draw(2 * n, n, pixel, mi.half_disc, (0, 255))
        image = os.path.join(work, "half_disc_%d.png" % n)
        with open(os.devnull, "w") as quiet:  # make_images prints what it wrote
            stdout, sys.stdout = sys.stdout, quiet
            mi.png(image, rows)
            sys.stdout = stdout
        pixel_area = 0.1 * sum(v == 255 for row in rows for v in row) * pixel ** 2
        for level in (4, 5, 6, 7, 8):
            output = os.path.join(work, "out-%d-%d" % (n, level))
            prm = os.path.join(work, "run-%d-%d.prm" % (n, level))
            with open(prm, "w") as f:
                f.write(PRM.format(level=level, image=image, pixel=pixel, output=output))
            subprocess.run([viscofilm, prm], check=True, capture_output=True)
            with open(os.path.join(output, "statistics.csv")) as f:
                value = float(next(csv.DictReader(f))["volume_fraction_integral"])
            print("%g,1/%d,%.7e,%+.2e,%+.2e" % (pixel, 2 ** level, value,
                                               value / pixel_area - 1, value / exact - 1),
                  flush=True)


if __name__ == "__main__":
    main()
