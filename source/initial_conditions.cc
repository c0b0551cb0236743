#include <viscofilm/initial_conditions.h>

namespace viscofilm
{
  void
  InitialConditions::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial conditions");
    ParsedExpression::declare(prm,
                              "Volume fraction",
                              "0",
                              "Biofilm volume fraction φ at t = 0, in [0, 1] "
                              "(the thesis: 0.1 inside the biofilm, 0 in water).");
    declare_function_constants(prm);
    prm.leave_subsection();
  }


  void
  InitialConditions::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial conditions");
    volume_fraction.parse(prm.get("Volume fraction"),
                          prm.get("Function constants"),
                          "Initial conditions/Volume fraction");
    prm.leave_subsection();
  }
} // namespace viscofilm
