// Time step and number of steps (MODEL.md §3: thesis k = 0.1 Δx).
#ifndef viscofilm_time_stepping_h
#define viscofilm_time_stepping_h

#include <deal.II/base/parameter_handler.h>

#include <vector>

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

    /// The length of the step from @p time: Time step, or with CFL number
    /// > 0 at most cfl × @p cell_size / @p max_speed (max|u^n|, the velocity
    /// the departure feet follow; @p cell_size the smallest cell edge), at
    /// most @p proposed (the controller's step; 0: none), shortened to land
    /// on the next breakpoint (the rest split in two equal steps when it is
    /// less than two steps), and ending at the end time n_steps × time_step
    /// at the latest.
    double
    step_length(const double time,
                const double max_speed,
                const double cell_size,
                const double proposed = 0) const;

    /// The error-controlled step (Tolerance > 0) is on.
    bool
    controlled() const;

    /// The controller's next step after a step of length @p time_step whose
    /// local error estimate (the largest of the fields') is @p estimate:
    /// the estimate is that of the embedded first-order update, O(k²), so
    /// k_new = k × safety (tolerance / estimate)^{1/2}, at most max_growth
    /// × k and at least minimum_time_step.
    double
    next_step(const double time_step, const double estimate) const;

    /// Accept a step of @p time_step with @p estimate: within the tolerance,
    /// or already at the minimum step.
    bool
    accept(const double time_step, const double estimate) const;

    double       time_step = 0.003125;
    unsigned int n_steps   = 200;
    /// > 0: k = min(time_step, cfl Δx / max|u|) each step, up to the end
    /// time n_steps × time_step.
    double       cfl = 0;
    /// Order of accuracy in k of the stress, φ and inertia updates: 1 or 2.
    unsigned int order = 1;
    /// Times the steps land on (sorted): where the boundary data's time
    /// derivative jumps, which a step must not straddle.
    std::vector<double> breakpoints;

    /// Error control (doc/numerics.md, "Error-controlled time steps"):
    /// tolerance on the local error estimate, 0 = off.
    double tolerance         = 0;
    double safety_factor     = 0.8;
    double max_growth        = 2;
    double minimum_time_step = 1e-6;

    /// The Picard loop between Stokes and the stress (MODEL.md §3 step 2c).
    double       picard_tolerance      = 1e-6;
    unsigned int max_picard_iterations = 10;
  };
} // namespace viscofilm

#endif
