# Issue 13 item 1 (φ): a blob carried half round by a rotation that starts
# from rest, ω = π² sin(πt): with Time stepping/Order = 2 (midpoint feet with
# (u^n + u^{n+1})/2) the error against the rotated blob is second order in k
# (Δx = 1/64: 4.45e-3, 1.14e-3, 3.00e-4, rates 1.97, 1.93); Order = 1 (feet
# with u^{n+1}) gives 1.81e-2, 1.04e-2, 5.49e-3 (rates 0.80, 0.92).
viscofilm_test(volume_fraction_rotation_order2 MODE convergence RANKS 1
  PRM ${S}/volume_fraction_rotation_order2/volume_fraction_rotation_order2.prm
  VARY "Time step=0.05,0.025,0.0125" "Number of steps=10,20,40"
  MIN_RATES "volume_fraction_l2_error=1.9"
  NUMDIFF "-a 1e-12 -r 1e-4")
