#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_tools.h>

#include <viscofilm/input.h>
#include <viscofilm/problem.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace viscofilm
{
  Problem::Problem(Parameters &parameters, const ParameterHandler &prm, MPI_Comm comm)
    : parameters(parameters)
    , prm(prm)
    , mpi_communicator(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , computing_timer(comm, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(comm,
                    Triangulation<2>::MeshSmoothing(
                      Triangulation<2>::smoothing_on_refinement |
                      Triangulation<2>::smoothing_on_coarsening),
                    parallel::distributed::Triangulation<2>::default_setting)
    , stokes(triangulation,
             parameters.stokes_solver,
             parameters.model,
             parameters.boundary_conditions)
    , volume_fraction(triangulation)
    , output(parameters.output, triangulation)
  {}


  void
  Problem::make_grid()
  {
    TimerOutput::Scope t(computing_timer, "setup");
    parameters.geometry.make_grid(triangulation);
  }


  void
  Problem::setup_dofs()
  {
    TimerOutput::Scope t(computing_timer, "setup");
    stokes.setup_dofs();
    volume_fraction.setup_dofs();
    output.mesh_changed();
    pcout << "Mesh: " << triangulation.n_global_active_cells() << " cells, Δx = "
          << parameters.geometry.initial_cell_size() << "; "
          << stokes.n_dofs() << " Stokes dofs, "
          << volume_fraction.dof_handler().n_dofs() << " volume fraction dofs, "
          << Utilities::MPI::n_mpi_processes(mpi_communicator) << " MPI rank(s)"
          << std::endl;
  }


  void
  Problem::set_initial_conditions()
  {
    // u = 0, p = 0 are the solver's initial state; φ from the input.
    volume_fraction.interpolate(
      parameters.initial_conditions.volume_fraction.function());
    stokes.invalidate_matrix();
  }


  unsigned int
  Problem::solve_stokes(const double time)
  {
    StokesSolver::Coefficients coefficients{
      time,
      parameters.time_stepping.time_step,
      &volume_fraction.dof_handler(),
      &volume_fraction.solution(),
      &parameters.verification.body_force.function(),
      {}};
    {
      TimerOutput::Scope t(computing_timer, "assemble stokes");
      stokes.assemble(coefficients);
    }
    unsigned int iterations;
    {
      TimerOutput::Scope t(computing_timer, "solve stokes");
      iterations = stokes.solve();
    }
    if (parameters.stokes_solver.verbose)
      pcout << "   Stokes solve: " << iterations << " FGMRES iterations"
            << std::endl;
    return iterations;
  }


  void
  Problem::write_statistics(const unsigned int step,
                            const double       time,
                            const unsigned int stokes_iterations)
  {
    CsvFile &statistics = output.statistics();
    statistics.set("step", step);
    statistics.set("time", time);
    statistics.set("stokes_iterations", stokes_iterations);
    statistics.set("max_velocity", stokes.max_velocity());
    statistics.set("volume_fraction_integral", volume_fraction.integral());
    const auto [phi_min, phi_max] = volume_fraction.range();
    statistics.set("volume_fraction_min", phi_min);
    statistics.set("volume_fraction_max", phi_max);
    if (parameters.verification.exact_solution)
      {
        const auto [velocity_error, pressure_error] =
          parameters.verification.l2_errors(
            stokes, time, !parameters.boundary_conditions.has_outflow());
        statistics.set("velocity_l2_error", velocity_error);
        statistics.set("pressure_l2_error", pressure_error);
      }
    statistics.write_row();
  }


  void
  Problem::output_results(const unsigned int step,
                          const double       time,
                          const bool         last_step)
  {
    TimerOutput::Scope t(computing_timer, "output");
    output.write_probes(step, time, stokes, volume_fraction);
    if (output.snapshot_due(step, last_step))
      output.write_snapshot(step, time, stokes, volume_fraction);
  }


  void
  Problem::run()
  {
    parameters.model.print(pcout);
    make_grid();
    setup_dofs();
    set_initial_conditions();
    output.prepare(prm);

    const unsigned int n_steps   = parameters.time_stepping.n_steps;
    const double       time_step = parameters.time_stepping.time_step;
    write_statistics(0, 0.0, 0);
    output_results(0, 0.0, n_steps == 0);

    const auto start = std::chrono::steady_clock::now();
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        const double time = step * time_step;
        try
          {
            const unsigned int stokes_iterations = solve_stokes(time);
            write_statistics(step, time, stokes_iterations);
            output_results(step, time, step == n_steps);
            stokes.advance_time();
          }
        catch (const std::exception &e)
          {
            std::ostringstream where;
            where << "at time step " << step << " (t = " << time
                  << "): " << error_message(e);
            throw ExcMessage(where.str());
          }

        const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
        pcout << "Step " << step << "/" << n_steps << ", t = " << time
              << ", elapsed " << std::fixed << std::setprecision(1) << elapsed
              << " s, remaining ~" << elapsed / step * (n_steps - step) << " s"
              << std::defaultfloat << std::setprecision(6) << std::endl;
      }
    computing_timer.print_summary();
  }
} // namespace viscofilm
