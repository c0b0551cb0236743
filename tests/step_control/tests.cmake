# Issue 13 item 3: error-controlled steps (Tolerance = 1e-3, Order = 2) on a
# uniform flow carrying a blob (closed forms in the .prm files). Start-up to
# steady flow: short steps while U' is large (< 0.012 up to t = 0.05), the
# full Time step = 0.1 once steady (t > 0.65); every accepted estimate within
# the tolerance; the error at t = 1 below it (4.7e-4; the fixed k = 0.01 run
# of the same scheme is space-limited alike).
viscofilm_test(step_control_startup MODE run RANKS 1
  PRM ${S}/step_control/step_control_startup.prm
  BOUND "statistics.csv[time<0.05]:time_step<0.012"
        "statistics.csv[time>0.65]:time_step>0.09"
        "statistics.csv:error_estimate<1e-3"
        "statistics.csv:volume_fraction_l2_error<1e-3"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,time_step,error_estimate,rejected_steps,volume_fraction_l2_error)

# A sudden change (U = 0.2 → 0.6 at t = 0.3): the steps across it are
# rejected (7 rejections) until one of 1e-3 is within the tolerance; the
# error at t = 0.6 is 3.2e-4, where fixed steps k = 0.05 give 3.1e-3
# (Order 2) and 1.2e-2 (Order 1).
viscofilm_test(step_control_jump MODE run RANKS 1 2
  PRM ${S}/step_control/step_control_jump.prm
  BOUND "statistics.csv:sum(rejected_steps)>0"
        "statistics.csv:error_estimate<1e-3"
        "statistics.csv[time>0.599]:volume_fraction_l2_error<1e-3"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,time_step,error_estimate,rejected_steps,volume_fraction_l2_error)

# Both with FCT, whose estimate is the step with u^{n+1} in every stage
# against the usual one: 33 steps and 1 rejection (start-up, the full Time
# step from t = 0.66 but for the last, to t = 1), 25 steps and 8
# rejections (jump). FCT's error is its space error (the limiter clips the
# blob's peak: 6.8e-3 and 4.6e-3), so the time error is measured against
# fixed steps of 0.0025: 6.766e-3 at t = 1 and 4.566e-3 at t = 0.6; the
# controlled runs are within 1e-5 of them (bound 1e-4), where the fixed steps
# of Time step (0.1 and 0.05, uncontrolled) are 4.9e-4 and 3.0e-3 off.
foreach(_case startup jump)
  file(READ ${S}/step_control/step_control_${_case}.prm _prm)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/step_control_${_case}_fct.prm "${_prm}
subsection Stabilization
  set Volume fraction scheme = FCT
end
")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
    ${S}/step_control/step_control_${_case}.prm)
endforeach()
viscofilm_test(step_control_startup_fct MODE run RANKS 1
  PRM ${CMAKE_CURRENT_BINARY_DIR}/step_control_startup_fct.prm
  REFERENCE ${S}/step_control/step_control_startup_fct.output
  BOUND "statistics.csv[time<0.05]:time_step<0.012"
        "statistics.csv[time>0.65]:max(time_step)>0.09"
        "statistics.csv:error_estimate<1e-3"
        "statistics.csv[time>0.999]:volume_fraction_l2_error>0.006666"
        "statistics.csv[time>0.999]:volume_fraction_l2_error<0.006866"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,time_step,error_estimate,rejected_steps,volume_fraction_l2_error)
viscofilm_test(step_control_jump_fct MODE run RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/step_control_jump_fct.prm
  REFERENCE ${S}/step_control/step_control_jump_fct.output
  BOUND "statistics.csv:sum(rejected_steps)>0"
        "statistics.csv:error_estimate<1e-3"
        "statistics.csv[time>0.599]:volume_fraction_l2_error>0.004466"
        "statistics.csv[time>0.599]:volume_fraction_l2_error<0.004666"
  NUMDIFF "-a 1e-9 -r 1e-6"
  COMPARE statistics.csv:step,time,time_step,error_estimate,rejected_steps,volume_fraction_l2_error)

# Resumed after step 3 of tests/step_control/step_control_restart.prm, the
# controller goes on with the step it proposed (0.089, saved in the
# checkpoint; without it the resumed run steps 0.1): the resumed run equals
# the uninterrupted one.
file(READ ${S}/step_control/step_control_restart.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/step_control_restart.prm "${_prm}
subsection Checkpointing
  set Interval = 1
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${S}/step_control/step_control_restart.prm)
viscofilm_test(step_control_restart MODE restart RANKS 1 2
  PRM ${CMAKE_CURRENT_BINARY_DIR}/step_control_restart.prm
  REFERENCE unused
  STOP_AFTER 3
  NUMDIFF "-a 1e-12 -r 1e-9"
  COMPARE statistics.csv:step,time,time_step,error_estimate,rejected_steps,volume_fraction_l2_error)

# A step too short to end the run (CFL number 1e-300) stops it with a
# message, after the steps before it (no endless loop: t + k == t).
viscofilm_test(cfl_too_small MODE error RANKS 1 2
  PRM ${S}/step_control/cfl_too_small.prm
  REFERENCE ${S}/step_control/cfl_too_small.output
  VALID_STEPS 1 TIMEOUT 60)
