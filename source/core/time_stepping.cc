#include <deal.II/base/utilities.h>

#include <viscofilm/core/input.h>
#include <viscofilm/core/time_stepping.h>

#include <algorithm>
#include <cmath>

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
                      "Number of steps × Time step; a step under 1e-13 of "
                      "that time stops the run with a message.");
    prm.declare_entry("Order",
                      "1",
                      Patterns::Integer(1, 2),
                      "Order of accuracy in the time step of the conformation "
                      "update along the characteristics, the volume fraction's "
                      "transport and the Res ∂u/∂t term: 1 (the thesis' "
                      "scheme) or 2 (doc/numerics.md, \"Second order in "
                      "time\").");
    prm.declare_entry("Breakpoints",
                      "",
                      Patterns::List(Patterns::Double(0)),
                      "Times (comma-separated, units of T0) where the "
                      "boundary data or forcing change non-smoothly, e.g. "
                      "the ends of an inflow ramp: no step straddles one. A "
                      "step that would is shortened to end there; when the "
                      "breakpoint is less than two steps ahead, the rest is "
                      "split into two equal steps (no sliver step). Bounds "
                      "every step, fixed, CFL-bound or error-controlled. A "
                      "step across such a time is only first-order accurate "
                      "whatever Order, and samples a peak there (max|u| at "
                      "the end of a plateau) O(k) early (doc/numerics.md, "
                      "\"Breakpoints\"). Empty: none.");
    prm.declare_entry("Tolerance",
                      "0",
                      Patterns::Double(0),
                      "0: no error control (steps as set by Time step and "
                      "CFL number). > 0, with Order = 2: the largest local "
                      "error estimate of the step's fields (the difference "
                      "of the second-order update from an embedded "
                      "first-order one; φ: max over its nodes, with the "
                      "semi-Lagrangian and FCT Volume fraction schemes; the "
                      "thesis scheme (GLS) gives none) must stay "
                      "below this, or the step is redone shorter; Time step "
                      "and CFL number bound the step from above "
                      "(doc/numerics.md, \"Error-controlled time steps\").");
    prm.declare_entry("Safety factor",
                      "0.8",
                      Patterns::Double(0),
                      "Used with Tolerance > 0: the next step is Safety "
                      "factor × (Tolerance / estimate)^(1/2) × the last one, "
                      "in (0, 1].");
    prm.declare_entry("Maximum growth",
                      "2",
                      Patterns::Double(1),
                      "Used with Tolerance > 0: a step is at most this many "
                      "times the last one, >= 1.");
    prm.declare_entry("Minimum time step",
                      "1e-6",
                      Patterns::Double(0),
                      "Used with Tolerance > 0: the controller's step is at "
                      "least this; a step this short is accepted whatever its "
                      "estimate (statistics.csv: error_estimate above the "
                      "tolerance), > 0.");
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
    breakpoints =
      Utilities::string_to_double(Utilities::split_string_list(prm.get("Breakpoints")));
    std::sort(breakpoints.begin(), breakpoints.end());
    tolerance             = prm.get_double("Tolerance");
    safety_factor         = prm.get_double("Safety factor");
    max_growth            = prm.get_double("Maximum growth");
    minimum_time_step     = prm.get_double("Minimum time step");
    picard_tolerance      = prm.get_double("Picard tolerance");
    max_picard_iterations = prm.get_integer("Maximum Picard iterations");
    prm.leave_subsection();
    check_input(time_step > 0,
                "Time stepping/Time step must be > 0, got " +
                  to_text(time_step));
    check_input(picard_tolerance > 0,
                "Time stepping/Picard tolerance must be > 0, got 0");
    check_input(tolerance == 0 || order == 2,
                "Time stepping/Tolerance > 0 needs Time stepping/Order = 2 (the "
                "error estimate compares the second-order update with the "
                "first-order one), got Order = 1");
    check_input(safety_factor > 0 && safety_factor <= 1,
                "Time stepping/Safety factor must be in (0, 1], got " +
                  to_text(safety_factor));
    check_input(minimum_time_step > 0,
                "Time stepping/Minimum time step must be > 0, got 0");
  }


  double
  TimeStepping::step_length(const double time,
                            const double max_speed,
                            const double cell_size,
                            const double proposed) const
  {
    double k = time_step;
    if (cfl > 0 && max_speed > 0)
      k = std::min(k, cfl * cell_size / max_speed);
    if (proposed > 0)
      k = std::min(k, proposed);
    // The first breakpoint after t (one the last step landed on, up to
    // round-off, is behind).
    const auto next = std::upper_bound(breakpoints.begin(),
                                       breakpoints.end(),
                                       time + 1e-9 * time_step);
    if (next != breakpoints.end())
      {
        const double rest = *next - time;
        if (rest <= k * (1 + 1e-9))
          k = rest;
        else if (rest < 2 * k)
          k = rest / 2;
      }
    const double end_time = n_steps * time_step;
    k                     = std::min(k, end_time - time);
    // A step this short would not end the run (t + k may not even change t
    // in double precision): a CFL number or Minimum time step far too small
    // for this flow. The loop ends once end_time - t <= 1e-12 end_time.
    if (k < 1e-13 * end_time)
      {
        std::string bounds;
        if (cfl > 0 && max_speed > 0)
          bounds = "Time stepping/CFL number = " + to_text(cfl) +
                   " bounds it by CFL number × Δx / max|u| = " +
                   to_text(cfl * cell_size / max_speed);
        if (tolerance > 0)
          bounds += std::string(bounds.empty() ? "" : "; ") +
                    "the error control takes it down to Time stepping/Minimum time step = " +
                    to_text(minimum_time_step);
        AssertThrow(false,
                    ExcMessage("the time step k = " + to_text(k) + " is below 1e-13 of the "
                               "run's length " + to_text(end_time) +
                               ", so the run would not end (" + bounds + "): raise it"));
      }
    return k;
  }


  bool
  TimeStepping::controlled() const
  {
    return tolerance > 0;
  }


  double
  TimeStepping::next_step(const double time_step, const double estimate) const
  {
    const double factor =
      estimate > 0 ? safety_factor * std::sqrt(tolerance / estimate) : max_growth;
    return std::max(minimum_time_step, time_step * std::min(factor, max_growth));
  }


  bool
  TimeStepping::accept(const double time_step, const double estimate) const
  {
    return estimate <= tolerance || time_step <= minimum_time_step * (1 + 1e-12);
  }
} // namespace viscofilm
