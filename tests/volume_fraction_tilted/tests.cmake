# φ entering through a boundary not normal to an axis (the tilted channel of
# tests/gmsh_mesh, slip walls, uniform flow along it): φ ≡ 1 once the front
# has left (min and ∫φ = 1, the channel's area, to 1e-14 from step 25 on).
# A segment along a slip wall, beyond it by round-off, used to be cut there
# (wall nodes kept φ ≈ 0.5, ∫φ = 0.937): exit faces need the tolerance.
file(READ ${S}/volume_fraction_tilted/volume_fraction_tilted.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/volume_fraction_tilted.prm "${_prm}
subsection Geometry
  set Mesh file = ${S}/gmsh_mesh/tilted_channel.msh
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${S}/volume_fraction_tilted/volume_fraction_tilted.prm)
viscofilm_test(volume_fraction_tilted MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/volume_fraction_tilted.prm
  REFERENCE ${S}/volume_fraction_tilted/volume_fraction_tilted.output
  BOUND "statistics.csv:volume_fraction_min>-1e-12" "statistics.csv:volume_fraction_max<1.000000000001"
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_min)
