#include <viscofilm/input.h>
#include <viscofilm/time_stepping.h>

#include <algorithm>

namespace viscofilm
{
  void
  TimeStepping::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.declare_entry("Time step",
                      "0.003125",
                      Patterns::Double(0),
                      "Time step k in units of T0 = 60 s, > 0. The thesis used "
                      "k = 0.1 Δx = 0.003125.");
    prm.declare_entry("Number of steps",
                      "200",
                      Patterns::Integer(0),
                      "Number of time steps to take (0: write the initial "
                      "state only).");
    prm.declare_entry("CFL number",
                      "0",
                      Patterns::Double(0),
                      "0: every step is Time step long. > 0: each step is "
                      "min(Time step, CFL number × Δx / max|u^n|) long (Δx the "
                      "smallest cell edge), and the run ends at the time "
                      "Number of steps × Time step.");
    prm.declare_entry("Order",
                      "1",
                      Patterns::Integer(1, 2),
                      "Order of accuracy in the time step of the conformation "
                      "update along the characteristics, the volume fraction's "
                      "transport and the Res ∂u/∂t term: 1 (the thesis' "
                      "scheme) or 2 (doc/numerics.md, \"Second order in "
                      "time\").");
    prm.declare_entry("Picard tolerance",
                      "1e-6",
                      Patterns::Double(0),
                      "The Picard loop of a time step stops when both relative "
                      "changes from the previous iterate, ‖Δu‖/‖u‖ of the "
                      "velocity and ‖Δτ‖/‖τ‖ of the elastic stress (L2 norms "
                      "over the domain), fall below this (after two iterations "
                      "at least), > 0.");
    prm.declare_entry("Maximum Picard iterations",
                      "10",
                      Patterns::Integer(1),
                      "Picard iterations per time step at most; reaching the cap "
                      "is reported (statistics.csv: picard_converged = 0) and "
                      "the run goes on.");
    prm.leave_subsection();
  }


  void
  TimeStepping::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    time_step = prm.get_double("Time step");
    n_steps   = prm.get_integer("Number of steps");
    cfl                   = prm.get_double("CFL number");
    order                 = prm.get_integer("Order");
    picard_tolerance      = prm.get_double("Picard tolerance");
    max_picard_iterations = prm.get_integer("Maximum Picard iterations");
    prm.leave_subsection();
    check_input(time_step > 0,
                "Time stepping/Time step must be > 0, got " +
                  to_text(time_step));
    check_input(picard_tolerance > 0,
                "Time stepping/Picard tolerance must be > 0, got 0");
  }


  double
  TimeStepping::step_length(const double time,
                            const double max_speed,
                            const double cell_size) const
  {
    double k = time_step;
    if (cfl > 0 && max_speed > 0)
      k = std::min(k, cfl * cell_size / max_speed);
    return std::min(k, n_steps * time_step - time);
  }
} // namespace viscofilm
