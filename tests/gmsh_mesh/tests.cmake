# A gmsh mesh (tests/gmsh_mesh/make_meshes.py): the slip channel rotated by
# atan(3/4), boundaries named by physical group or tag; slip and outflow on
# boundaries not normal to an axis. Exact in Q2-Q1.
# (run_test.py runs a copy of the .prm elsewhere: the mesh by its full path;
# bad_input_missing_type reads it relative to its .prm.)
file(READ ${S}/gmsh_mesh/gmsh_tilted_channel.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/gmsh_tilted_channel.prm "${_prm}
subsection Geometry
  set Mesh file = ${S}/gmsh_mesh/tilted_channel.msh
end
")
viscofilm_test(gmsh_tilted_channel MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/gmsh_tilted_channel.prm
  REFERENCE ${S}/gmsh_mesh/gmsh_tilted_channel.output
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE statistics.csv:step,velocity_l2_error,pressure_l2_error
          probes.csv:step,x,y,u,v,p)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${S}/gmsh_mesh/gmsh_tilted_channel.prm)

# A gmsh hexahedral mesh with named physical surfaces: the tilted slip
# channel of gmsh_tilted_channel extruded in z (slip Sides), slip and outflow
# on faces not normal to an axis. Exact in Q2-Q1.
file(READ ${S}/gmsh_mesh/gmsh_tilted_duct.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/gmsh_tilted_duct.prm "${_prm}
subsection Geometry
  set Mesh file = ${S}/gmsh_mesh/tilted_duct.msh
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/gmsh_mesh/gmsh_tilted_duct.prm)
viscofilm_test(gmsh_tilted_duct MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/gmsh_tilted_duct.prm
  REFERENCE ${S}/gmsh_mesh/gmsh_tilted_duct.output
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE statistics.csv:step,velocity_l2_error,pressure_l2_error)
