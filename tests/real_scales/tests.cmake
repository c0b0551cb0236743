# Real scales: the start of DFG 2D-1 in SI (water, Re = 20; ρ/k dominates
# η/h² on the cylinder's cells) and its dimensionless twin. The 1/η
# pressure mass matrix alone is no Schur complement there (FGMRES did not
# converge in 1100 iterations); with Cahouet & Chabard's M_{1/η}^{-1} +
# (ρ/k) L_p^{-1} it takes 82, 63, 55 iterations. Both references hold the
# direct solver's (KLU) SI answer, converted to the twin's units by hand
# (u / 0.2 m/s, F / 2e-4 N/m): the same answer to the solver tolerance. With
# the pressure scaled by ηs/L the twins take the same iterations, which both
# references record (without it 74, 67, 57 and 82, 63, 55).
foreach(_case si dimensionless)
  viscofilm_test(dfg_${_case}_startup MODE run RANKS 2
    PRM ${S}/real_scales/dfg_${_case}_startup.prm
    NUMDIFF "-a 1e-9 -r 1e-6"
    COMPARE statistics.csv:step,stokes_iterations,max_velocity,force_x_Cylinder,force_y_Cylinder)
endforeach()

# The same start at Order 2 with k = 0.2 s (CFL 2.3): on 2 ranks a Newton
# iterate of a foot beyond the bottom wall, whose walk left the rank's cells
# before it reached the wall, lay in no cell and stopped the run at step 3
# (1 rank cuts it at the wall). Both now take the point of its segment at
# the wall; a regression check, 2 ranks against 1 rank's run.
file(READ ${S}/real_scales/dfg_si_startup.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/dfg_order2_cfl2.prm "${_prm}
subsection Time stepping
  set Order           = 2
  set Time step       = 0.2
  set Number of steps = 5
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/real_scales/dfg_si_startup.prm)
viscofilm_test(dfg_order2_cfl2 MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/dfg_order2_cfl2.prm
  REFERENCE ${S}/real_scales/dfg_order2_cfl2.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,max_velocity,force_x_Cylinder,force_y_Cylinder)

