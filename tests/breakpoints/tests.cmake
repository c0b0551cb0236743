# tta: Time stepping/Breakpoints (issue 13 item 5). Poiseuille flow whose
# inflow peaks (a kink of r(t)) at t = 0.3, k = 0.25: the steps land on
# 0.3 (0.15, 0.3, 0.55, 0.8, 1) and max|u| reaches the exact peak 1 there
# (the flow is Q2-exact: velocity and pressure errors at solver
# tolerance). Without breakpoints the steps end at 0.25, 0.5, ... and the
# peak of max|u| is 0.8333.
viscofilm_test(breakpoints MODE run RANKS 1
  PRM ${S}/breakpoints/breakpoints.prm
  BOUND "statistics.csv:max(max_velocity)>0.9999999999"
        "statistics.csv:max(max_velocity)<1.0000000001"
        "statistics.csv[step>0]:velocity_l2_error<1e-9"
  NUMDIFF "-a 1e-9 -r 0"
  COMPARE statistics.csv:step,time,time_step,max_velocity,velocity_l2_error)
