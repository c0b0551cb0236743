# Issue 10 item 3: walls with u·n = -1e-16 are no inflow: ∫φ stays 1/4 (the
# exact integral of φ = xy) with either scheme.
file(READ ${S}/volume_fraction_inflow/volume_fraction_inflow.prm _prm)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/volume_fraction_inflow_thesis.prm "${_prm}
subsection Stabilization
  set Volume fraction scheme = thesis
end
")
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${S}/volume_fraction_inflow/volume_fraction_inflow.prm)
foreach(_case volume_fraction_inflow volume_fraction_inflow_thesis)
  if(_case STREQUAL volume_fraction_inflow)
    set(_prm ${S}/volume_fraction_inflow/volume_fraction_inflow.prm)
  else()
    set(_prm ${CMAKE_CURRENT_BINARY_DIR}/${_case}.prm)
  endif()
  viscofilm_test(${_case} MODE run RANKS 1 2
    PRM ${_prm}
    REFERENCE ${S}/volume_fraction_inflow/${_case}.output
    BOUND "statistics.csv:volume_fraction_integral>0.2499999999"
          "statistics.csv:volume_fraction_integral<0.2500000001"
          "statistics.csv:volume_fraction_min>-1e-12"
          "statistics.csv:volume_fraction_max<1.000000001"
    NUMDIFF "-a 1e-10 -r 1e-6"
    COMPARE statistics.csv:step,volume_fraction_integral,volume_fraction_min,volume_fraction_max)
endforeach()
