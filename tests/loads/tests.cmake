# Loads on the biofilm against hand-computed values (references written by
# hand: tests/loads/*.prm explain them).
foreach(_case loads_poiseuille loads_shear)
  viscofilm_test(${_case} MODE run RANKS 1 2
    PRM ${S}/loads/${_case}.prm
    NUMDIFF "-a 1e-8 -r 0"
    COMPARE statistics.csv:step,wall_shear_stress_mean,wall_shear_stress_max,interface_traction_mean,interface_traction_max,von_mises_max,detachment_area)
endforeach()
