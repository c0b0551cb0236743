# Issue 11 item 8: feet where k|∇u|/2 is O(1), in the closed-streamline
# Stokes flow of tests/feet_strain (φ0 = sin²(πx) sin²(πy) is steady, the
# exact solution). k = 0.5: undamped Newton cycled at 20 nodes, its runaway
# iterates were cut at the walls and taken as feet (198 per step; error
# 0.173 after one step, 0.190 at t = 2); with the line search, and cuts only
# where the flow enters, all feet are found (9 rounds) and none is cut:
# 0.0149 after one step, 0.0362 at t = 2 (implicit-midpoint drift across
# the streamlines).
viscofilm_test(feet_strain MODE run RANKS 1 2
  PRM ${S}/feet_strain/feet_strain.prm
  BOUND "statistics.csv:volume_fraction_l2_error<0.04" "statistics.csv:feet_left_domain<1"
        "statistics.csv:feet_substepped<1"
  NUMDIFF "-a 1e-10 -r 1e-6"
  COMPARE statistics.csv:step,volume_fraction_l2_error,feet_newton_iterations,feet_left_domain,feet_substepped)

# k = 0.8: for 286 nodes the implicit midpoint rule has no root (Newton with
# line search gives up): their feet are traced by explicit midpoint
# sub-steps (error 0.0173 after one step, 0.0256 at t = 2.4; undamped
# Newton cut 548 feet per step at the walls, error 0.232). One rank: on two, an iterate that runs away beyond the
# ghost layer and out of the mesh cannot be cut and stops the run ("lies in
# no cell", doc/numerics.md).
file(READ ${S}/feet_strain/feet_strain.prm _prm)
string(REGEX REPLACE "set Time step *= [0-9.]+" "set Time step = 0.8" _prm "${_prm}")
string(REGEX REPLACE "set Number of steps *= [0-9]+" "set Number of steps = 3" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/feet_strain_substeps.prm "${_prm}")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/feet_strain/feet_strain.prm)
viscofilm_test(feet_strain_substeps MODE run RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/feet_strain_substeps.prm
  REFERENCE ${S}/feet_strain/feet_strain_substeps.output
  BOUND "statistics.csv:volume_fraction_l2_error<0.03" "statistics.csv:sum(feet_substepped)>100"
  NUMDIFF "-a 1e-10 -r 1e-6"
  COMPARE statistics.csv:step,volume_fraction_l2_error,feet_newton_iterations,feet_left_domain,feet_substepped)
