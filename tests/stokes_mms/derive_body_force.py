#!/usr/bin/env python3
"""Derive the body forces of the variable-viscosity manufactured solutions
(needs python3-sympy; run by hand, not by the tests):

    derive_body_force.py [stokes_mms|wall]

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
Both: f = -div(2 eta D(u)) + grad p.
"""
import sys

import sympy as sp

x, y = sp.symbols("x y")
r = 11
pi = sp.pi
cases = {
    "stokes_mms": (x * y,
                   sp.sin(pi * x) ** 2 * sp.sin(2 * pi * y),
                   -sp.sin(2 * pi * x) * sp.sin(pi * y) ** 2),
    "wall": (16 * x * (1 - x) * y * (1 - y),
             sp.sin(pi * x) * sp.cos(pi * y),
             -sp.cos(pi * x) * sp.sin(pi * y)),
}
phi, u, v = cases[sys.argv[1] if len(sys.argv) > 1 else "stokes_mms"]
eta = 1 + (r - 1) * phi
p = sp.cos(pi * x) * sp.cos(pi * y)

assert sp.simplify(sp.diff(u, x) + sp.diff(v, y)) == 0
assert sp.integrate(p, (x, 0, 1), (y, 0, 1)) == 0

grad = sp.Matrix([[sp.diff(u, x), sp.diff(u, y)], [sp.diff(v, x), sp.diff(v, y)]])
D = (grad + grad.T) / 2
stress = 2 * eta * D
f = [
    -(sp.diff(stress[i, 0], x) + sp.diff(stress[i, 1], y)) + sp.diff(p, [x, y][i])
    for i in range(2)
]


def muparser(expression):
    return str(sp.simplify(expression)).replace("**", "^")


print("Body force     =", muparser(f[0]), ";", muparser(f[1]))
print("Exact solution =", muparser(u), ";", muparser(v), ";", muparser(p))
