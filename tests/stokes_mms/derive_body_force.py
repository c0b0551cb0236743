#!/usr/bin/env python3
"""Derive the body force of the variable-viscosity manufactured solution used
by tests/stokes_mms (needs python3-sympy; run by hand, not by the tests).

    eta = 1 + (r - 1) phi,  phi = x y,  r = 11      (viscosity 1 .. 11)
    u = sin(pi x)^2 sin(2 pi y),  v = -sin(2 pi x) sin(pi y)^2   (div u = 0)
    p = cos(pi x) cos(pi y)                                      (mean 0)
    f = -div(2 eta D(u)) + grad p
"""
import sympy as sp

x, y = sp.symbols("x y")
r = 11
eta = 1 + (r - 1) * x * y
u = sp.sin(sp.pi * x) ** 2 * sp.sin(2 * sp.pi * y)
v = -sp.sin(2 * sp.pi * x) * sp.sin(sp.pi * y) ** 2
p = sp.cos(sp.pi * x) * sp.cos(sp.pi * y)

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
