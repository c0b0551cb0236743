# Two-layer Couette flow (viscosity 1 below y = 0.25, 3 above): u is exact in
# Q2 and the vorticity jumps from -2 to -2/3 across y = 0.25. The snapshot
# must hold each cell's own value at its corners (no merged vertices), the
# continuous fields equal at both copies (to the single precision DataOut
# writes in).
viscofilm_test(two_layer_couette MODE fields RANKS 1 2
  PRM ${S}/two_layer_couette/two_layer_couette.prm
  REFERENCE unused
  TOLERANCE 1e-6
  EXACT "vorticity=-2 if y < 0.25 else -2/3"
        "divergence=0"
        "velocity[0]=2*y if y < 0.25 else 0.5 + (y - 0.25)*2/3"
        "velocity[1]=0"
        "pressure=0")
