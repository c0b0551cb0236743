# Detachment (Detachment/Release) in Couette flow, viscosity 1 everywhere:
# the simple shear σ_xy = 1 is exact in Q2 × Q1, so each criterion's load is
# known in closed form at every node (von Mises √3, interface traction 1).
# With the strength 1e-7 below it the layer is released (all at once by von
# Mises, a cell a step from the surface by the traction), 1e-7 above it
# nothing is; the mass released plus the φ left is ∫φ(0) = 0.25 − h/6 =
# 11/48 (references checked by hand: tests/detachment/*.prm explain them).
foreach(_case above traction_above)
  viscofilm_test(detachment_couette_${_case} MODE run RANKS 1 2
    PRM ${S}/detachment/detachment_couette_${_case}.prm
    BOUND "statistics.csv:max(detached_mass_total)>0.22916666666"
          "statistics.csv:max(detached_mass_total)<0.22916666667"
          "statistics.csv:sum(detached_mass)>0.22916666666"
          "statistics.csv:sum(detached_mass)<0.22916666667"
          "statistics.csv[step>2]:volume_fraction_integral<1e-12"
    NUMDIFF "-a 1e-10 -r 0"
    COMPARE statistics.csv:step,volume_fraction_integral,detached_mass,detached_mass_total,detached_y_min,detached_y_max)
endforeach()
foreach(_case below traction_below)
  viscofilm_test(detachment_couette_${_case} MODE run RANKS 1 2
    PRM ${S}/detachment/detachment_couette_${_case}.prm
    BOUND "statistics.csv:max(detached_mass_total)<1e-300"
          "statistics.csv:volume_fraction_integral>0.22916666666"
    NUMDIFF "-a 1e-10 -r 0"
    COMPARE statistics.csv:step,volume_fraction_integral,detached_mass,detached_mass_total)
endforeach()

# Detachment/Duration: the layer goes at the step whose clock first reaches
# the duration (step 3 of 0.01 for 0.025; reference checked by hand), and a
# resume after step 2 brings the clock and the total back from the checkpoint.
viscofilm_test(detachment_couette_duration MODE run RANKS 1 2
  PRM ${S}/detachment/detachment_couette_duration.prm
  BOUND "statistics.csv[step>2]:detached_mass_total>0.22916666666"
        "statistics.csv:sum(detached_mass)<0.22916666667"
  NUMDIFF "-a 1e-10 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,detached_mass,detached_mass_total)
viscofilm_test(detachment_couette_duration_restart MODE restart RANKS 1 2
  PRM ${S}/detachment/detachment_couette_duration.prm
  REFERENCE unused
  STOP_AFTER 2
  NUMDIFF "-a 1e-10 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,detached_mass,detached_mass_total)
