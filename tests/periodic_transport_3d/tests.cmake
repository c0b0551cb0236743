# Feet wrapped round a periodic pair normal to z (Front/Back): a φ blob and a
# stress blob (all six components) carried once through a 1 × 1 × 2 channel
# at k = one node spacing, so that every foot is a node or its periodic
# image. The errors stay at the interpolation error of the blob's position
# (φ 1.52e-8 … 1.70e-8 of a scale 1e-6; τ 0.041 … 0.046, alternating as the
# blob's centre passes nodes and cell centres); without the wrap (feet cut
# at the Front) 1.4e-6 and 0.21 after the period.
viscofilm_test(periodic_transport_3d MODE run RANKS 1 2
  PRM ${S}/periodic_transport_3d/periodic_transport_3d.prm
  BOUND "statistics.csv:volume_fraction_l2_error<2e-8"
        "statistics.csv:stress_l2_error<0.047"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,volume_fraction_l2_error,stress_l2_error)
