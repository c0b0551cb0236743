// The simulator: owns the mesh and the fields and runs the time loop.
#ifndef viscofilm_problem_h
#define viscofilm_problem_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <viscofilm/output.h>
#include <viscofilm/parameters.h>
#include <viscofilm/stokes.h>
#include <viscofilm/volume_fraction.h>

namespace viscofilm
{
  using namespace dealii;

  class Problem
  {
  public:
    /// @p prm is kept to write the parameters used next to the results.
    Problem(Parameters &parameters, const ParameterHandler &prm, MPI_Comm comm);

    /// Run all time steps; throws with the step and time on failure.
    void
    run();

  private:
    void
    make_grid();
    void
    setup_dofs();
    void
    set_initial_conditions();
    /// Returns the Krylov iteration count.
    unsigned int
    solve_stokes(const double time);
    void
    output_results(const unsigned int step, const double time, const bool last_step);
    void
    write_statistics(const unsigned int step,
                     const double       time,
                     const unsigned int stokes_iterations);

    Parameters &            parameters;
    const ParameterHandler &prm;
    MPI_Comm                mpi_communicator;
    ConditionalOStream      pcout;
    TimerOutput             computing_timer;

    parallel::distributed::Triangulation<2> triangulation;
    StokesSolver                            stokes;
    VolumeFraction                          volume_fraction;
    Output                                  output;
  };
} // namespace viscofilm

#endif
