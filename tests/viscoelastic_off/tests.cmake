# Model/Viscoelastic = false: an initial stress that would drive a flow
# drives none; the Newtonian Poiseuille answer, τ = 0 in probes and loads
# (reference written by hand from the exact solution; c = ηp/(a Wi) I = 1.5 I).
viscofilm_test(viscoelastic_off MODE run RANKS 1 2
  PRM ${S}/viscoelastic_off/viscoelastic_off.prm
  BOUND "statistics.csv:min_conformation_eigenvalue>1.4999"
        "statistics.csv:min_conformation_eigenvalue<1.5001"
  NUMDIFF "-a 1e-8 -r 0"
  COMPARE statistics.csv:step,velocity_l2_error,pressure_l2_error,wall_shear_stress_mean
          probes.csv:step,x,y,u,v,p,tau_xx,tau_xy,tau_yy)
