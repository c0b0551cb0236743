# Bad input: message, exit status, no output written.
file(GLOB _bad_inputs ${S}/bad_input/*.prm)
foreach(_prm ${_bad_inputs})
  get_filename_component(_case ${_prm} NAME_WE)
  viscofilm_test(bad_input_${_case} MODE error RANKS 1 PRM ${_prm}
    REFERENCE ${S}/bad_input/${_case}.output
    DATA ${S}/bad_input/colour.png ${S}/bad_input/triangles.msh ${S}/bad_input/tetrahedra.msh
         ${S}/image/half_disc_16bit.png ${S}/image/half_disc_16bit.tif
         ${S}/image/half_ball_stack.tif)
endforeach()
viscofilm_test(bad_input_misspelt_parameter MODE error RANKS 2
  PRM ${S}/bad_input/misspelt_parameter.prm
  REFERENCE ${S}/bad_input/misspelt_parameter.output)
