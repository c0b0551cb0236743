#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_tools.h>

#include <viscofilm/core/input.h>
#include <viscofilm/core/problem.h>
#include <viscofilm/core/version.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace viscofilm
{
  namespace
  {
    /// max over φ's nodes of |η(φ_new) − η(φ_old)| / η(φ_old): how far the
    /// viscosity moved.
    double
    viscosity_change(const Model &                        model,
                     const TrilinosWrappers::MPI::Vector &old_phi,
                     const TrilinosWrappers::MPI::Vector &new_phi)
    {
      double change = 0;
      for (const auto i : new_phi.locally_owned_elements())
        {
          const double eta = model.viscosity(old_phi(i));
          change = std::max(change, std::abs(model.viscosity(new_phi(i)) - eta) / eta);
        }
      return Utilities::MPI::max(change, new_phi.get_mpi_communicator());
    }
  } // namespace


  template <int dim>
  Problem<dim>::Problem(const Parameters<dim> &parameters, const ParameterHandler &prm, MPI_Comm comm)
    : parameters(parameters)
    , prm(prm)
    , mpi_communicator(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , computing_timer(
        std::make_unique<TimerOutput>(comm, pcout, TimerOutput::never, TimerOutput::wall_times))
    // Only the smoothing p4est's 2:1 balance does anyway: deal.II's other
    // smoothing flags (island elimination) act on each rank's view of the
    // mesh and made the adapted mesh depend on the number of ranks.
    , triangulation(comm,
                    Triangulation<dim>::limit_level_difference_at_vertices,
                    parallel::distributed::Triangulation<dim>::default_setting)
    , curved_mapping(parameters.geometry.mapping_degree() > 1 ?
                       std::make_unique<MappingQCache<dim>>(parameters.geometry.mapping_degree()) :
                       nullptr)
    , mapping(curved_mapping ? static_cast<const Mapping<dim> &>(*curved_mapping) :
                               StaticMappingQ1<dim>::mapping)
    , stokes(triangulation,
             mapping,
             parameters.stokes_solver,
             parameters.model,
             parameters.boundary_conditions,
             parameters.time_stepping.order)
    , volume_fraction(triangulation,
                      mapping,
                      parameters.volume_fraction,
                      parameters.boundary_conditions)
    , stress(triangulation,
             mapping,
             parameters.stress,
             parameters.model,
             parameters.boundary_conditions,
             parameters.time_stepping.order,
             stokes.quadrature(),
             volume_fraction)
    , departure_feet(parameters.departure_feet, triangulation, mapping)
    , mesh_refinement(parameters.mesh_refinement)
    , verification(parameters.verification,
                   stokes,
                   stress,
                   volume_fraction,
                   !parameters.boundary_conditions.fixes_pressure_level())
    , loads(parameters.loads,
            parameters.detachment.biofilm,
            parameters.model,
            stokes,
            volume_fraction,
            stress)
    , detachment(parameters.detachment,
                 parameters.model,
                 triangulation,
                 parameters.volume_fraction,
                 parameters.boundary_conditions,
                 stokes,
                 volume_fraction,
                 stress)
    , output(parameters.output, triangulation, mapping)
    , checkpoint(parameters.checkpointing, parameters.output.directory, comm)
    // A checkpoint attaches the fields' vectors in this order.
    , fields{&stokes, &stress, &volume_fraction}
    // statistics.csv's columns and the snapshots' datasets in this order.
    , reporters{&stokes, &volume_fraction, &stress, &departure_feet, &loads, &detachment, &verification}
  {
    if (VolumeFraction<dim> *detached = detachment.detached_fraction())
      fields.push_back(detached);
    if (parameters.substrate.enabled)
      {
        substrate = std::make_unique<Substrate<dim>>(triangulation,
                                                     mapping,
                                                     parameters.substrate,
                                                     parameters.boundary_conditions,
                                                     volume_fraction);
        fields.push_back(substrate.get());
        reporters.push_back(substrate.get());
        if (parameters.growth.enabled)
          {
            growth =
              std::make_unique<Growth<dim>>(parameters.growth,
                                            parameters.detachment.biofilm,
                                            *substrate,
                                            volume_fraction);
            reporters.push_back(growth.get());
          }
      }
  }


  template <int dim>
  void
  Problem<dim>::make_grid()
  {
    TimerOutput::Scope t(*computing_timer, "setup");
    make_coarse_grid();
    parameters.geometry.refine_initial_mesh(triangulation);
    cache_mapping();
    check_probe_points();
  }


  template <int dim>
  void
  Problem<dim>::make_coarse_grid()
  {
    parameters.geometry.make_coarse_grid(triangulation);
    parameters.boundary_conditions.add_periodicity(triangulation);
  }


  template <int dim>
  void
  Problem<dim>::check_probe_points() const
  {
    for (const Point<dim> &p : parameters.output.probe_points)
      {
        bool found = false;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() && cell->point_inside(p))
            {
              found = true;
              break;
            }
        std::string point;
        for (unsigned int d = 0; d < dim; ++d)
          point += (d == 0 ? "" : ", ") + to_text(p[d]);
        check_input(Utilities::MPI::logical_or(found, mpi_communicator),
                    "Output/Probe points: the point (" + point +
                      ") lies in no cell of the mesh");
      }
  }


  template <int dim>
  void
  Problem<dim>::setup_dofs()
  {
    TimerOutput::Scope t(*computing_timer, "setup");
    for (FieldBase<dim> *field : fields)
      field->setup_dofs();
    detachment.setup_dofs();
    mesh_changed();
    pcout << "Mesh: " << triangulation.n_global_active_cells() << " cells, Δx = "
          << parameters.geometry.initial_cell_size() << "; "
          << stokes.n_dofs() << " Stokes dofs, "
          << stress.dof_handler().n_dofs() << " stress dofs, "
          << volume_fraction.dof_handler().n_dofs() << " volume fraction dofs, "
          << Utilities::MPI::n_mpi_processes(mpi_communicator) << " MPI rank(s) × "
          << MultithreadInfo::n_threads() << " thread(s)";
    pcout << "; Stokes solver " << stokes.solver_description() << std::endl;
  }


  template <int dim>
  bool
  Problem<dim>::refine_mesh(const bool coarsen, const typename MeshRefinement<dim>::InitialInput *input)
  {
    TimerOutput::Scope t(*computing_timer, "refine mesh");
    if (!mesh_refinement.flag_cells(triangulation,
                                               volume_fraction,
                                               detachment.detached_fraction(),
                                               stokes,
                                               coarsen,
                                               input))
      return false;
    triangulation.prepare_coarsening_and_refinement();
    for (FieldBase<dim> *field : fields)
      field->prepare_for_refinement();
    triangulation.execute_coarsening_and_refinement();
    cache_mapping();
    const std::string solver = stokes.solver_description();
    for (FieldBase<dim> *field : fields)
      field->finish_refinement();
    mesh_changed();
    // Method = auto and Velocity preconditioner = auto choose anew on each
    // mesh: say when an adapted mesh crossed a threshold.
    if (stokes.solver_description() != solver)
      pcout << "Stokes solver " << stokes.solver_description() << " from here on ("
            << triangulation.n_global_active_cells() << " cells, " << stokes.n_dofs()
            << " Stokes dofs)" << std::endl;
    return true;
  }


  template <int dim>
  void
  Problem<dim>::cache_mapping()
  {
    // Every cell of this rank's view, ghost and artificial ones included.
    if (curved_mapping)
      curved_mapping->initialize(MappingQ<dim>(curved_mapping->get_degree()), triangulation);
  }


  template <int dim>
  void
  Problem<dim>::mesh_changed()
  {
    output.mesh_changed();
    detachment.mesh_changed();
    // The edge of the smallest (square or cubic) cell: its diameter / √dim.
    min_cell_size = GridTools::minimal_cell_diameter(triangulation) / std::sqrt(double(dim));
  }


  template <int dim>
  void
  Problem<dim>::write_checkpoint(const unsigned int step, const double time)
  {
    TimerOutput::Scope t(*computing_timer, "checkpoint");
    const std::string mesh_file = checkpoint.begin();
    for (FieldBase<dim> *field : fields)
      field->prepare_for_checkpoint();
    triangulation.save(mesh_file);
    for (FieldBase<dim> *field : fields)
      field->checkpoint_written();
    typename Checkpoint<dim>::State state{step, time, proposed_time_step, output.snapshots(), {}};
    for (const Reporter<dim> *reporter : reporters)
      reporter->save_state(state.values);
    checkpoint.commit(state, prm);
  }


  template <int dim>
  typename Checkpoint<dim>::State
  Problem<dim>::resume_from_checkpoint()
  {
    const typename Checkpoint<dim>::State state = checkpoint.read(prm);
    {
      TimerOutput::Scope t(*computing_timer, "setup");
      make_coarse_grid();
      triangulation.load(checkpoint.mesh_file());
      cache_mapping();
    }
    setup_dofs();
    for (FieldBase<dim> *field : fields)
      field->finish_refinement();
    for (Reporter<dim> *reporter : reporters)
      reporter->load_state(state.values);
    mesh_changed();
    proposed_time_step = state.next_time_step;
    output.prepare(prm, state.step, state.snapshots);
    pcout << "Resumed from " << parameters.output.directory << "/checkpoint at step "
          << state.step << ", t = " << state.time << std::endl;
    return state;
  }


  template <int dim>
  void
  Problem<dim>::set_initial_conditions()
  {
    // u = 0, p = 0 are the solver's initial state; φ from the input,
    // softened (eq. 2.50); τ = 0. An adaptive mesh must resolve both the
    // input φ and the softened one (whose tail carries a viscosity well
    // above the water's at large viscosity ratios): refine for the input φ
    // until it is resolved, soften, refine for the result and start again
    // from the input φ, until softening asks for no more cells. Only
    // refinement, so that this ends (at the maximum level at the latest).
    const Function<dim> &initial_phi =
      parameters.initial_conditions.initial_volume_fraction();
    // An image has detail between φ's nodes: refine on its pixels too.
    const double resolution = parameters.initial_conditions.input_resolution();
    const typename MeshRefinement<dim>::InitialInput input{initial_phi, resolution};
    const bool adaptive = parameters.mesh_refinement.adaptive;
    for (bool softened = false; !softened;)
      {
        volume_fraction.interpolate(initial_phi);
        if (adaptive && refine_mesh(false, resolution > 0 ? &input : nullptr))
          continue;
        {
          TimerOutput::Scope t(*computing_timer, "softening");
          volume_fraction.soften(parameters.model.diffusion,
                                 parameters.initial_conditions.softening_steps,
                                 parameters.initial_conditions.softening_time_step);
        }
        softened = !(adaptive && refine_mesh(false));
      }
    volume_fraction.advance_time(); // φ^0: the first step's φ^n
    if (substrate)
      substrate->set_initial_values();
    if (growth)
      growth->start_step(); // u^0 below, with Order 2, expands already
    if (adaptive)
      pcout << "Adapted mesh: " << triangulation.n_global_active_cells()
            << " cells, " << stokes.n_dofs() << " Stokes dofs, smallest Δx = "
            << min_cell_size << std::endl;
    stress.set_initial_conditions(parameters.initial_conditions.stress.at(0));
    stokes.invalidate_matrix();
    // With Res > 0, u = 0 is the initial condition; boundary data that are
    // not zero at t = 0 make it an impulsive start (ElasticStress::update).
    if (parameters.model.density > 0 && stokes.check_initial_velocity())
      pcout << "Note: the velocity boundary data at t = 0 are not zero, so the initial "
               "condition u = 0 is an impulsive start."
            << std::endl;
    // Order 2 with Res = 0: u^0 is the flow of the initial state and the
    // boundary data at t = 0 (the solver's u = 0 is none: the first step's
    // feet and its rate of deformation at t_0 need it).
    if (parameters.time_stepping.order == 2 && parameters.model.density == 0)
      {
        time_step = parameters.time_stepping.time_step; // enters no term at Res = 0
        solve_stokes(0);
        stokes.advance_time();
        // No step led to u^0: the first step has no u^{-1} to extrapolate
        // with, and statistics.csv's initial row no step length.
        stokes.set_previous_time_step(0);
        time_step = 0;
        stokes.invalidate_matrix();
      }
  }


  template <int dim>
  unsigned int
  Problem<dim>::solve_stokes(const double time, const bool predictor)
  {
    typename StokesFlow<dim>::Coefficients coefficients{
      time,
      time_step,
      &volume_fraction.dof_handler(),
      &volume_fraction.solution(),
      &parameters.verification.body_force,
      &stress,
      growth ? growth->expansion() : nullptr};
    {
      TimerOutput::Scope t(*computing_timer, "assemble stokes");
      stokes.assemble(coefficients);
    }
    unsigned int iterations;
    {
      TimerOutput::Scope t(*computing_timer, "solve stokes");
      iterations = stokes.solve(predictor);
    }
    return iterations;
  }


  template <int dim>
  unsigned int
  Problem<dim>::advance_volume_fraction(const double k)
  {
    TimerOutput::Scope t(*computing_timer, "volume fraction");
    return volume_fraction.advance(stokes,
                                   departure_feet,
                                   parameters.model.diffusion,
                                   k,
                                   parameters.time_stepping.order,
                                   parameters.time_stepping.controlled());
  }


  template <int dim>
  typename Problem<dim>::StepReport
  Problem<dim>::do_time_step(const double time)
  {
    const double k = time_step;
    StepReport   report;

    // 0. Growth: the flow's expansion from φ^n and S^n.
    if (growth)
      growth->start_step();
    // 1. Departure feet from u^n: c^n there, and u^n for the inertia term.
    const bool viscoelastic = parameters.model.viscoelastic;
    departure_feet.reset_statistics();
    {
      TimerOutput::Scope t(*computing_timer, "departure feet");
      if (viscoelastic)
        stress.trace_back(departure_feet, stokes, time - k, k); // c^n at t_n
      stokes.trace_back(departure_feet, k);
    }

    // 2. Picard loop l = 1, 2, ... for the fields at t_{n+1}:
    //    a. Stokes (eq. 3.40) with η(φ^{n+1,l-1}) and s(φ^{n+1,l-1}) τ^{n+1,l-1};
    //    b. c^{n+1,l} from ∇u^{n+1,l} (eq. 3.39-3.44, or the exponential
    //       trapezoid);
    //    c. Order 2: φ^{n+1,l} (eq. 3.45) from φ^n along (u^n + u^{n+1,l})/2,
    //       and the matrix reassembled with η(φ^{n+1,l}) while η moves by
    //       more than the Picard tolerance (relative, at φ's nodes) from the
    //       η the matrix has: below that the loop's u could not tell the
    //       two matrices apart (doc/numerics-transport.md, "Reassembly at Order 2";
    //       the right-hand side is always of φ^{n+1,l}). Order 1 (the thesis,
    //       MODEL.md §3): φ after the loop with u^{n+1}, so the step's Stokes
    //       problem has η(φ^n) and s(φ^n), an O(k) lag (doc/numerics-transport.md, "The
    //       coupled step at Order 2").
    //    (l = 1 starts from φ^n and c^n.) Without elastic stress and with η
    //    independent of φ one Stokes solve is the whole step.
    const bool phi_in_loop = (parameters.time_stepping.order == 2);
    const Model &model     = parameters.model;
    const bool   coupled =
      viscoelastic || (phi_in_loop && model.viscosity(0) != model.viscosity(1));
    const unsigned int max_picard =
      coupled ? parameters.time_stepping.max_picard_iterations : 1;
    const double tolerance = parameters.time_stepping.picard_tolerance;
    // Order 2: the φ of the Stokes matrix (the step's first: φ^n).
    TrilinosWrappers::MPI::Vector matrix_phi;
    if (phi_in_loop)
      matrix_phi = volume_fraction.solution();
    for (unsigned int l = 1; l <= max_picard; ++l)
      {
        const TrilinosWrappers::MPI::BlockVector previous = stokes.solution();
        // The first iterate is never the loop's last (it iterates at least
        // twice, below): its solve may be a predictor's.
        const unsigned int iterations = solve_stokes(time, l == 1 && max_picard > 1);
        report.stokes_iterations +=
          (l > 1 ? "+" : "") + std::to_string(iterations);
        report.total_stokes_iterations += iterations;
        report.picard_iterations = l;
        if (viscoelastic)
          {
            TimerOutput::Scope t(*computing_timer, "stress update");
            report.picard_stress_change = stress.update(stokes, k);
          }
        if (phi_in_loop)
          {
            if (l > 1)
              volume_fraction.restore_old(); // each iterate from φ^n
            report.transport_iterations += advance_volume_fraction(k);
            if (viscosity_change(model, matrix_phi, volume_fraction.solution()) > tolerance)
              {
                stokes.invalidate_matrix();
                matrix_phi = volume_fraction.solution();
              }
          }
        if (!coupled)
          break;
        report.picard_velocity_change = stokes.velocity_relative_change(previous);
        // The first iterate is compared with u^n: iterate at least twice so
        // that the updated stress (and φ) has acted on the flow once. Both u
        // and τ must have settled, each relative to its own size.
        if (l > 1 && report.picard_velocity_change < tolerance &&
            report.picard_stress_change < tolerance)
          break;
        report.picard_converged = (l < max_picard);
      }
    if (!report.picard_converged)
      pcout << "   Warning: the Picard loop did not reach Time stepping/Picard "
               "tolerance in "
            << report.picard_iterations << " iterations at t = " << time << std::endl;

    // 3. Order 1: φ^{n+1} with u^{n+1}. The viscosity changes with φ.
    if (!phi_in_loop)
      report.transport_iterations = advance_volume_fraction(k);
    const double defect = volume_fraction.last_mass_defect();
    if (defect != 0 && std::abs(defect) > 1e-9 * std::abs(volume_fraction.integral()))
      pcout << "   Warning: φ's transport missed its mass balance by " << defect
            << " (of ∫φ = " << volume_fraction.integral() << ") at t = " << time
            << ": the step (CFL " << step_cfl
            << ") is too long for the room its mass fixer has at the fronts" << std::endl;
    // 4. The substrate with u^{n+1} and φ^{n+1}.
    if (substrate)
      {
        TimerOutput::Scope t(*computing_timer, "substrate");
        substrate->advance(stokes, k);
      }
    stokes.invalidate_matrix();
    return report;
  }


  template <int dim>
  typename Problem<dim>::StepReport
  Problem<dim>::take_step(const double time)
  {
    const TimeStepping &stepping = parameters.time_stepping;
    // The step's CFL number is that of u^n, which the feet follow.
    const double speed = stokes.max_velocity();
    for (unsigned int rejected = 0;; ++rejected)
      {
        time_step = 0; // a failure to find the step reports t_n, not t_n + the last k
        time_step = stepping.step_length(time, speed, min_cell_size, proposed_time_step);
        step_cfl  = speed * time_step / min_cell_size;
        StepReport report = do_time_step(time + time_step);
        if (stepping.controlled())
          {
            // The fields' local error estimates; the controller takes the
            // largest.
            report.error_estimate =
              std::max(volume_fraction.error_estimate(), stress.error_estimate());
            report.rejected_steps = rejected;
            proposed_time_step    = stepping.next_step(time_step, report.error_estimate);
            if (!stepping.accept(time_step, report.error_estimate))
              {
                // Rejected: every field back to t_n, and again shorter.
                for (FieldBase<dim> *field : fields)
                  field->restore_old();
                stokes.invalidate_matrix();
                continue;
              }
            if (report.error_estimate > stepping.tolerance)
              pcout << "   Warning: the error estimate " << report.error_estimate
                    << " exceeds Time stepping/Tolerance at Minimum time step, t = "
                    << time + time_step << std::endl;
          }
        // 4. The biomass grows on what the step's substrate consumed.
        if (growth)
          {
            TimerOutput::Scope t(*computing_timer, "growth");
            const double unplaced = growth->grow(time_step);
            if (unplaced != 0)
              pcout << "   Warning: growth could not place " << unplaced
                    << " of ∫φ within [0, Growth/Maximum volume fraction] at t = "
                    << time + time_step << " (the fronts have too little room for "
                    << "one step's growth: shorten the time step)" << std::endl;
          }
        // 5. Release what the accepted step's loads detach (Detachment/Release).
        {
          TimerOutput::Scope t(*computing_timer, "detachment");
          detachment.release(departure_feet, time_step, parameters.time_stepping.order);
        }
        return report;
      }
  }


  template <int dim>
  void
  Problem<dim>::write_statistics(const unsigned int step,
                            const double       time,
                            const StepReport & report)
  {
    CsvFile &statistics = output.statistics();
    statistics.set("step", step);
    statistics.set("time", time);
    statistics.set("time_step", time_step);
    statistics.set("cfl", step_cfl);
    statistics.set("cells", triangulation.n_global_active_cells());
    statistics.set("stokes_iterations", report.total_stokes_iterations);
    statistics.set("picard_iterations", report.picard_iterations);
    statistics.set("picard_converged", report.picard_converged);
    statistics.set("picard_velocity_change", report.picard_velocity_change);
    statistics.set("picard_stress_change", report.picard_stress_change);
    statistics.set("transport_iterations", report.transport_iterations);
    statistics.set("error_estimate", report.error_estimate);
    statistics.set("rejected_steps", report.rejected_steps);
    for (const Reporter<dim> *reporter : reporters)
      reporter->add_statistics(statistics, time);
    statistics.write_row();
  }


  template <int dim>
  void
  Problem<dim>::output_results(const unsigned int step,
                          const double       time,
                          const bool         last_step)
  {
    TimerOutput::Scope t(*computing_timer, "output");
    output.write_probes(step, time, stokes, volume_fraction, stress);
    if (output.snapshot_due(step, last_step))
      output.write_snapshot(step, time, [this](DataOut<dim> &data_out) {
        for (Reporter<dim> *reporter : reporters)
          reporter->add_output(data_out);
      });
  }


  template <int dim>
  void
  Problem<dim>::run()
  {
    try
      {
        run_time_loop();
      }
    catch (...)
      {
        computing_timer.reset();
        throw;
      }
  }


  template <int dim>
  void
  Problem<dim>::run_time_loop()
  {
    pcout << run_description(mpi_communicator) << std::endl;
    parameters.model.print(pcout);
    const double end_time =
      parameters.time_stepping.n_steps * parameters.time_stepping.time_step;
    unsigned int first_step = 1;
    double       time       = 0;
    if (parameters.checkpointing.resume)
      {
        const typename Checkpoint<dim>::State state = resume_from_checkpoint();
        first_step                    = state.step + 1;
        time                          = state.time;
      }
    else
      {
        make_grid();
        setup_dofs();
        set_initial_conditions();
        output.prepare(prm);
        write_statistics(0, 0.0, StepReport());
        output_results(0, 0.0, end_time == 0);
      }

    // Progress on rank 0: every step up to 200 steps, else 100 lines.
    const unsigned int n_steps = parameters.time_stepping.n_steps;
    const unsigned int progress_interval = std::max(1u, n_steps / 100 * (n_steps > 200));
    const auto         start             = std::chrono::steady_clock::now();
    const double       start_time        = time;
    for (unsigned int step = first_step; time < end_time * (1 - 1e-12); ++step)
      {
        StepReport report;
        bool       last_step = false;
        bool       stepped   = false; // time is t_{n+1}
        try
          {
            report    = take_step(time);
            time     += time_step;
            stepped   = true;
            last_step = (time >= end_time * (1 - 1e-12));
            write_statistics(step, time, report);
            output_results(step, time, last_step);
            for (FieldBase<dim> *field : fields)
              field->advance_time();
            if (parameters.mesh_refinement.adaptive && !last_step &&
                step % parameters.mesh_refinement.interval == 0)
              refine_mesh();
            if (checkpoint.due(step) ||
                (last_step && parameters.checkpointing.interval > 0))
              write_checkpoint(step, time);
          }
        catch (const std::exception &e)
          {
            std::ostringstream where;
            where << "at time step " << step << " (t = " << (stepped ? time : time + time_step)
                  << "): " << error_message(e)
                  << ". statistics.csv and the snapshots written so far are valid.";
            throw ExcMessage(where.str());
          }

        if (step % progress_interval == 0 || last_step)
          {
            const double elapsed =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                .count();
            pcout << "Step " << step << "  t = " << time << "/" << end_time
                  << "  k = " << time_step << "  max|u| = " << stokes.max_velocity()
                  << "  Picard " << report.picard_iterations << " (Stokes "
                  << report.stokes_iterations << ")  " << std::fixed
                  << std::setprecision(1) << elapsed << " s, ~"
                  << elapsed / (time - start_time) * (end_time - time) << " s to go"
                  << std::defaultfloat << std::setprecision(6) << std::endl;
          }
      }
    computing_timer->print_summary();
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    pcout << "Peak memory (VmHWM): "
          << Utilities::MPI::max(memory.VmHWM, mpi_communicator) / 1024.0
          << " MiB on the largest rank, "
          << Utilities::MPI::sum(memory.VmHWM, mpi_communicator) / 1024.0
          << " MiB in all" << std::endl;
  }


  VISCOFILM_INSTANTIATE(Problem)
} // namespace viscofilm
