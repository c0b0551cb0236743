# A φ blob and a stress blob carried once round a periodic channel by a
# uniform flow: feet wrap across Inlet/Outlet. Errors stay at the initial
# interpolation error (φ 3.7e-9 → 4.5e-9, τ 0.0085 → 0.0094); without the
# wrap 1.5e-6 and 0.41.
viscofilm_test(periodic_transport MODE run RANKS 1 2
  PRM ${S}/periodic_transport/periodic_transport.prm
  BOUND "statistics.csv:volume_fraction_l2_error<5e-9" "statistics.csv:stress_l2_error<0.01"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,volume_fraction_l2_error,stress_l2_error)
