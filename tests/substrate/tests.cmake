# The substrate (Substrate, doc/model.md "Substrate") in a flat biofilm on a
# wall against closed forms, in balance with no flow: the uptake through the
# biofilm's top, measured rates 2.00 from Δx = L/8 to L/64 (errors 7.4e-3,
# 1.9e-3, 4.6e-4, 1.2e-4). Balance (inflow = consumed) to 2e-13 of the uptake.
viscofilm_test(substrate_first_order MODE convergence RANKS 2
  PRM ${S}/substrate/substrate_first_order.prm
  VARY "Initial global refinement=3,4,5,6"
  MIN_RATES "substrate_inflow_rate@1.5424441281213e-12=1.95"
  BOUND "statistics.csv:substrate_inflow-substrate_outflow-substrate_consumed<2e-24"
        "statistics.csv:substrate_inflow-substrate_outflow-substrate_consumed>-2e-24"
        "statistics.csv[step>0]:substrate_min>0"
        "statistics.csv:substrate_max<1.000000000001e-3"
  NUMDIFF "-a 1e-20 -r 1e-6")
# Monod kinetics with K_S ≪ S_s in a deep biofilm: J = √(2 D_b q (S_s − K_S
# ln(1 + S_s/K_S))) (zero order as K_S → 0), measured rates 1.90, 2.00, 2.00
# (errors 2.6e-3 … 4.3e-5).
viscofilm_test(substrate_zero_order MODE convergence RANKS 1
  PRM ${S}/substrate/substrate_zero_order.prm
  VARY "Initial global refinement=3,4,5,6"
  MIN_RATES "substrate_inflow_rate@3.1252858523782197e-12=1.85"
  BOUND "statistics.csv:substrate_inflow-substrate_outflow-substrate_consumed<2e-24"
        "statistics.csv:substrate_inflow-substrate_outflow-substrate_consumed>-2e-24"
        "statistics.csv[step>0]:substrate_min>0"
  NUMDIFF "-a 1e-20 -r 1e-6")
# The thesis' bulb in its channel flow on an adapted mesh (a refinement at
# step 3), S = 0.5 at t = 0 and 1 at the inlet, carried in and consumed: the
# balance amount(t) − amount(0) = inflow − outflow − consumed + remeshed to
# round-off (measured 6e-16 of the amount), 0 <= S <= 1. The columns against
# 1 and 2 ranks' own run (regression).
set(_substrate_bulb "
subsection Substrate
  set Enable              = true
  set Diffusivity         = 1e-2
  set Maximum growth rate = 1
  set Half saturation     = 0.5
  set Yield               = 0.5
  set Biomass density     = 1
  set Initial value       = 0.5
  set Fixed values        = Inlet: 1
end
")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/substrate_bulb_amr.prm "${_prm_bulb_amr}${_substrate_bulb}")
viscofilm_test(substrate_bulb_amr MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/substrate_bulb_amr.prm
  REFERENCE ${S}/substrate/substrate_bulb_amr.output
  COMPARE statistics.csv:step,substrate_amount,substrate_inflow,substrate_consumed,substrate_remeshed,substrate_min,substrate_max
  BOUND "statistics.csv:substrate_amount-substrate_inflow+substrate_outflow+substrate_consumed-substrate_remeshed<0.515625000001"
        "statistics.csv:substrate_amount-substrate_inflow+substrate_outflow+substrate_consumed-substrate_remeshed>0.515624999999"
        "statistics.csv:substrate_min>-1e-14"
        "statistics.csv:substrate_max<1.000000000001"
  NUMDIFF "-a 1e-14 -r 1e-8")
# A front entering S = 0 on the adapted bulb (refined at steps 3 and 6): S
# >= 0 behind the refinement edges (measured 0 to 1e-24 at step 7; with the
# mass condensed per cell onto the hanging nodes' masters −4e-4) and the
# balance (6e-16).
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/substrate_front_amr.prm "${_prm_bulb_amr}${_substrate_bulb}
subsection Substrate
  set Initial value = 0
end
")
viscofilm_test(substrate_front_amr MODE run RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/substrate_front_amr.prm
  REFERENCE ${S}/substrate/substrate_front_amr.output
  COMPARE statistics.csv:step,substrate_amount,substrate_inflow,substrate_remeshed
  BOUND "statistics.csv:substrate_min>-1e-15"
        "statistics.csv:substrate_max<1.000000000001"
  NUMDIFF "-a 1e-14 -r 1e-8")
# The same stopped after step 4 (its last checkpoint) and resumed: S and its
# totals (the checkpoint's state) equal the uninterrupted run's.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/substrate_restart.prm "${_prm_bulb_amr}${_substrate_bulb}
subsection Checkpointing
  set Interval = 2
end
")
viscofilm_test(substrate_restart MODE restart RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/substrate_restart.prm
  REFERENCE unused
  NUMDIFF "-a 1e-14 -r 1e-8"
  COMPARE statistics.csv:step,time,substrate_amount,substrate_inflow,substrate_outflow,substrate_consumed,substrate_remeshed,substrate_min,substrate_max)
# 3D: the flat first-order biofilm as a slab (φ = 1, L × L × L), S_s on the
# top, no flow: the same closed form, uptake through a top of area L²:
# 1.5424441281213e-16.
file(READ ${S}/substrate/substrate_first_order.prm _prm)
string(REPLACE "set Lower left corner         = 0, 0" "set Dimension = 3
  set Lower left corner         = 0, 0, 0" _prm "${_prm}")
string(REPLACE "set Upper right corner        = 1e-4, 1e-4" "set Upper right corner        = 1e-4, 1e-4, 1e-4" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/substrate_first_order_3d.prm "${_prm}")
viscofilm_test(substrate_first_order_3d MODE convergence RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/substrate_first_order_3d.prm
  REFERENCE ${S}/substrate/substrate_first_order_3d.output
  VARY "Initial global refinement=1,2,3"
  MIN_RATES "substrate_inflow_rate@1.5424441281213e-16=1.9"
  BOUND "statistics.csv[step>0]:substrate_min>0"
  NUMDIFF "-a 1e-24 -r 1e-6")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${S}/substrate/substrate_first_order.prm)
