# The bounded softening (sub-cell Q1 diffusion, discrete upwinding) against
# the 3D Barenblatt–Pattle solution (closed form in the .prm), Δx = 1/4 …
# 1/16 with k ∝ Δx: rates 1.34, 1.62 (first order in k: asserted >= 0.9).
viscofilm_test(barenblatt_3d MODE convergence RANKS 1
  PRM ${S}/barenblatt_3d/barenblatt_3d.prm
  VARY "Initial global refinement=2,3,4" "Softening steps=10,20,40"
       "Softening time step=0.02,0.01,0.005"
  MIN_RATES "volume_fraction_l2_error=0.9"
  BOUND "statistics.csv:volume_fraction_min>-1e-15"
        "statistics.csv:volume_fraction_max<0.08"
  NUMDIFF "-a 1e-12 -r 1e-6")
