# order2: the bulb's probe stresses second order in k (issue 13 item 2).
# prm/thesis.prm (Δx = 1/32) to t = 0.125 at Order 2 with fixed steps
# k = T/4 … T/32. No closed form: the "error" of each k is the largest
# difference of the five probes' τ_xx, τ_xy, τ_yy from the run at k/2
# (Richardson), whose rate is the scheme's order. 2.00, 2.00; before φ and
# η(φ) were advanced inside the Picard loop (η(φ^n) in the step's Stokes
# matrix) 2.06, 0.95.
file(READ ${CMAKE_SOURCE_DIR}/prm/thesis.prm _prm)
string(REGEX REPLACE "set Interval += [0-9]+" "set Interval = 0" _prm "${_prm}")
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/bulb_time_order.prm "${_prm}
subsection Time stepping
  set Order           = 2
  set Tolerance       = 0
  set CFL number      = 0
  set Time step       = 0.03125
  set Number of steps = 4
end
")
viscofilm_test(bulb_time_order MODE convergence RANKS 1 DIFFERENCES
  PRM ${CMAKE_CURRENT_BINARY_DIR}/bulb_time_order.prm
  REFERENCE ${S}/bulb_time_order/bulb_time_order.output
  VARY "Time step=0.03125,0.015625,0.0078125,0.00390625" "Number of steps=4,8,16,32"
  MIN_RATES "probes.csv:tau_xx+tau_xy+tau_yy=1.8"
  NUMDIFF "-a 1e-6 -r 2e-2")
