# Issue 10 item 1: a sharp disc (φ = 0.1 or 0) carried once round by the same
# rotation at Δx = 1/32 stays in [0, 0.1] (measured exactly) and keeps its
# mass (0.00703125) to 3e-8 relative (measured 8.4e-9); error against the
# rotated disc 0.00802 (bound 0.0081; the thesis' GLS: 0.0140, φ in
# [-0.0235, 0.1250]).
viscofilm_test(volume_fraction_sharp MODE run RANKS 2
  PRM ${S}/volume_fraction_sharp/volume_fraction_sharp.prm
  BOUND "statistics.csv:volume_fraction_min>-1e-12"
        "statistics.csv:volume_fraction_max<0.100000000001"
        "statistics.csv:volume_fraction_integral>0.00703124979"
        "statistics.csv:volume_fraction_integral<0.00703125021"
        "statistics.csv:volume_fraction_l2_error<0.0081"
  NUMDIFF "-a 1e-10 -r 1e-6"
  COMPARE statistics.csv:step,volume_fraction_l2_error,volume_fraction_integral,volume_fraction_min,volume_fraction_max
          probes.csv:step,x,y,volume_fraction)
