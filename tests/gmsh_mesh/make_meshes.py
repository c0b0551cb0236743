#!/usr/bin/env python3
"""Write the gmsh (msh 2.2 ASCII) meshes of the gmsh tests.

tilted_channel.msh: the channel 0 <= xi <= 2, 0 <= eta <= 1/2 rotated by
theta (cos 0.8, sin 0.6), 4 x 1 quadrilaterals; boundary lines in physical
groups 5 "Inflow" (xi = 0), 7 without a name (xi = 2), 11 "Wall" (eta = 0),
3 "Symmetry" (eta = 1/2). triangles.msh (tests/bad_input): the unit square
in two triangles.
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def write(path, names, nodes, elements):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write("$PhysicalNames\n%d\n" % len(names))
        for dim, tag, name in names:
            f.write('%d %d "%s"\n' % (dim, tag, name))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % len(nodes))
        for i, (x, y) in enumerate(nodes):
            f.write("%d %.17g %.17g 0\n" % (i + 1, x, y))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elements))
        for i, (kind, tag, vertices) in enumerate(elements):
            f.write("%d %d 2 %d %d %s\n" % (i + 1, kind, tag, tag,
                                          " ".join(str(v + 1) for v in vertices)))
        f.write("$EndElements\n")


def tilted_channel():
    c, s = 0.8, 0.6
    nx, ny = 4, 1
    node = lambda i, j: j * (nx + 1) + i
    nodes = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            xi, eta = 2.0 * i / nx, 0.5 * j / ny
            nodes.append((c * xi - s * eta, s * xi + c * eta))
    elements = []
    for i in range(nx):  # walls
        elements.append((1, 11, (node(i, 0), node(i + 1, 0))))
        elements.append((1, 3, (node(i + 1, ny), node(i, ny))))
    for j in range(ny):  # inflow, outflow
        elements.append((1, 5, (node(0, j + 1), node(0, j))))
        elements.append((1, 7, (node(nx, j), node(nx, j + 1))))
    for j in range(ny):
        for i in range(nx):
            elements.append((3, 1, (node(i, j), node(i + 1, j),
                                    node(i + 1, j + 1), node(i, j + 1))))
    write(os.path.join(HERE, "tilted_channel.msh"),
          [(1, 5, "Inflow"), (1, 11, "Wall"), (1, 3, "Symmetry"), (2, 1, "Fluid")],
          nodes, elements)


def triangles():
    nodes = [(0, 0), (1, 0), (1, 1), (0, 1)]
    elements = [(1, 1, (0, 1)), (1, 1, (1, 2)), (1, 1, (2, 3)), (1, 1, (3, 0)),
                (2, 2, (0, 1, 2)), (2, 2, (0, 2, 3))]
    write(os.path.join(HERE, "..", "bad_input", "triangles.msh"),
          [(1, 1, "Wall"), (2, 2, "Fluid")], nodes, elements)


tilted_channel()
triangles()
