# Start-up of simple shear against the analytic τ(t), Oldroyd-B and
# Johnson-Segalman a = 0.5: the stress update is first order in k.
foreach(_case shear_startup shear_startup_js)
  viscofilm_test(${_case} MODE convergence RANKS 1
    PRM ${S}/shear_startup/${_case}.prm
    VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
    MIN_RATES "stress_l2_error=0.95"
    BOUND "statistics.csv:min_conformation_eigenvalue>0"
    NUMDIFF "-a 1e-12 -r 1e-6")
endforeach()

# Model/Mixture = modulus (G = ηp/(aλ) and λ linear in φ): two phases at a
# uniform φ = 0.5 whose mixture is the fluid of an existing test, so each
# must meet that test's closed form at its rates and its reference (to
# round-off; _stiff to its Picard tolerance). Mixed as `viscosity` (ηp and λ
# linear) each is another fluid, and its errors stop falling.
# shear_startup_modulus: water ηp = 0.25, λ = 0.25 (G = 1), biofilm ηp =
#   2.25, λ = 0.75 (G = 3) -> G = 2, λ = 0.5, shear_startup's (viscosity:
#   G = 1.25/0.5 = 2.5). ηs = 3 as the thesis mixture's s/η(φ) = 0.5/1.5: the
#   flow answers the discrete stress error alike (with ηs = 1 the errors
#   are 0.5 % smaller).
# channel_startup_modulus: Newtonian water (ηs = 0.39), biofilm ηs = 0.79,
#   ηp = 1.64, λ = 1 (G = 1.64) -> ηs = 0.59, G = 0.82, λ = 0.5, ηp = Gλ =
#   0.41, channel_startup_mixed's (viscosity: ηp = 0.82).
# channel_startup_stiff_modulus: Newtonian water, biofilm ηp = 4, λ = 1, ηs
#   = 0.01 in both -> ηp = 1, λ = 0.5, channel_startup_stiff's (viscosity:
#   ηp = 2), with the implicit elastic viscosity of the mixed G.
# shear_startup_geometric (Mixture = geometric: G linear, λ = λw^(1−φ) λb^φ):
#   water ηp = 0.25, λ = 0.25 (G = 1), biofilm ηp = 3, λ = 1 (G = 3) -> G =
#   2, λ = 0.5, shear_startup's again (modulus: λ = 0.625).
file(READ ${S}/shear_startup/shear_startup.prm _shear_prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/shear_startup_geometric.prm "${_shear_prm}
subsection Model
  set Rheology = phases
  set Mixture  = geometric
  subsection Water
    set Solvent viscosity = 3
    set Polymer viscosity = 0.25
    set Relaxation time   = 0.25
  end
  subsection Biofilm
    set Solvent viscosity = 3
    set Polymer viscosity = 3
    set Relaxation time   = 1
  end
end
")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/shear_startup_modulus.prm "${_shear_prm}
subsection Model
  set Rheology = phases
  set Mixture  = modulus
  subsection Water
    set Solvent viscosity = 3
    set Polymer viscosity = 0.25
    set Relaxation time   = 0.25
  end
  subsection Biofilm
    set Solvent viscosity = 3
    set Polymer viscosity = 2.25
    set Relaxation time   = 0.75
  end
end
")
file(READ ${S}/rheology/channel_startup_mixed.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/channel_startup_modulus.prm "${_prm}
subsection Model
  set Mixture = modulus
  subsection Biofilm
    set Polymer viscosity = 1.64
  end
end
")
file(READ ${S}/rheology/channel_startup_stiff.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/channel_startup_stiff_modulus.prm "${_prm}
subsection Model
  set Mixture = modulus
  subsection Water
    set Polymer viscosity = 0
    set Relaxation time   = 0
  end
  subsection Biofilm
    set Solvent viscosity = 0.01
    set Polymer viscosity = 4
    set Relaxation time   = 1
  end
end
subsection Initial conditions
  set Volume fraction = 0.5
end
subsection Boundary conditions
  subsection Inlet
    set Volume fraction = 0.5
  end
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             ${S}/shear_startup/shear_startup.prm
             ${S}/rheology/channel_startup_mixed.prm
             ${S}/rheology/channel_startup_stiff.prm)
foreach(_mixture modulus geometric)
  viscofilm_test(shear_startup_${_mixture} MODE convergence RANKS 1
    PRM ${CMAKE_CURRENT_BINARY_DIR}/shear_startup_${_mixture}.prm
    REFERENCE ${S}/shear_startup/shear_startup.output
    VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
    MIN_RATES "stress_l2_error=0.95"
    BOUND "statistics.csv:min_conformation_eigenvalue>0"
    NUMDIFF "-a 1e-12 -r 1e-6")
endforeach()
viscofilm_test(channel_startup_modulus MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/channel_startup_modulus.prm
  REFERENCE ${S}/rheology/channel_startup_mixed.output
  VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
  MIN_RATES "pressure_l2_error=0.95,stress_l2_error=0.95"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-12 -r 1e-6")
viscofilm_test(channel_startup_stiff_modulus MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/channel_startup_stiff_modulus.prm
  REFERENCE ${S}/rheology/channel_startup_stiff.output
  VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
  MIN_RATES "pressure_l2_error=0.9,stress_l2_error=0.9"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
        "statistics.csv:picard_converged>0.5"
  NUMDIFF "-a 1e-12 -r 1e-6")

foreach(_case shear_startup shear_startup_js)
  viscofilm_order2_prm(${_case}_order2 ${S}/shear_startup/${_case}.prm)
  viscofilm_test(${_case}_order2 MODE convergence RANKS 1
    PRM ${CMAKE_CURRENT_BINARY_DIR}/${_case}_order2.prm
    REFERENCE ${S}/shear_startup/${_case}_order2.output
    VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
    MIN_RATES "stress_l2_error=1.9"
    BOUND "statistics.csv:min_conformation_eigenvalue>0"
    NUMDIFF "-a 1e-12 -r 1e-6")
endforeach()

# Issue 13, the bulb's Order 1/Order 2 limits (helper bulb)
# Start-up of shear in the thesis mixture's stiff regime (φ = 0.002: λ = Wi φ
# = 0.002, μk = 50 … 6.25), against the closed form, at both orders: both
# updates converge where relaxation is stiff (Order 1 at rate 1.00; Order 2
# at 1.06, 1.13, 1.30, pre-asymptotic until μk < 1, as a model of the two
# formulas predicts), so neither is inconsistent there (doc/numerics-transport.md,
# "The bulb's two limits").
viscofilm_test(shear_startup_stiff MODE convergence RANKS 1
  PRM ${S}/shear_startup/shear_startup_stiff.prm
  VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
  MIN_RATES "stress_l2_error=0.95"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-12 -r 1e-6")
viscofilm_order2_prm(shear_startup_stiff_order2 ${S}/shear_startup/shear_startup_stiff.prm)
viscofilm_test(shear_startup_stiff_order2 MODE convergence RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/shear_startup_stiff_order2.prm
  REFERENCE ${S}/shear_startup/shear_startup_stiff_order2.output
  VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
  MIN_RATES "stress_l2_error=1.0"
  BOUND "statistics.csv:min_conformation_eigenvalue>0"
  NUMDIFF "-a 1e-12 -r 1e-6")
