// Time step and number of steps (MODEL.md §3: thesis k = 0.1 Δx).
#ifndef viscofilm_time_stepping_h
#define viscofilm_time_stepping_h

#include <deal.II/base/parameter_handler.h>

namespace viscofilm
{
  using namespace dealii;

  class TimeStepping
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    double       time_step = 0.003125;
    unsigned int n_steps   = 200;
  };
} // namespace viscofilm

#endif
