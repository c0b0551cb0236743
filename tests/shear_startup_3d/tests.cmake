# Issue 12, stress, feet and volume fraction in 3D (Geometry/Dimension = 3;
# the .prm files in shear_startup_3d/ and rotation_3d/ are written by their
# make_prm.py, which derives the exact solutions). Each run takes < 40 s of
# CPU on one core.
# Start-up of the shear u = (n·x) e, e = (1, 2, 2)/3, n = (2, 1, −2)/3: the
# 2D closed forms rotated, all six stored components non-zero (a component
# order or a component lost fails it). Order 1 at rate 1, Order 2 at rate 2.
foreach(_case shear_startup_3d shear_startup_3d_js)
  viscofilm_test(${_case} MODE convergence RANKS 1
    PRM ${S}/shear_startup_3d/${_case}.prm
    VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
    MIN_RATES "stress_l2_error=0.95"
    BOUND "statistics.csv:min_conformation_eigenvalue>0"
    NUMDIFF "-a 1e-12 -r 1e-6")
  viscofilm_order2_prm(${_case}_order2 ${S}/shear_startup_3d/${_case}.prm)
  viscofilm_test(${_case}_order2 MODE convergence RANKS 1
    PRM ${CMAKE_CURRENT_BINARY_DIR}/${_case}_order2.prm
    REFERENCE ${S}/shear_startup_3d/${_case}_order2.output
    VARY "Time step=0.1,0.05,0.025,0.0125" "Number of steps=10,20,40,80"
    MIN_RATES "stress_l2_error=1.9"
    BOUND "statistics.csv:min_conformation_eigenvalue>0"
    NUMDIFF "-a 1e-12 -r 1e-6")
endforeach()
