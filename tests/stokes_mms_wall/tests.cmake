# Tangential wall velocity (inhomogeneous Dirichlet data on every wall) on
# adapted meshes whose hanging nodes touch the walls, with the viscoelastic
# Picard loop (zero elastic stress) and without: both must give the same
# errors (one reference, the Newtonian run's; the loop's second Stokes solve
# assembles only the right-hand side with the matrix of the first), and no
# adapted mesh may do worse against the exact solution than the uniform 1/8
# mesh it starts from (3.65e-4 and 8.7e-3; the matrix-current path that
# dropped the inhomogeneity of hanging dofs next to the walls gave 8.9e-3 and
# 0.46).
file(READ ${S}/stokes_mms_wall/stokes_mms_wall.prm _prm)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/stokes_mms_wall/stokes_mms_wall.prm)
foreach(_viscoelastic true false)
  set(_name stokes_mms_wall_viscoelastic_${_viscoelastic})
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${_name}.prm "${_prm}
subsection Model
  set Viscoelastic = ${_viscoelastic}
end
")
  viscofilm_test(${_name} MODE run RANKS 1 2
    PRM ${CMAKE_CURRENT_BINARY_DIR}/${_name}.prm
    REFERENCE ${S}/stokes_mms_wall/stokes_mms_wall.output
    BOUND "statistics.csv[step>0]:velocity_l2_error<4e-4"
          "statistics.csv[step>0]:pressure_l2_error<1e-2"
    NUMDIFF "-a 1e-10 -r 1e-6"
    COMPARE statistics.csv:step,cells,velocity_l2_error,pressure_l2_error)
endforeach()

# The Newtonian run with the geometric multigrid: its levels carry the
# hanging nodes and the walls' constraints; the same errors, and its FGMRES
# iterations bounded (21-23; with the SIMD lanes 2-4 of every cell batch
# given no viscosity, failed).
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_wall_gmg.prm "${_prm}
subsection Model
  set Viscoelastic = false
end
${_gmg}")
viscofilm_test(stokes_mms_wall_gmg MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_wall_gmg.prm
  REFERENCE ${S}/stokes_mms_wall/stokes_mms_wall.output
  BOUND "statistics.csv[step>0]:velocity_l2_error<4e-4"
        "statistics.csv[step>0]:pressure_l2_error<1e-2"
        "statistics.csv[step>0]:stokes_iterations<28"
  NUMDIFF "-a 1e-10 -r 1e-6"
  COMPARE statistics.csv:step,cells,velocity_l2_error,pressure_l2_error)

# Velocity preconditioner = auto (the default) on meshes adapted across its
# 2D threshold of 2e4 Stokes dofs: the wall case from Δx = 1/32 (9539 dofs,
# AMG: 58 FGMRES iterations), refined to 3724 cells (about 3.4e4 dofs, GMG:
# 15; the AMG takes 37 there), coarsened to 1540 (AMG: 36). The same errors
# as the run with the AMG named throughout (the reference), and the
# iterations of the GMG on the large mesh and of the AMG on the small ones
# (with the threshold at 1e9 dofs: 37 on the large mesh, failed; at 0: at
# most 27 on the small ones, failed).
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_wall_auto.prm "${_prm}
subsection Geometry
  set Initial global refinement = 5
end
subsection Model
  set Viscoelastic = false
end
subsection Mesh refinement
  set Minimum level      = 5
  set Maximum level      = 6
  set Velocity threshold = 2e-6
end
subsection Time stepping
  set Number of steps = 3
end
")
viscofilm_test(stokes_mms_wall_auto MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stokes_mms_wall_auto.prm
  REFERENCE ${S}/stokes_mms_wall/stokes_mms_wall_auto.output
  BOUND "statistics.csv[cells>2000]:stokes_iterations<25"
        "statistics.csv[cells<2000]:max(stokes_iterations)>30"
        "statistics.csv[step>0]:velocity_l2_error<5.5e-6"
  NUMDIFF "-a 1e-10 -r 1e-6"
  COMPARE statistics.csv:step,cells,velocity_l2_error,pressure_l2_error)
