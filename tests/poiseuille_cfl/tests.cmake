# The same with Time stepping/CFL number = 0.5 and Time step = 0.1 to t = 1:
# the first step (from u = 0) is 0.1 long, then k = 0.5 Δx / max|u^n| =
# 0.5 (1/8) / 1 = 0.0625 (CFL 0.5 attained, never exceeded), and the last
# step ends at t = 1 (0.025). Reference written by hand
# (tests/poiseuille_cfl/poiseuille_cfl.output).
file(READ ${S}/poiseuille/poiseuille.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_cfl.prm "${_prm}
subsection Time stepping
  set Time step       = 0.1
  set Number of steps = 10
  set CFL number      = 0.5
end
")
viscofilm_test(poiseuille_cfl MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/poiseuille_cfl.prm
  REFERENCE ${S}/poiseuille_cfl/poiseuille_cfl.output
  BOUND "statistics.csv:cfl<0.500000000001" "statistics.csv:max(cfl)>0.499999999999"
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE statistics.csv:step,time,time_step,cfl,max_velocity)
