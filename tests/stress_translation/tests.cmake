# The feet's velocity at t_{n+1/2}: a stress carried by a time-dependent
# uniform flow round a periodic channel. Order 2 only (Order 1: rates 1.5,
# 1.3, errors 0.15 … 0.021).
viscofilm_order2_prm(stress_translation_order2
  ${S}/stress_translation/stress_translation.prm)
viscofilm_test(stress_translation_order2 MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/stress_translation_order2.prm
  REFERENCE ${S}/stress_translation/stress_translation_order2.output
  VARY "Time step=0.08,0.04,0.02" "Number of steps=4,8,16"
  MIN_RATES "stress_l2_error=1.9"
  NUMDIFF "-a 1e-12 -r 1e-6")
