# φ entering through the Inlet (1) and the Bottom (0) at an angle: each node
# takes the value of the boundary its characteristic crosses; the probes are
# nodes whose exact value is 1 or 0, (1/16, 1/16) among them, whose foot the
# clamp moved to the corner (φ = 0 there, exact 1).
viscofilm_test(volume_fraction_oblique MODE run RANKS 1 2
  PRM ${S}/volume_fraction_oblique/volume_fraction_oblique.prm
  BOUND "statistics.csv:volume_fraction_min>-1e-12" "statistics.csv:volume_fraction_max<1.000000000001"
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE probes.csv:step,x,y,volume_fraction)
