// Initial state: u = 0, p = 0, τ = 0 and the biofilm's volume fraction
// (MODEL.md §4).
#ifndef viscofilm_initial_conditions_h
#define viscofilm_initial_conditions_h

#include <deal.II/base/parameter_handler.h>

#include <viscofilm/input.h>

namespace viscofilm
{
  using namespace dealii;

  class InitialConditions
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// φ(x, y) at t = 0.
    ParsedExpression volume_fraction{1};
  };
} // namespace viscofilm

#endif
