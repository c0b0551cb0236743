# Start-up of Poiseuille flow from rest with inertia (Res = π²) against its
# Fourier series: the velocity error at t = 1 is first order in k.
viscofilm_test(poiseuille_startup MODE convergence RANKS 2
  PRM ${S}/poiseuille_startup/poiseuille_startup.prm
  VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
  MIN_RATES "velocity_l2_error=0.95"
  BOUND "statistics.csv:pressure_l2_error<1e-8"
  NUMDIFF "-a 1e-12 -r 1e-6")

# Res ∂u/∂t by BDF2 (variable-step coefficients; constant k here).
viscofilm_order2_prm(poiseuille_startup_order2
  ${S}/poiseuille_startup/poiseuille_startup.prm)
viscofilm_test(poiseuille_startup_order2 MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_startup_order2.prm
  REFERENCE ${S}/poiseuille_startup/poiseuille_startup_order2.output
  VARY "Time step=0.2,0.1,0.05,0.025" "Number of steps=5,10,20,40"
  MIN_RATES "velocity_l2_error=1.9"
  BOUND "statistics.csv:pressure_l2_error<1e-8"
  NUMDIFF "-a 1e-12 -r 1e-6")

# The same with Momentum convection = Eulerian: BDF2 at the point with u^n
# and u^{n-1} of the nodes; in this flow u·∇u = 0 and u^n at a foot is u^n at
# the point, so the errors are the semi-Lagrangian step's (the same
# reference, rates 2.17, 2.07, 2.02).
file(READ ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_startup_order2.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_startup_order2_eulerian.prm "${_prm}
subsection Stokes solver
  set Momentum convection = Eulerian
end
")
viscofilm_test(poiseuille_startup_order2_eulerian MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_startup_order2_eulerian.prm
  REFERENCE ${S}/poiseuille_startup/poiseuille_startup_order2.output
  VARY "Time step=0.2,0.1,0.05,0.025" "Number of steps=5,10,20,40"
  MIN_RATES "velocity_l2_error=1.9"
  BOUND "statistics.csv:pressure_l2_error<1e-8"
  NUMDIFF "-a 1e-12 -r 1e-6")
