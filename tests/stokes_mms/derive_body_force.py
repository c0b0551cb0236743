#!/usr/bin/env python3
"""Derive the body forces of the variable-viscosity manufactured solutions
(needs python3-sympy; run by hand, not by the tests):

    derive_body_force.py [stokes_mms|wall|3d]

stokes_mms (tests/stokes_mms):
    eta = 1 + (r - 1) phi,  phi = x y,  r = 11      (viscosity 1 .. 11)
    u = sin(pi x)^2 sin(2 pi y),  v = -sin(2 pi x) sin(pi y)^2   (div u = 0)
    p = cos(pi x) cos(pi y)                                      (mean 0)
wall (tests/stokes_mms_wall): a flow that slides along all four walls, so that
every boundary dof carries an inhomogeneity:
    eta = 1 + (r - 1) phi,  phi = 16 x (1 - x) y (1 - y),  r = 11
        (phi is zero on the walls, so the inflow value phi = 0 holds wherever
        round-off makes u.n < 0, and it is Q2, so the phi field is exact and
        stays so when the mesh is refined)
    u = sin(pi x) cos(pi y),  v = -cos(pi x) sin(pi y)    (div u = 0)
        u.n = 0 on the walls of the unit square, u.t = +-sin(pi s) != 0
    p = cos(pi x) cos(pi y)                               (mean 0)
3d (tests/stokes_mms, stokes_mms_3d.prm): a flow along every axis on the
unit cube, Dirichlet data on all six sides:
    eta = 1 + (r - 1) phi,  phi = x y z,  r = 11
    u = sin(pi x) cos(pi y) cos(pi z),  v = cos(pi x) sin(pi y) cos(pi z),
    w = -2 cos(pi x) cos(pi y) sin(pi z)                     (div u = 0)
    p = cos(pi x) cos(pi y) cos(pi z)                        (mean 0)
All: f = -div(2 eta D(u)) + grad p.
"""
import sys

import sympy as sp

x, y, z = sp.symbols("x y z")
r = 11
pi = sp.pi
S, C = sp.sin, sp.cos
cases = {
    "stokes_mms": (x * y,
                   [S(pi * x) ** 2 * S(2 * pi * y), -S(2 * pi * x) * S(pi * y) ** 2],
                   C(pi * x) * C(pi * y)),
    "wall": (16 * x * (1 - x) * y * (1 - y),
             [S(pi * x) * C(pi * y), -C(pi * x) * S(pi * y)],
             C(pi * x) * C(pi * y)),
    "3d": (x * y * z,
           [S(pi * x) * C(pi * y) * C(pi * z), C(pi * x) * S(pi * y) * C(pi * z),
            -2 * C(pi * x) * C(pi * y) * S(pi * z)],
           C(pi * x) * C(pi * y) * C(pi * z)),
}
phi, u, p = cases[sys.argv[1] if len(sys.argv) > 1 else "stokes_mms"]
X = [x, y, z][:len(u)]
eta = 1 + (r - 1) * phi

assert sp.simplify(sum(sp.diff(u[i], X[i]) for i in range(len(X)))) == 0
assert sp.integrate(p, *[(c, 0, 1) for c in X]) == 0

grad = sp.Matrix([[sp.diff(u[i], X[j]) for j in range(len(X))] for i in range(len(X))])
D = (grad + grad.T) / 2
stress = 2 * eta * D
f = [-sum(sp.diff(stress[i, j], X[j]) for j in range(len(X))) + sp.diff(p, X[i])
     for i in range(len(X))]


def muparser(expression):
    return str(sp.simplify(expression)).replace("**", "^")


print("Body force     =", " ; ".join(muparser(c) for c in f))
print("Exact solution =", " ; ".join(muparser(c) for c in u + [p]))
