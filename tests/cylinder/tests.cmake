# The confined-cylinder benchmark's short version (prm/cylinder.prm,
# benchmarks/cylinder/): the drag coefficient K = force_x_Cylinder against the
# published K (doc/verification.md): Newtonian on the middle mesh (64 cells
# around the cylinder) within 0.03 % of 132.36 (measured 132.365 with the
# quadratic mapping of the cylinder, Problem::mapping; the bilinear one gave
# 132.04, −0.24 %, and fails), and at
# Wi = 0.1 on the coarsest (32 cells), from t = 1.6 (16 relaxation times) to
# 2, within 2 % of 130.36 (measured 129.664 with the quadratic map; 128.37
# with the bilinear one, whose Newtonian error was 0.9 %).
# run_test.py copies the .prm into its work directory, so the include of
# prm/cylinder.prm is made absolute here.
foreach(_case newtonian wi0.1 wi0.1_order2 wi0.5 graded)
  file(READ ${S}/cylinder/cylinder_drag_${_case}.prm _prm)
  string(REPLACE "include ../../prm/cylinder.prm" "include ${CMAKE_SOURCE_DIR}/prm/cylinder.prm"
         _prm "${_prm}")
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_${_case}.prm "${_prm}")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
               ${S}/cylinder/cylinder_drag_${_case}.prm ${CMAKE_SOURCE_DIR}/prm/cylinder.prm)
endforeach()
viscofilm_test(cylinder_drag_newtonian MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_newtonian.prm
  REFERENCE ${S}/cylinder/cylinder_drag_newtonian.output
  NUMDIFF "-a 1e-5 -r 1e-6"
  COMPARE statistics.csv:step,force_x_Cylinder,force_y_Cylinder
  BOUND "statistics.csv[step>0]:force_x_Cylinder>132.32"
        "statistics.csv[step>0]:force_x_Cylinder<132.40")

# One mapping on curved meshes: a manufactured Stokes flow on the channel with
# a cylinder, velocity data on the cylinder too. Velocity L2 rates 3.07, 3.03,
# 3.01 and pressure 2.14, 2.04, 2.01 (levels 1 … 4); with the bilinear map in the
# boundary data and the error integrals (the quadratic one in the solve) they
# fell to 2.90, 2.60, 2.26.
viscofilm_test(stokes_mms_cylinder MODE convergence RANKS 2
  PRM ${S}/cylinder/stokes_mms_cylinder.prm
  VARY "Initial global refinement=1,2,3,4"
  MIN_RATES "velocity_l2_error=2.9,pressure_l2_error=1.9"
  NUMDIFF "-a 1e-12 -r 2e-3")

# φ = f(r) in a rigid rotation about the cylinder (steady, so the exact φ at
# every time), semi-Lagrangian, k ∝ Δx: L2 rates 2.2, 1.8 (levels 2 … 4),
# asserted ≥ 1.6; the Stokes velocity exact (2e-10, bound 1e-8; 2e-4 with the
# bilinear map in the boundary data); φ in [0, 1] to round-off. Feet that left
# through the cylinder, which the flow follows, once took its inflow value (u·n
# < 0 on the wall's quadratic image, without the curved face's tolerance of
# DepartureFeet::enters): φ = 0 instead of 1 there, L2 rate 1.04.
viscofilm_test(transport_rotation_cylinder MODE convergence RANKS 2
  PRM ${S}/cylinder/transport_rotation_cylinder.prm
  VARY "Initial global refinement=2,3,4" "Time step=0.05,0.025,0.0125"
       "Number of steps=10,20,40"
  MIN_RATES "volume_fraction_l2_error=1.6"
  BOUND "statistics.csv[step>0]:velocity_l2_error<1e-8"
        "statistics.csv:volume_fraction_min>-1e-12"
        "statistics.csv:volume_fraction_max<1.000000000001"
  NUMDIFF "-a 1e-12 -r 2e-3")

