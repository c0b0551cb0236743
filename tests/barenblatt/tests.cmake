# The bounded softening against the Barenblatt-Pattle solution (m = 2):
# first order with k ~ Δx (implicit Euler), φ >= 0 and below its peak.
viscofilm_test(barenblatt MODE convergence RANKS 1
  PRM ${S}/barenblatt/barenblatt.prm
  VARY "Initial global refinement=3,4,5,6" "Softening steps=10,20,40,80"
       "Softening time step=0.02,0.01,0.005,0.0025"
  MIN_RATES "volume_fraction_l2_error=0.95"
  BOUND "statistics.csv:volume_fraction_min>-1e-15"
        "statistics.csv:volume_fraction_max<0.1"
  NUMDIFF "-a 1e-12 -r 1e-6")
