# The attached φ washed out (detachment off): none of the blob's 1/9 leaves
# before its leading edge can (t < 1.5), half of it when its centre reaches
# the outlet (t = 2 + k/2, bracket [1.99, 2.02]), all of it by t = 2.5; ∫φ +
# outflow = ∫φ(0) to round-off while the blob is in the channel (t < 2.35),
# then to the scheme's conservation error as its last 0.3 % leaves (the mass
# fixer has nothing left to take from: measured 5.6e-5).
viscofilm_test(phi_washout MODE run RANKS 1 2
  PRM ${S}/phi_outflow/phi_washout.prm
  BOUND "statistics.csv[time<2.35]:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow>0.111111111110"
        "statistics.csv[time<2.35]:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow<0.111111111112"
        "statistics.csv:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow<0.1112"
        "statistics.csv:volume_fraction_inflow<1e-12"
        "statistics.csv[time<1.5]:volume_fraction_outflow<1e-12"
        "statistics.csv[time<1.99]:volume_fraction_outflow<0.0555555556"
        "statistics.csv[time>2.02]:volume_fraction_outflow>0.0555555555"
        "statistics.csv[time>2.49]:volume_fraction_outflow>0.1111111"
        "statistics.csv[time>2.49]:volume_fraction_outflow<0.1112"
        "statistics.csv[time>2.49]:volume_fraction_integral<1e-7"
  NUMDIFF "-a 1e-10 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_outflow,volume_fraction_inflow)

# With φ = 1 flowing in at the inlet (and a C¹ quadratic ramp from 1 down to
# 0 over x in [0, 1/4] at t = 0, 1/8 of mass, its front 0.25 from the outlet
# at t = 2.5): the inflow is u × 1 × 1 per unit time, volume_fraction_inflow
# = t at every step; ∫φ + outflow − inflow = ∫φ(0) = 1/9 + 1/8 (the blob's
# tail now leaves while the fixer has the ramp's front to work on).
file(READ ${S}/phi_outflow/phi_washout.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/phi_washout_inflow.prm "${_prm}
subsection Boundary conditions
  subsection Inlet
    set Volume fraction = 1
  end
end
subsection Initial conditions
  set Volume fraction = \\
    (4/3)*if(abs(x-1) < d/2, 0.75 - ((x-1)/d)^2, if(abs(x-1) < 1.5*d, 0.5*(1.5 - abs(x-1)/d)^2, 0)) * \\
    (4/3)*if(abs(y-0.5) < d/2, 0.75 - ((y-0.5)/d)^2, if(abs(y-0.5) < 1.5*d, 0.5*(1.5 - abs(y-0.5)/d)^2, 0)) + \\
    if(x < 0.125, 1 - 2*(4*x)^2, if(x < 0.25, 2*(1 - 4*x)^2, 0))
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/phi_outflow/phi_washout.prm)
viscofilm_test(phi_washout_inflow MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/phi_washout_inflow.prm
  REFERENCE ${S}/phi_outflow/phi_washout_inflow.output
  BOUND "statistics.csv:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow>0.236111111110"
        "statistics.csv:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow<0.236111111112"
        "statistics.csv:volume_fraction_inflow-time<1e-12"
        "statistics.csv:volume_fraction_inflow-time>-1e-12"
        "statistics.csv[time<1.5]:volume_fraction_outflow<1e-12"
  NUMDIFF "-a 1e-10 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_outflow,volume_fraction_inflow)

# Resumed after step 40 from a checkpoint: the totals come back.
viscofilm_test(phi_washout_restart MODE restart RANKS 1 2
  PRM ${S}/phi_outflow/phi_washout.prm
  REFERENCE unused
  STOP_AFTER 40
  NUMDIFF "-a 1e-12 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_outflow,volume_fraction_inflow)
