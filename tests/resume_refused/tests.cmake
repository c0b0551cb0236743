# Resuming with a changed parameter that shapes the solution is refused with
# a message naming it, statistics.csv untouched: entries the old hand-kept
# list missed (averaging, indicator, Picard settings, softening).
viscofilm_test(resume_refused MODE refused RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/bulb_restart.prm
  REFERENCE ${S}/resume_refused/resume_refused.output
  STOP_AFTER 2
  RESUME_SET "Stokes solver/Viscosity averaging=arithmetic"
             "Mesh refinement/Indicator=biofilm"
             "Time stepping/Picard tolerance=1e-5"
             "Time stepping/Maximum Picard iterations=5"
             "Initial conditions/Softening steps=3")
