# The channel with a cylinder in 3D (axis along z), slip Front and Back: the
# extruded mesh holds the 2D mesh in every plane z = const, so the creeping
# flow equals the 2D run's (tests/boundary_types/cylinder.output:
# max_velocity 2.93375422498, both with the quadratic mapping of the
# cylinder), on 1 and 2 ranks.
viscofilm_test(cylinder_3d MODE run RANKS 1 2
  PRM ${S}/cylinder_3d/cylinder_3d.prm
  NUMDIFF "-a 1e-8 -r 1e-8"
  COMPARE statistics.csv:step,max_velocity)
