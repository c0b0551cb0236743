# z-invariant 3D channels (slip Front and Back) against the closed form and
# the 2D runs. Poiseuille in [0,2]x[0,1]x[0,1], exact in Q2-Q1 (errors at
# solver tolerance; at step 0 the exact solution's norms, those of the 2D
# tests/poiseuille): with a velocity inlet (block preconditioned and direct
# solvers), with Front/Back periodic instead of slip, and driven by the
# pressure P = 16 on the inlet (tests/boundary_types/pressure_inlet in 3D).
file(READ ${S}/z_invariant/poiseuille_3d.prm _prm)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/z_invariant/poiseuille_3d.prm)
set(_variant_direct "
subsection Stokes solver
  set Method = direct
end
")
set(_variant_periodic "
subsection Boundary conditions
  subsection Front
    set Type             = periodic
    set Periodic partner = Back
  end
  subsection Back
    set Type             = periodic
    set Periodic partner = Front
  end
end
")
set(_variant_pressure_inlet "
subsection Boundary conditions
  subsection Inlet
    set Type     = pressure
    set Pressure = 16
    set Velocity = 0; 0; 0
  end
end
")
foreach(_variant direct periodic pressure_inlet)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_3d_${_variant}.prm "${_prm}${_variant_${_variant}}")
endforeach()
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_3d.prm "${_prm}")
foreach(_case poiseuille_3d poiseuille_3d_direct poiseuille_3d_periodic poiseuille_3d_pressure_inlet)
  viscofilm_test(${_case} MODE run RANKS 1 2
    PRM ${CMAKE_CURRENT_BINARY_DIR}/${_case}.prm
    REFERENCE ${S}/z_invariant/poiseuille_3d.output
    NUMDIFF "-a 1e-9 -r 0"
    COMPARE statistics.csv:step,max_velocity,velocity_l2_error,pressure_l2_error)
endforeach()

# The coupled start-up of tests/channel_startup (Oldroyd-B mixture, stress
# and φ transported, Picard loop) z-invariant in 3D, one layer of depth 1/4
# on the 2D test's in-plane mesh: the closed form's rates, and the 2D run's
# errors times sqrt(1/4) as the reference (a regression check; the table
# prints 4 digits, hence -r 2e-3). One rank (36 s; 2 ranks took 131 s on the
# shared machine); the rank counts are compared on the cases around it.
viscofilm_test(channel_startup_3d MODE convergence RANKS 1
  PRM ${S}/z_invariant/channel_startup_3d.prm
  VARY "Time step=0.1,0.05,0.025" "Number of steps=10,20,40"
  MIN_RATES "pressure_l2_error=0.95,stress_l2_error=0.95"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-10 -r 2e-3")
