#!/usr/bin/env python3
"""Write the gmsh (msh 2.2 ASCII) meshes of the gmsh tests.

tilted_channel.msh: the channel 0 <= xi <= 2, 0 <= eta <= 1/2 rotated by
theta (cos 0.8, sin 0.6), 4 x 1 quadrilaterals; boundary lines in physical
groups 5 "Inflow" (xi = 0), 7 without a name (xi = 2), 11 "Wall" (eta = 0),
3 "Symmetry" (eta = 1/2). triangles.msh (tests/bad_input): the unit square
in two triangles.
tilted_duct.msh (3D): tilted_channel.msh extruded over 0 <= z <= 1/2 in one
layer of 4 hexahedra; boundary quadrilaterals in the same physical groups,
and 13 "Sides" (z = 0 and z = 1/2). tetrahedra.msh (tests/bad_input): the
unit tetrahedron, its faces in 1 "Wall".
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
        for i, node in enumerate(nodes):
            x, y, z = (tuple(node) + (0,))[:3]
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elements))
        for i, (kind, tag, vertices) in enumerate(elements):
            f.write("%d %d 2 %d %d %s\n" % (i + 1, kind, tag, tag,
                                          " ".join(str(v + 1) for v in vertices)))
        f.write("$EndElements\n")


def tilted_nodes(nx, ny):
    c, s = 0.8, 0.6
    nodes = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            xi, eta = 2.0 * i / nx, 0.5 * j / ny
            nodes.append((c * xi - s * eta, s * xi + c * eta))
    return nodes


def tilted_channel():
    nx, ny = 4, 1
    node = lambda i, j: j * (nx + 1) + i
    nodes = tilted_nodes(nx, ny)
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


def tilted_duct():
    nx, ny, depth = 4, 1, 0.5
    plane = tilted_nodes(nx, ny)
    nodes = [(x, y, 0.0) for x, y in plane] + [(x, y, depth) for x, y in plane]
    node = lambda i, j, k: k * len(plane) + j * (nx + 1) + i
    quad = lambda a, b, c, d: (3, (a, b, c, d))
    faces = []  # (tag, vertices)
    for i in range(nx):  # walls
        faces.append((11, (node(i, 0, 0), node(i + 1, 0, 0), node(i + 1, 0, 1), node(i, 0, 1))))
        faces.append((3, (node(i, ny, 0), node(i, ny, 1), node(i + 1, ny, 1), node(i + 1, ny, 0))))
    for j in range(ny):  # inflow, outflow
        faces.append((5, (node(0, j, 0), node(0, j, 1), node(0, j + 1, 1), node(0, j + 1, 0))))
        faces.append((7, (node(nx, j, 0), node(nx, j + 1, 0), node(nx, j + 1, 1), node(nx, j, 1))))
    for j in range(ny):  # front, back
        for i in range(nx):
            faces.append((13, (node(i, j, 0), node(i, j + 1, 0), node(i + 1, j + 1, 0), node(i + 1, j, 0))))
            faces.append((13, (node(i, j, 1), node(i + 1, j, 1), node(i + 1, j + 1, 1), node(i, j + 1, 1))))
    elements = [(3, tag, vertices) for tag, vertices in faces]
    for j in range(ny):
        for i in range(nx):
            elements.append((5, 1, tuple(node(a, b, k) for k in (0, 1)
                                         for a, b in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)))))
    write(os.path.join(HERE, "tilted_duct.msh"),
          [(2, 5, "Inflow"), (2, 11, "Wall"), (2, 3, "Symmetry"), (2, 13, "Sides"),
           (3, 1, "Fluid")], nodes, elements)


def tetrahedra():
    nodes = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    elements = [(2, 1, (0, 2, 1)), (2, 1, (0, 1, 3)), (2, 1, (0, 3, 2)), (2, 1, (1, 2, 3)),
                (4, 2, (0, 1, 2, 3))]
    write(os.path.join(HERE, "..", "bad_input", "tetrahedra.msh"),
          [(2, 1, "Wall"), (3, 2, "Fluid")], nodes, elements)


tilted_channel()
triangles()
tilted_duct()
tetrahedra()
