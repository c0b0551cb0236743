#!/usr/bin/python3
"""Write the committed images (Initial conditions/Volume fraction = image):
the example biofilm geometry/biofilm_mushroom.png and the test images in
tests/image/ and tests/bad_input/. Standard library only (PNG: zlib; TIFF:
uncompressed baseline), so that it runs anywhere and the files are the same
bit for bit on every run. All pictures are drawn from formulas (no downloaded
data); every intensity is a number of the bit depth, rows from the top.

    /usr/bin/python3 geometry/make_images.py
"""
import math
import os
import struct
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def png(path, rows, bit_depth=8, colour=False):
    """Grayscale (or RGB with colour=True) PNG; rows: lists of samples."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    sample = ">B" if bit_depth == 8 else ">H"
    raw = b"".join(b"\0" + b"".join(struct.pack(sample, v) for v in row) for row in rows)
    width = len(rows[0]) // (3 if colour else 1)
    header = struct.pack(">IIBBBBB", width, len(rows), bit_depth, 2 if colour else 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    print("wrote", os.path.relpath(path, ROOT))


def tiff(path, pages, bit_depth=8, big_endian=False):
    """Grayscale (min-is-black) uncompressed TIFF, one page per entry of
    pages (each a list of rows), in the given byte order."""
    order = ">" if big_endian else "<"
    sample = "B" if bit_depth == 8 else "H"
    out = bytearray((b"MM" if big_endian else b"II") + struct.pack(order + "HI", 42, 0))
    previous_link = 4  # where the offset of the next page goes
    for rows in pages:
        height, width = len(rows), len(rows[0])
        data = b"".join(struct.pack(order + sample * width, *row) for row in rows)
        data_offset = len(out)
        out += data + b"\0" * (len(data) % 2)
        ifd_offset = len(out)
        struct.pack_into(order + "I", out, previous_link, ifd_offset)
        entries = [(256, 4, width), (257, 4, height), (258, 3, bit_depth), (259, 3, 1),
                   (262, 3, 1), (273, 4, data_offset), (277, 3, 1), (278, 4, height),
                   (279, 4, len(data))]
        out += struct.pack(order + "H", len(entries))
        for tag, kind, value in entries:
            packed = struct.pack(order + ("H" if kind == 3 else "I"), value)
            out += struct.pack(order + "HHI", tag, kind, 1) + packed + b"\0" * (4 - len(packed))
        previous_link = len(out)
        out += struct.pack(order + "I", 0)
    with open(path, "wb") as f:
        f.write(out)
    print("wrote", os.path.relpath(path, ROOT))


def draw(width, height, pixel, inside, levels, supersample=1):
    """Rows (top first) of a picture of the set inside(x, y) on pixels of
    edge `pixel` whose lower-left corner is at (0, 0): levels = (outside,
    inside) intensities; with supersample > 1 a pixel's intensity is mixed
    in proportion to the fraction of it inside (anti-aliased)."""
    rows = []
    for r in range(height):
        j = height - 1 - r  # rows go down, y goes up
        row = []
        for i in range(width):
            n = supersample
            hits = sum(inside((i + (a + 0.5) / n) * pixel, (j + (b + 0.5) / n) * pixel)
                       for a in range(n) for b in range(n))
            row.append(round(levels[0] + (levels[1] - levels[0]) * hits / n ** 2))
        rows.append(row)
    return rows


def half_disc(x, y):
    """The test biofilm: a half-disc of radius 0.25 centred at (0.5, 0) on
    the bottom wall; area π/32."""
    return (x - 0.5) ** 2 + y ** 2 < 0.25 ** 2


def mushroom(x, y):
    """The example biofilm: a mushroom-shaped colony on a thin base layer,
    the shape the thesis' bulb profile stands for (its figure 4.1) and that
    Pseudomonas aeruginosa biofilms grow in flow cells: a base layer 0.02
    thick over the whole wall, a stalk of half-width 0.05 up to y = 0.2 and
    a cap, the half-ellipse of half-axes 0.16 × 0.1 on y = 0.18, with an
    undercut."""
    base = y < 0.02
    stalk = abs(x - 0.45) < 0.05 and y < 0.2
    cap = y > 0.18 and ((x - 0.45) / 0.16) ** 2 + ((y - 0.18) / 0.1) ** 2 < 1
    return base or stalk or cap


def speckle(i, j):
    """Deterministic noise in [-1, 1] (a hash of the pixel), the graininess
    of a microscope image."""
    return math.sin(12.9898 * i + 78.233 * j) * 43758.5453 % 2 - 1


def main():
    # The example: 200 × 100 pixels of 1/200 over x in [0, 1], y in [0, 0.5]
    # of the unit-square channel; biofilm bright (~200) on a dark background
    # (~40), edges anti-aliased, ±15 of speckle; prm/examples/biofilm-image.prm
    # thresholds it at 0.5 (128).
    clean = draw(200, 100, 1 / 200, mushroom, (40, 200), supersample=4)
    noisy = [[min(255, max(0, v + round(15 * speckle(i, r)))) for i, v in enumerate(row)]
             for r, row in enumerate(clean)]
    png(os.path.join(ROOT, "geometry", "biofilm_mushroom.png"), noisy)

    # The tests (tests/image/): the half-disc on 100 × 50 pixels of 0.01.
    directory = os.path.join(ROOT, "tests", "image")
    os.makedirs(directory, exist_ok=True)
    # 8-bit anti-aliased, for the linear map (20 → φ = 0, 220 → φ = 0.1).
    png(os.path.join(directory, "half_disc_8bit.png"),
        draw(100, 50, 0.01, half_disc, (20, 220), supersample=8))
    # 16-bit with a contrast that only 16 bits carry: 100 outside, 200
    # inside (of 65535; threshold 0.0023 ≈ 151): read as 8 bits it is black.
    png(os.path.join(directory, "half_disc_16bit.png"),
        draw(100, 50, 0.01, half_disc, (100, 200)), bit_depth=16)
    # 16-bit big-endian TIFF, binary (0, 40000).
    tiff(os.path.join(directory, "half_disc_16bit.tif"),
         [draw(100, 50, 0.01, half_disc, (0, 40000))], bit_depth=16, big_endian=True)
    # A filament thinner than the initial cells, between their nodes: x in
    # [0.475, 0.495], y < 0.3, on 200 × 100 pixels of 0.005, 8-bit binary.
    png(os.path.join(directory, "filament.png"),
        draw(200, 100, 0.005, lambda x, y: 0.475 < x < 0.495 and y < 0.3, (0, 255)))
    # A 3D stack (tests/image/image_3d.cc, tests/output_3d/half_ball_3d.prm):
    # a half-ball of radius 0.25 on the bottom wall y = 0, in sections parallel
    # to it (stacked along y), 20 × 20 pixels of 0.05 per slice, 10 slices, in
    # an 8-bit multi-page TIFF; slice k holds the disc of radius √(R² − y_k²).
    pages = []
    for k in range(10):
        y = (k + 0.5) * 0.05
        r2 = 0.25 ** 2 - y ** 2
        pages.append(draw(20, 20, 0.05, lambda x, y: (x - 0.5) ** 2 + (y - 0.5) ** 2 < r2,
                          (0, 255)))
    tiff(os.path.join(directory, "half_ball_stack.tif"), pages)

    # Bad input: the half-disc in colour (red on black).
    png(os.path.join(ROOT, "tests", "bad_input", "colour.png"),
        [sum(([v, 0, 0] for v in row), []) for row in draw(100, 50, 0.01, half_disc, (0, 255))],
        colour=True)


if __name__ == "__main__":
    main()