# DFG 2D-1 against the published steady drag (John 2004): c_D =
# 5.57953523384 (F_x = c_D ρŪ²D/2 = 0.0111591 N/m). Measured at level 3,
# k = 0.05 s: c_D +0.63 % at t = 4.5 s (+0.54 % before the consistent force
# took the inertia in; +0.53 % at t = 15 s then, Δp −0.13 %,
# benchmarks/dfg); band ±0.7 %, at that accuracy. The lift is no check here:
# not converged on this mesh (−4.5 % at t = 15 s) and still moving by 1.5 %
# a step at t = 4.5 s (a regression column only). The semi-Lagrangian
# momentum step's steady state depends on k (doc/verification.md, "DFG
# 2D-1"): at k = 0.1 s c_D is +6.6 %. Level 3
# (22k Stokes dofs), Order 2, 90 steps to t = 4.5 s, where the drag is
# within 1e-4 of its value at t = 15 s.
file(READ ${S}/real_scales/dfg_si_startup.prm _prm)
set(_prm_dfg_2d1 "${_prm}
subsection Geometry
  set Initial global refinement = 3
end
subsection Time stepping
  set Order           = 2
  set Time step       = 0.05
  set Number of steps = 90
end
subsection Stokes solver
  set Tolerance = 1e-8
end
")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/dfg_2d1.prm "${_prm_dfg_2d1}")
viscofilm_test(dfg_2d1 MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/dfg_2d1.prm
  REFERENCE ${S}/real_scales/dfg_2d1.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,max_velocity,force_x_Cylinder,force_y_Cylinder
  BOUND "statistics.csv[step>89]:force_x_Cylinder>0.0110810"
        "statistics.csv[step>89]:force_x_Cylinder<0.0112372")

# DFG 2D-1 with Momentum convection = Eulerian (implicit (u*·∇)u, BDF2): its
# steady state does not depend on k, so a step of 0.2 s (CFL 4.6), at which
# the semi-Lagrangian drag is 25 % high (doc/verification.md), gives the
# level-3 mesh's drag: c_D within 1 % of the published 5.57953523384
# (measured −0.81 %; −0.06 % on level 4). The lift is not converged at this
# step (it oscillates) and is not compared.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/dfg_2d1_eulerian.prm "${_prm_dfg_2d1}
subsection Time stepping
  set Time step       = 0.2
  set Number of steps = 30
end
subsection Stokes solver
  set Method              = direct
  set Momentum convection = Eulerian
end
")
viscofilm_test(dfg_2d1_eulerian MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/dfg_2d1_eulerian.prm
  REFERENCE ${S}/real_scales/dfg_2d1_eulerian.output
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,max_velocity,force_x_Cylinder
  BOUND "statistics.csv[step>27]:force_x_Cylinder>0.0110475"
        "statistics.csv[step>27]:force_x_Cylinder<0.0112706")

# prm/examples/channel-biofilm-si.prm (water and a measured biofilm rheology
# in SI: a viscosity ratio of 1.08e6) with the default Stokes solver/Method
# (auto), 6 steps: auto picks the direct solver (no Krylov iterations,
# bound), and the run goes on where the block preconditioner stops at step 1
# (its velocity CG does not converge; the default before auto). Regression
# check of the answer; `bulb_short_direct_mumps` checks MUMPS against the
# iterative solve.
file(READ ${CMAKE_SOURCE_DIR}/prm/examples/channel-biofilm-si.prm _prm)
string(REGEX REPLACE "set Number of steps *= *[0-9]+" "set Number of steps = 6" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/channel_biofilm_si_auto.prm "${_prm}
subsection Output
  set Interval = 0
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${CMAKE_SOURCE_DIR}/prm/examples/channel-biofilm-si.prm)
viscofilm_test(channel_biofilm_si_auto MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/channel_biofilm_si_auto.prm
  REFERENCE ${S}/real_scales/channel_biofilm_si_auto.output
  BOUND "statistics.csv:max(stokes_iterations)<0.5" "statistics.csv:max(step)>5.5"
  NUMDIFF "-a 1e-12 -r 1e-6"
  COMPARE statistics.csv:step,time,stokes_iterations,max_velocity,volume_fraction_integral)
# The same example with the block preconditioner (AMG on this mesh), 3 steps,
# against the direct solver's answer: the reference holds
# channel_biofilm_si_auto's MUMPS values (not blessed from this run; measured
# 2.6e-9 apart in max|u|, 1.2e-7 in the von Mises maximum). The interface
# solve makes it converge at this viscosity ratio of 1.08e6 (measured
# 114–262 outer iterations a step); without it the velocity block's inner CG
# does not converge at step 1 and the run stops.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/channel_biofilm_si_iterative.prm "${_prm}
subsection Time stepping
  set Number of steps = 3
end
subsection Stokes solver
  set Method = block preconditioned
end
subsection Output
  set Interval = 0
end
")
viscofilm_test(channel_biofilm_si_iterative MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/channel_biofilm_si_iterative.prm
  REFERENCE ${S}/real_scales/channel_biofilm_si_iterative.output
  BOUND "statistics.csv:max(stokes_iterations)<400" "statistics.csv:max(step)>2.5"
  NUMDIFF "-a 1e-12 -r 1e-6"
  COMPARE statistics.csv:step,time,max_velocity,von_mises_max,min_conformation_eigenvalue)
# A diffusion-dominated φ step (k D/Δx² = 6.4e4): ILU stalls, AMG takes over
# (1000 + 2 iterations, then 3 a step); φ = 1 stays 1 to 1e-9.
viscofilm_test(volume_fraction_stiff_diffusion MODE run RANKS 1 2
  PRM ${S}/real_scales/volume_fraction_stiff_diffusion.prm
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE statistics.csv:step,volume_fraction_min,volume_fraction_max
  BOUND "statistics.csv:volume_fraction_min>0.999999999"
        "statistics.csv:volume_fraction_max<1.000000001")
# The substrate at real scales (prm/examples/channel-biofilm-substrate.prm,
# 20 steps of 0.5 s): acetate at 0.03 kg/m³ in the water everywhere and at the
# inlet, consumed inside the bulb; S must stay in [0, 0.03] (the maximum
# principle; measured 0.03 + 4e-17) and its balance must close (measured
# 4e-15 of the amount). Q1 on the Q2 nodes' sub-cells, against whose
# functions Taylor–Hood's u is not divergence-free, reached 0.0313 and fails.
file(READ ${CMAKE_SOURCE_DIR}/prm/examples/channel-biofilm-si.prm _prm)
string(REGEX REPLACE "set Number of steps *= *[0-9]+" "set Number of steps = 20" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/channel_biofilm_substrate.prm "${_prm}
subsection Substrate
  set Enable        = true
  set Initial value = 0.03
  set Fixed values  = Inlet: 0.03
end
subsection Output
  set Interval = 0
end
")
viscofilm_test(channel_biofilm_substrate MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/channel_biofilm_substrate.prm
  REFERENCE ${S}/real_scales/channel_biofilm_substrate.output
  BOUND "statistics.csv:substrate_max<0.03000000000001"
        "statistics.csv:substrate_min>0"
        "statistics.csv:substrate_amount-substrate_inflow+substrate_outflow+substrate_consumed-substrate_remeshed<3.00000000001e-6"
        "statistics.csv:substrate_amount-substrate_inflow+substrate_outflow+substrate_consumed-substrate_remeshed>2.99999999999e-6"
  NUMDIFF "-a 1e-16 -r 1e-6"
  COMPARE statistics.csv:step,substrate_amount,substrate_consumed,substrate_min,substrate_max)
# Steps far beyond the bounded transport's reach: a viscous flat patch (1 mm ×
# 6 mm, φ = 1) in the SI channel at k = 900 s (CFL 500 in the water). The
# semi-Lagrangian step makes more biofilm where the sheared water's feet land
# in the patch than its mass fixer has room to remove at the fronts (∫φ +36 %
# in 2 hours): the run must say so. statistics.csv's
# volume_fraction_mass_defect is −2.79e-8 (of ∫φ = 6.1e-6) at step 2, and the
# run warns. With the defect not recorded: 0 (fails). Two steps only: the
# later ones amplify run-to-run round-off differences on 2 ranks (step 4's
# defect −2.1e-7 to −1.36e-6 over six runs; step 2's agreed to 8e-7 relative).
file(READ ${CMAKE_SOURCE_DIR}/prm/examples/channel-biofilm-si.prm _prm)
string(REGEX REPLACE "set Number of steps *= *[0-9]+" "set Number of steps = 2" _prm "${_prm}")
string(REGEX REPLACE "set Time step *= *[0-9.]+" "set Time step = 900" _prm "${_prm}")
string(REGEX REPLACE "set Volume fraction = if[^\n]*" "set Volume fraction = if(x > 2e-3 & x < 8e-3 & y < 1e-3, 1, 0)" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/phi_balance_long_steps.prm "${_prm}
subsection Model
  set Viscoelastic = false
end
subsection Output
  set Interval = 0
end
")
viscofilm_test(phi_balance_long_steps MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/phi_balance_long_steps.prm
  REFERENCE ${S}/real_scales/phi_balance_long_steps.output
  BOUND "statistics.csv[step>1]:volume_fraction_mass_defect<-1e-8"
  NUMDIFF "-a 1e-16 -r 1e-5"
  COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_mass_defect)
