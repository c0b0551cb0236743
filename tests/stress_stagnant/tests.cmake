# A DG stress that jumps across a face, at rest (u = 0: every node is
# stagnant, every foot on its node): kept exactly by the upwind (own cell)
# foot value; averaging over the cells sharing a foot made the error 0.091.
viscofilm_test(stress_stagnant MODE run RANKS 1 2
  PRM ${S}/stress_stagnant/stress_stagnant.prm
  BOUND "statistics.csv:stress_l2_error<1e-11"
  NUMDIFF "-a 1e-11 -r 0"
  COMPARE statistics.csv:step,stress_l2_error
          probes.csv:step,x,y,tau_xx,tau_xy,tau_yy)