# Its snapshot after one step (level 2): the patches of every cell placed by
# the quadratic mapping, so the exact velocity holds at each written point to
# 1e-8 (the bilinear patches, on the chords, were off by 1e-3).
file(READ ${S}/cylinder/transport_rotation_cylinder.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/transport_rotation_cylinder_snapshot.prm "${_prm}
subsection Geometry
  set Initial global refinement = 2
end
subsection Time stepping
  set Time step       = 0.05
  set Number of steps = 1
end
subsection Output
  set Interval = 1
end
")
viscofilm_test(transport_rotation_cylinder_snapshot MODE fields RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/transport_rotation_cylinder_snapshot.prm
  REFERENCE unused
  TOLERANCE 1e-8
  EXACT "velocity[0]=-y" "velocity[1]=x" "pressure=0")

# Its mass at level 3 with each bounded scheme: ∫φ at the start against the
# closed form 25.3398236 (measured +3.0e-4, bound ±6e-4; the bilinear map's ∫φ
# was +5.4e-3 off), and ∫φ + outflow − inflow kept to ±1e-10 (drift 2e-12).
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             ${S}/cylinder/transport_rotation_cylinder.prm)
foreach(_scheme semi-Lagrangian FCT)
  string(TOLOWER ${_scheme} _name)
  string(REPLACE "-" "_" _name transport_rotation_cylinder_mass_${_name})
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${_name}.prm "${_prm}
subsection Geometry
  set Initial global refinement = 3
end
subsection Time stepping
  set Time step       = 0.025
  set Number of steps = 20
end
subsection Stabilization
  set Volume fraction scheme = ${_scheme}
end
")
  viscofilm_test(${_name} MODE run RANKS 2
    PRM ${CMAKE_CURRENT_BINARY_DIR}/${_name}.prm
    REFERENCE ${S}/cylinder/${_name}.output
    NUMDIFF "-a 1e-10 -r 1e-12"
    COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_min,volume_fraction_max
    BOUND "statistics.csv[step<1]:volume_fraction_integral<25.34042"
          "statistics.csv[step<1]:volume_fraction_integral>25.33922"
          "statistics.csv:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow<25.3401216004"
          "statistics.csv:volume_fraction_integral+volume_fraction_outflow-volume_fraction_inflow>25.3401216002"
          "statistics.csv:volume_fraction_min>-1e-12"
          "statistics.csv:volume_fraction_max<1.000000000001")
endforeach()

# The Newtonian drag on the cylinder against the published K = 132.358 (Alves
# et al. 2001) on three meshes: rates 3.2 and 3.8 with the quadratic mapping
# (errors 0.91, 0.099, 0.007); the bilinear map of the cylinder (a polygon)
# gave 1.67 and 1.85 and fails.
viscofilm_test(cylinder_drag_convergence MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_newtonian.prm
  REFERENCE ${S}/cylinder/cylinder_drag_convergence.output
  VARY "Initial global refinement=1,2,3"
  MIN_RATES "force_x_Cylinder@132.358=3.0"
  NUMDIFF "-a 1e-4 -r 1e-6")
viscofilm_test(cylinder_drag_wi0.1 MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_wi0.1.prm
  REFERENCE ${S}/cylinder/cylinder_drag_wi0.1.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,force_x_Cylinder,force_y_Cylinder
  BOUND "statistics.csv[step>40]:force_x_Cylinder>127.75"
        "statistics.csv[step>40]:force_x_Cylinder<132.97")

# The same at Time stepping/Order = 2 (k = 0.04, three Picard iterations a
# step, 30 steps): K within 0.2 % of the published 130.36 from t = 1 on
# (measured 130.253, −0.08 %). Order 1's steady state has an O(k/λ) error
# from its implicit relaxation: the same run at Order 1 gives 129.663
# (−0.53 %) and fails; Order 2's moves by 0.01 % from k = 0.04 to 0.02.
# Its twin on 2 threads runs the assembly's workers with the implicit η_e,
# without feet (Res = 0) and through the cylinder's quadratic mapping.
viscofilm_test(cylinder_drag_wi0.1_order2 MODE run RANKS 1 THREADS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_wi0.1_order2.prm
  REFERENCE ${S}/cylinder/cylinder_drag_wi0.1_order2.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,force_x_Cylinder,force_y_Cylinder
  BOUND "statistics.csv[step>24]:force_x_Cylinder>130.099"
        "statistics.csv[step>24]:force_x_Cylinder<130.621")

