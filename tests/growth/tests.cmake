# Biomass growth (Growth, doc/model.md "Growth").
#
# Uniform biomass in a closed box with S ≫ K_S (Expansion = none): ∫φ = ∫φ0
# e^{(μmax − b)t} at t = 1, errors 3.3e-3, 1.7e-3, 8.8e-4 for k = 0.1, 0.05,
# 0.025 (forward Euler: rates 0.95, 0.98). The balance ∫φ − ∫φ0 = produced −
# decayed and produced = Y/ρX × consumed (Y/ρX = 2) to round-off.
viscofilm_test(growth_exponential MODE convergence RANKS 2
  PRM ${S}/growth/growth_exponential.prm
  VARY "Time step=0.1,0.05,0.025" "Number of steps=10,20,40"
  MIN_RATES "volume_fraction_integral@0.1112770464246234=0.9"
  BOUND "statistics.csv:volume_fraction_integral-biomass_produced+biomass_decayed<0.05000000000001"
        "statistics.csv:volume_fraction_integral-biomass_produced+biomass_decayed>0.04999999999999"
        "statistics.csv:biomass_produced-substrate_consumed-substrate_consumed<1e-15"
        "statistics.csv:biomass_produced-substrate_consumed-substrate_consumed>-1e-15"
        "statistics.csv:biomass_unplaced<1e-15"
        "statistics.csv:biomass_unplaced>-1e-15")
# A flat layer pushed up by its own growth (Expansion = flow): the velocity
# against v = g min(y, L0 e^{gt}) at t = 0.5, errors 1.0e-2, 5.1e-3 (rate 0.95
# in h and k together; Expansion = none: 0.18, no flow), φ against the layer
# of height L0 e^{gt}, errors at most 2.0e-2, 1.4e-2 (none: 0.10). φ <= φmax;
# what the fronts took, at most 1.3e-4 and 3.1e-5 a step of 2e-3 grown (the
# first step, from the sharp initial front, leaves 4e-5 and 7e-6 unplaced).
# The thickness on the bottom: the layer's height L0 e^{gt} = 0.412 at t =
# 0.5 (measured 0.407 and 0.409, the initial interpolant's 1–2 % low), the
# same in every column (max = mean, roughness 1e-12 and 6e-14).
viscofilm_test(growth_layer MODE convergence RANKS 2
  PRM ${S}/growth/growth_layer.prm
  VARY "Initial global refinement=3,4" "Time step=0.05,0.025" "Number of steps=10,20"
  MIN_RATES "velocity_l2_error=0.85"
  BOUND "statistics.csv[step>0]:velocity_l2_error<0.0105"
        "statistics.csv[step>0]:volume_fraction_l2_error<0.021"
        "statistics.csv:volume_fraction_max<0.500000000001"
        "statistics.csv:volume_fraction_min>-1e-15"
        "statistics.csv[step>0]:biomass_relocated<1.6e-4"
        "statistics.csv[step>0]:biomass_relocated>-1.6e-4"
        "statistics.csv[time>0.49]:biofilm_thickness_mean>0.395"
        "statistics.csv[time>0.49]:biofilm_thickness_mean<0.425"
        "statistics.csv:biofilm_thickness_max-biofilm_thickness_mean<1e-12"
        "statistics.csv:biofilm_thickness_roughness<1e-11")
# The thesis' bulb (φ = φmax = 0.1) in its channel flow on an adapted mesh,
# S ≫ K_S: whatever the flow and the expansion do, ∫φ = ∫φ0 e^{(μmax − b)t},
# measured +1.5e-5 relative at t = 0.021875 (bound ±3e-5: forward Euler's
# error is −2.2e-5; the growth counts the biomass ∫ψ_i φ of S's nodes clipped
# at 0, not the Q2 φ's undershoots at the sharp front). The balance ∫φ − ∫φ0
# = produced − decayed − outflow + inflow to round-off (measured 1e-17),
# 0 <= φ <= φmax. The columns against 1 and 2 ranks' own run (regression).
set(_growth_bulb "
subsection Substrate
  set Enable              = true
  set Diffusivity         = 1e-2
  set Maximum growth rate = 1
  set Half saturation     = 1e-6
  set Yield               = 0.5
  set Biomass density     = 1
  set Initial value       = 1
  set Fixed values        = Inlet: 1
end
subsection Growth
  set Enable                  = true
  set Decay rate              = 0.2
  set Maximum volume fraction = 0.1
end
")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/growth_bulb_amr.prm "${_prm_bulb_amr}${_growth_bulb}")
viscofilm_test(growth_bulb_amr MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/growth_bulb_amr.prm
  REFERENCE ${S}/growth/growth_bulb_amr.output
  COMPARE statistics.csv:step,volume_fraction_integral,biomass_produced,biomass_decayed,substrate_consumed
  BOUND "statistics.csv[step>6]:volume_fraction_integral>0.004241478125739114"
        "statistics.csv[step>6]:volume_fraction_integral<0.004241732622061549"
        "statistics.csv:volume_fraction_integral-biomass_produced+biomass_decayed+volume_fraction_outflow-volume_fraction_inflow<0.004168023003473149"
        "statistics.csv:volume_fraction_integral-biomass_produced+biomass_decayed+volume_fraction_outflow-volume_fraction_inflow>0.00416802300347115"
        "statistics.csv:volume_fraction_max<0.100000000001"
        "statistics.csv[step>0]:volume_fraction_min>-1e-15"
        "statistics.csv:biomass_unplaced<1e-15"
        "statistics.csv:biomass_unplaced>-1e-15"
  NUMDIFF "-a 1e-14 -r 1e-8")
# The same stopped after step 4 (its last checkpoint) and resumed: φ and the
# growth's totals (the checkpoint's state) equal the uninterrupted run's.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/growth_restart.prm "${_prm_bulb_amr}${_growth_bulb}
subsection Checkpointing
  set Interval = 2
end
")
viscofilm_test(growth_restart MODE restart RANKS 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/growth_restart.prm
  REFERENCE unused
  NUMDIFF "-a 1e-14 -r 1e-8"
  COMPARE statistics.csv:step,time,volume_fraction_integral,biomass_produced,biomass_decayed,substrate_consumed)
