# Manufactured solution with viscosity 1 + 10xy: Taylor-Hood rates, velocity
# L2 ~ h^3 and pressure L2 ~ h^2, asserted over four meshes.
viscofilm_test(stokes_mms MODE convergence RANKS 1 2 THREADS 1 2
  PRM ${S}/stokes_mms/stokes_mms.prm
  VARY "Initial global refinement=2,3,4,5" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  NUMDIFF "-a 1e-12 -r 2e-3")

# The same with the locally conservative Q2 × P1disc pair: the same rates,
# and ∫_K ∇·u = 0 on every cell (1.3e-10 at tolerance 1e-12), where Q2 × Q1
# leaves max |∫_K ∇·u|/|K| = 1.8e-2 (Δx = 1/4) to 2.7e-5 (Δx = 1/32).
file(READ ${S}/stokes_mms/stokes_mms.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_dgp.prm "${_prm}
subsection Stokes solver
  set Pressure element = discontinuous
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/stokes_mms/stokes_mms.prm)
viscofilm_test(stokes_mms_dgp MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_dgp.prm
  REFERENCE ${S}/stokes_mms/stokes_mms_dgp.output
  VARY "Initial global refinement=2,3,4,5" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  BOUND "statistics.csv:max_cell_divergence<1e-9"
  NUMDIFF "-a 1e-12 -r 2e-3")

# The same with the geometric multigrid for the velocity block (Velocity
# preconditioner = GMG): a preconditioner only, so the same errors and rates
# as with the AMG (the same reference), on 1 and 2 ranks; and its FGMRES
# iterations bounded on every mesh (29 at Δx = 1/32 to 1e-12; with the
# coarse levels' viscosity averaged wrongly, 1/4 of the one below: 40 at
# Δx = 1/16, failed).
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_gmg.prm "${_prm}
${_gmg}")
viscofilm_test(stokes_mms_gmg MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_gmg.prm
  REFERENCE ${S}/stokes_mms/stokes_mms.output
  VARY "Initial global refinement=2,3,4,5" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  BOUND "statistics.csv:stokes_iterations<36"
  NUMDIFF "-a 1e-12 -r 2e-3")

# Issue 13 item 4: the velocity AMG kept across time steps (Stokes solver/
# Preconditioner/Reuse, the default). stokes_mms for three steps of k = 1e-9
# (φ = xy moves by 1e-9, so the manufactured solution still holds): one AMG
# build for the three solves, and the last step's errors are the one-step
# errors of stokes_mms (its reference) at the same rates.
file(READ ${S}/stokes_mms/stokes_mms.prm _prm_stokes_mms)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_reuse.prm "${_prm_stokes_mms}
subsection Time stepping
  set Time step       = 1e-9
  set Number of steps = 3
end
subsection Stokes solver
  subsection Preconditioner
    set Reuse = true
  end
end
")
viscofilm_test(stokes_mms_reuse MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_reuse.prm
  REFERENCE ${S}/stokes_mms/stokes_mms.output
  VARY "Initial global refinement=2,3,4,5" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  BOUND "statistics.csv:max(stokes_preconditioner_builds)<1.5"
  NUMDIFF "-a 1e-12 -r 2e-3")

# A rebuild forced: φ = xy of stokes_mms carried by its flow with k = 0.1
# for 8 steps changes η = 1 + 10 φ by a mean |ln(η/η_built)| of 0.07 per
# step (statistics.csv: stokes_viscosity_change), 0.13 after two, so the AMG
# (Rebuild viscosity change = 0.1) is rebuilt every second step: 4 builds
# for 8 steps (must be >= 2 and < 8). Against the run with the AMG rebuilt
# for every matrix (Reuse = false, today's solver; the reference): reuse
# changes the answer by no more than the solver tolerance (1e-12).
foreach(_reuse true false)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_reuse_rebuild_${_reuse}.prm "${_prm_stokes_mms}
subsection Time stepping
  set Time step       = 0.1
  set Number of steps = 8
end
subsection Stokes solver
  subsection Preconditioner
    set Reuse = ${_reuse}
  end
