# Stress/Foot interpolation = logarithm against the exact translation of a
# stress spanning e^{-3} … e^{3} (see its prm): log c is smooth where c is
# steep, and the error is 5 times the Q2 interpolant of c's smaller (0.0387
# against 0.211 on level 4, 0.00254 against 0.0138 on level 5). The bound
# fails with Foot interpolation = conformation; rate 3.9 from level 4 to 5.
viscofilm_test(stress_log_translation MODE convergence RANKS 2
  PRM ${S}/stress_log_translation/stress_log_translation.prm
  VARY "Initial global refinement=4,5"
  MIN_RATES "stress_l2_error=3"
  BOUND "statistics.csv[time>0.01]:stress_l2_error<0.05"
  NUMDIFF "-a 1e-10 -r 1e-6")
