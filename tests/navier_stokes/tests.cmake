# Navier–Stokes against a closed form: Kovasznay flow at Re = 40
# (tests/navier_stokes/kovasznay.prm), run to its steady state with
# Momentum convection = Eulerian: velocity L2 errors 2.72e-2, 3.26e-3,
# 4.07e-4 (rates 3.06, 3.00), pressure 0.483, 0.0871, 0.0205 (2.47, 2.09).
# The semi-Lagrangian step at k = 1 settles 0.29-0.31 away in u (8.1-8.7 in
# p) on all three meshes: no rate.
viscofilm_test(kovasznay MODE convergence RANKS 2
  PRM ${S}/navier_stokes/kovasznay.prm
  VARY "Initial global refinement=3,4,5"
  MIN_RATES "velocity_l2_error=2.9,pressure_l2_error=2.0"
  NUMDIFF "-a 1e-12 -r 1e-6")

# The Eulerian convection in time: a Taylor-Green vortex started from rest
# (tests/navier_stokes/vortex_startup.prm, a manufactured solution whose
# convection the pressure balances), k = 0.2, 0.1, 0.05 to t = 1 at Order 2:
# velocity L2 errors 5.39e-4, 1.01e-4, 2.24e-5 (rates 2.42, 2.17; the mesh's
# floor is 4.5e-6), pressure 0.284, 0.066, 0.021 (2.10, 1.65). With the
# convecting velocity not extrapolated (u* = u^n) the pressure errors are
# 1.30, 0.613 (rate 1.08) and the test fails.
viscofilm_test(vortex_startup MODE convergence RANKS 2
  PRM ${S}/navier_stokes/vortex_startup.prm
  VARY "Time step=0.2,0.1,0.05" "Number of steps=5,10,20"
  MIN_RATES "velocity_l2_error=1.9,pressure_l2_error=1.5"
  NUMDIFF "-a 1e-12 -r 1e-6")
