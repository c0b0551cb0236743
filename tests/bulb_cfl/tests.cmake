# The bulb with an inflow peak of 1 at CFL ≈ 1.5 (prm/cfl-1.prm, 12 steps):
# runs, the Picard loop converges, c stays positive definite, feet leave
# their cells, the flow over the bulb reaches 1.18 (bounds 1.15 … 1.2);
# 1 and 2 ranks agree.
file(READ ${CMAKE_SOURCE_DIR}/prm/cfl-1.prm _prm)
string(REPLACE "include thesis.prm" "include ${CMAKE_SOURCE_DIR}/prm/thesis.prm" _prm "${_prm}")
string(REGEX REPLACE "set Number of steps = [0-9]+" "set Number of steps = 12" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/bulb_cfl.prm "${_prm}
subsection Stokes solver
  set Tolerance = 1e-11
end
subsection Output
  set Interval = 0
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/prm/cfl-1.prm)
viscofilm_test(bulb_cfl MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/bulb_cfl.prm
  REFERENCE ${S}/bulb_cfl/bulb_cfl.output
  BOUND "statistics.csv:picard_converged>0.5"
        "statistics.csv:min_conformation_eigenvalue>0"
        "statistics.csv:max_velocity<1.2" "statistics.csv:max(max_velocity)>1.15"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,max_velocity,volume_fraction_integral,min_conformation_eigenvalue,feet_left_cell
          probes.csv:step,x,y,u,v,p,volume_fraction,tau_xx,tau_xy,tau_yy)
