# Issue 11 item 3: departure feet cut at the boundary, inflow values per
# boundary, wrapped across periodic pairs (doc/verification.md).
# A relaxed stress entering a Poiseuille channel develops along each
# streamline like start-up of shear with t = x/U(y) (closed form); first
# order in h (kink at the front x = tU(y), corner (0, 0)); the box clamp kept
# the inlet nodes' own, developing stress (error 4.1 at every h).
viscofilm_test(stress_inflow MODE convergence RANKS 1
  PRM ${S}/stress_inflow/stress_inflow.prm
  VARY "Initial global refinement=2,3,4" "Time step=0.05,0.025,0.0125" "Number of steps=40,80,160"
  MIN_RATES "stress_l2_error=0.8"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-10 -r 1e-6")

# The fully developed stress as the inflow Stress (and initial stress): the
# channel stays developed, to the O(k) by which the first-order update's
# discrete equilibrium differs from it (τ_xx 8 → 8.15 at k = 0.05 away from
# the inlet); first order in k (the clamp passes this too).
file(READ ${S}/stress_inflow/stress_inflow.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stress_inflow_developed.prm "${_prm}
subsection Boundary conditions
  subsection Inlet
    set Stress = 32*(1-2*y)^2; 4*(1-2*y); 0
  end
end
subsection Initial conditions
  set Stress = 32*(1-2*y)^2; 4*(1-2*y); 0
end
subsection Verification
  set Exact stress = 32*(1-2*y)^2; 4*(1-2*y); 0
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/stress_inflow/stress_inflow.prm)
viscofilm_test(stress_inflow_developed MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stress_inflow_developed.prm
  REFERENCE ${S}/stress_inflow/stress_inflow_developed.output
  VARY "Time step=0.1,0.05,0.025" "Number of steps=20,40,80"
  MIN_RATES "stress_l2_error=0.9"
  NUMDIFF "-a 1e-10 -r 1e-6")