end
")
endforeach()
viscofilm_test(stokes_reuse_rebuild MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_reuse_rebuild_true.prm
  REFERENCE ${S}/stokes_mms/stokes_reuse_rebuild.output
  BOUND "statistics.csv:max(stokes_preconditioner_builds)>1.5"
        "statistics.csv:max(stokes_preconditioner_builds)<7.5"
  NUMDIFF "-a 1e-10 -r 1e-8"
  COMPARE statistics.csv:step,max_velocity,velocity_l2_error,pressure_l2_error,volume_fraction_integral)
viscofilm_test(stokes_reuse_rebuild_off MODE run RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_reuse_rebuild_false.prm
  REFERENCE ${S}/stokes_mms/stokes_reuse_rebuild.output
  NUMDIFF "-a 1e-10 -r 1e-8"
  COMPARE statistics.csv:step,max_velocity,velocity_l2_error,pressure_l2_error,volume_fraction_integral)

# Issue 12, the flow in 3D (geometry, boundary conditions, Stokes)
#
# Manufactured solution in 3D with viscosity 1 + 10xyz (derive_body_force.py
# 3d), Dirichlet data on all six sides: Taylor-Hood rates, velocity L2 ~ h^3
# and pressure L2 ~ h^2, asserted over three meshes, on 1 and 2 ranks (one
# reference: the two must agree).
viscofilm_test(stokes_mms_3d MODE convergence RANKS 2
  PRM ${S}/stokes_mms/stokes_mms_3d.prm
  VARY "Initial global refinement=1,2,3" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  NUMDIFF "-a 1e-12 -r 2e-3")

# The same with the geometric multigrid (its 3D matrix-free levels), its
# FGMRES iterations bounded (34 at Δx = 1/8).
file(READ ${S}/stokes_mms/stokes_mms_3d.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_3d_gmg.prm "${_prm}
${_gmg}")
viscofilm_test(stokes_mms_3d_gmg MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_3d_gmg.prm
  REFERENCE ${S}/stokes_mms/stokes_mms_3d.output
  VARY "Initial global refinement=1,2,3" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  BOUND "statistics.csv:stokes_iterations<40"
  NUMDIFF "-a 1e-12 -r 2e-3")

# stokes: the velocity AMG built on the Q1 sub-cell matrix (Stokes solver/
# Preconditioner/AMG matrix, issues 13.4 and 12.4). The manufactured
# solutions of stokes_mms (2D) and stokes_mms_3d, solved with the AMG on the
# FE_Q_iso_Q1(2) matrix without couplings between the velocity components
# and one V-cycle: the errors of the Q2 runs (their references) at the same
# rates, since FGMRES still applies the Q2 matrix, and few outer iterations
# on the finest mesh (56 in 2D; 60–80 in 3D at tolerance 1e-12, varying
# between runs and ranks), which a sub-cell matrix on the wrong nodes does
# not give (130 in 2D with the sub-cells' midline nodes left out of the
# lower sub-cells). The AMG named, since auto would take the GMG on the
# finest meshes.
set(_stokes_subcells "
subsection Stokes solver
  subsection Preconditioner
    set Velocity preconditioner = AMG
    set AMG matrix = Q1 sub-cells by component
    set AMG cycle  = V
    set AMG cycles = 1
  end
end
")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_subcells.prm "${_prm_stokes_mms}${_stokes_subcells}")
viscofilm_test(stokes_mms_subcells MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_subcells.prm
  REFERENCE ${S}/stokes_mms/stokes_mms.output
  VARY "Initial global refinement=2,3,4,5" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  BOUND "statistics.csv:max(stokes_iterations)<80"
  NUMDIFF "-a 1e-12 -r 2e-3")
file(READ ${S}/stokes_mms/stokes_mms_3d.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_3d_subcells.prm "${_prm}${_stokes_subcells}")
viscofilm_test(stokes_mms_3d_subcells MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_3d_subcells.prm
  REFERENCE ${S}/stokes_mms/stokes_mms_3d.output
  VARY "Initial global refinement=1,2,3" MIN_RATES "velocity_l2_error=2.8,pressure_l2_error=1.8"
  BOUND "statistics.csv:max(stokes_iterations)<100"
  NUMDIFF "-a 1e-12 -r 2e-3")
