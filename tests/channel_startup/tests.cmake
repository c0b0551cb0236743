# Inertialess start-up of channel flow at a fixed flow rate, uniform φ,
# Oldroyd-B: the pressure gradient (the elastic stress's effect on the flow)
# and τ against the closed form; first order in k.
viscofilm_test(channel_startup MODE convergence RANKS 1
  PRM ${S}/channel_startup/channel_startup.prm
  VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
  MIN_RATES "pressure_l2_error=0.95,stress_l2_error=0.95"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-12 -r 1e-6")

# With inertia: the same start-up as channel_startup at Reynolds number =
# 1e-9 (the flow reaches the parabola in a time of order Res, so the closed
# form holds) from the initial condition u = 0, which the boundary data at
# t = 0 do not meet. The first step's stress update took the mean of ∇u^0 =
# 0 and ∇u^1: an O(k) error that stayed (τ 3.1e-2 … 7.4e-3 over k = 0.04 …
# 0.01, rate 1.04); with ∇u^1 alone the rates are 2 (the pressure's 1.89 at
# k = 0.04 … 0.02).
viscofilm_order2_prm(channel_startup_inertia_order2
  ${S}/channel_startup/channel_startup.prm)
file(APPEND ${CMAKE_CURRENT_BINARY_DIR}/channel_startup_inertia_order2.prm "
subsection Model
  set Reynolds number = 1e-9
end
")
viscofilm_test(channel_startup_inertia_order2 MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/channel_startup_inertia_order2.prm
  REFERENCE ${S}/channel_startup/channel_startup_inertia_order2.output
  VARY "Time step=0.02,0.01,0.005" "Number of steps=20,40,80"
  MIN_RATES "pressure_l2_error=1.9,stress_l2_error=1.9"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-12 -r 1e-6")