# cyl: the stress on the confined cylinder's no-slip walls (issue 11.7).
# Wi = 0.5 on the coarsest mesh to t = 3 (tests/cylinder/cylinder_drag_wi0.5.prm):
# steady Oldroyd-B shear at a wall has τ_nn = 0, here τ_yy at the cylinder's
# top and on the channel's bottom wall (measured 4e-16 and 0; the nodal mean
# ∇u, Stress/Wall velocity gradient = mean of cells, gives 22.5 and 8.2), and
# the drag K within 5 % of the published 118.83 (measured 124.60 at t = 3,
# +4.9 %, with the quadratic map; 120.20 with the bilinear one; the mean ∇u:
# 165 and climbing; level 1 has no steady state at this Wi).
viscofilm_test(cylinder_drag_wi0.5 MODE run RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_wi0.5.prm
  REFERENCE ${S}/cylinder/cylinder_drag_wi0.5.output
  NUMDIFF "-a 1e-6 -r 1e-6"
  COMPARE probes.csv:step,x,y,tau_xx,tau_xy,tau_yy
  BOUND "probes.csv[step>74]:tau_yy<1e-10" "probes.csv[step>74]:tau_yy>-1e-10"
        "statistics.csv[step>74]:force_x_Cylinder>112.89"
        "statistics.csv[step>74]:force_x_Cylinder<124.77")

# cyl3: meshes graded towards the cylinder and its wake (Geometry/Cylinder
# refinement). The Newtonian drag on the uniform level 1 refined twice near
# the cylinder (528 cells) within 0.06 % of the published K = 132.358 (Alves
# et al. 2001): measured 132.416 (+0.044 %); the uniform level 1 (216 cells)
# gives 133.268 (+0.69 %) and fails.
viscofilm_test(cylinder_drag_graded MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_graded.prm
  REFERENCE ${S}/cylinder/cylinder_drag_graded.output
  NUMDIFF "-a 1e-6 -r 1e-6"
  COMPARE statistics.csv:step,cells,force_x_Cylinder,force_y_Cylinder
  BOUND "statistics.csv[step>0]:force_x_Cylinder>132.279"
        "statistics.csv[step>0]:force_x_Cylinder<132.437")

# The same with the velocity block's geometric multigrid on 2 ranks, on the
# uniform level 2 refined once near the cylinder (1224 cells): the
# multigrid's coarse meshes copy the triangulation and its manifolds, and
# deal.II 9.4's clone of the transfinite manifold around the cylinder wrote
# past its table on this graded mesh (heap corruption: a segfault or a hang
# in the set-up before Geometry's CopyableTransfiniteManifold). The drag
# within the same band of the published K (measured 132.369, +0.009 %), the
# solve within 50 FGMRES iterations (measured 44).
file(READ ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_graded.prm _prm)
string(REGEX REPLACE "set Initial global refinement *= 1" "set Initial global refinement = 2"
       _prm "${_prm}")
string(REGEX REPLACE "set Cylinder refinement *= 2" "set Cylinder refinement = 1"
       _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_graded_gmg.prm "${_prm}
subsection Stokes solver
  subsection Preconditioner
    set Velocity preconditioner = GMG
  end
end
")
viscofilm_test(cylinder_drag_graded_gmg MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_drag_graded_gmg.prm
  REFERENCE ${S}/cylinder/cylinder_drag_graded_gmg.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,cells,force_x_Cylinder,force_y_Cylinder
  BOUND "statistics.csv[step>0]:force_x_Cylinder>132.279"
        "statistics.csv[step>0]:force_x_Cylinder<132.437"
        "statistics.csv[step>0]:stokes_iterations<50")

# A departure foot's midpoint in the sliver between a coarse cell's
# quadratic edge and its refined neighbours' (graded mesh, Wi = 0.5, step
# 14) was in no cell and stopped the run; it runs through the 15 steps and
# the lift stays zero as the channel's symmetry demands (|F_y| < 0.1, 1e-3 of F_x
# ≈ 110). Otherwise a regression check (no published value for the
# transient): on the old code the run fails at step 14.
file(READ ${S}/cylinder/cylinder_graded_feet.prm _prm)
string(REPLACE "include ../../prm/cylinder.prm" "include ${CMAKE_SOURCE_DIR}/prm/cylinder.prm"
       _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/cylinder_graded_feet.prm "${_prm}")
viscofilm_test(cylinder_graded_feet MODE run RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/cylinder_graded_feet.prm
  REFERENCE ${S}/cylinder/cylinder_graded_feet.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,cells,force_x_Cylinder
  BOUND "statistics.csv[step>0]:force_y_Cylinder<0.1"
        "statistics.csv[step>0]:force_y_Cylinder>-0.1")
