# Steady Poiseuille flow in a 2 x 1 channel with an outflow outlet: Q2-Q1 holds
# the exact u = 4y(1-y), p = 8(2-x), so errors are at solver tolerance; with
# each Stokes solver.
file(READ ${S}/poiseuille/poiseuille.prm _prm)
foreach(_method "block preconditioned" direct thesis)
  string(REPLACE " " "_" _name "poiseuille_${_method}")
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${_name}.prm "${_prm}
subsection Stokes solver
  set Method = ${_method}
end
")
  viscofilm_test(${_name} MODE run RANKS 1 2
    PRM ${CMAKE_CURRENT_BINARY_DIR}/${_name}.prm
    REFERENCE ${S}/poiseuille/poiseuille.output
    NUMDIFF "-a 1e-9 -r 0"
    COMPARE statistics.csv:step,max_velocity,velocity_l2_error,pressure_l2_error
            probes.csv:step,x,y,u,v,p)
endforeach()
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/poiseuille/poiseuille.prm)
