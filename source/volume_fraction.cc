#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/numerics/vector_tools.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <viscofilm/input.h>
#include <viscofilm/stokes.h>
#include <viscofilm/volume_fraction.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace viscofilm
{
  void
  VolumeFraction::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stabilization");
    prm.declare_entry("GLS tau",
                      "constant",
                      Patterns::Selection("constant|standard"),
                      "constant: τ_GLS = GLS parameter (the thesis, eq. 3.49). "
                      "standard: τ_GLS = GLS parameter × (4/k² + (2|u|/h)²)^(-1/2).");
    prm.declare_entry("GLS parameter",
                      "1.0",
                      Patterns::Double(0),
                      "τ_GLS (constant) or its factor (standard), >= 0. The thesis "
                      "used 1.0 and tried 0.3.");
    prm.leave_subsection();
  }


  void
  VolumeFraction::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stabilization");
    standard_tau  = (prm.get("GLS tau") == "standard");
    gls_parameter = prm.get_double("GLS parameter");
    prm.leave_subsection();
  }


  VolumeFraction::VolumeFraction(
    const parallel::distributed::Triangulation<2> &triangulation,
    const Parameters &                             parameters,
    const BoundaryConditions &                     boundary_conditions)
    : parameters(parameters)
    , boundary_conditions(boundary_conditions)
    , mpi_communicator(triangulation.get_communicator())
    , fe(2)
    , dofs(triangulation)
  {}


  void
  VolumeFraction::setup_dofs()
  {
    dofs.distribute_dofs(fe);
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    constraints.close();
    current_solution.reinit(dofs.locally_owned_dofs(),
                            locally_relevant_dofs,
                            mpi_communicator);
    system_rhs.reinit(dofs.locally_owned_dofs(), mpi_communicator);

    // Inflow faces change with the flow: keep constrained dofs in the pattern
    // so that any of them can be constrained later.
    TrilinosWrappers::SparsityPattern sparsity(dofs.locally_owned_dofs(),
                                               dofs.locally_owned_dofs(),
                                               locally_relevant_dofs,
                                               mpi_communicator);
    DoFTools::make_sparsity_pattern(dofs,
                                    sparsity,
                                    constraints,
                                    /*keep constrained dofs*/ true,
                                    Utilities::MPI::this_mpi_process(
                                      mpi_communicator));
    sparsity.compress();
    system_matrix.reinit(sparsity);
  }


  void
  VolumeFraction::make_constraints(const StokesSolver *stokes)
  {
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    if (stokes != nullptr)
      {
        const QGauss<1>     face_quadrature(3);
        FEFaceValues<2>     stokes_face(stokes->dof_handler().get_fe(),
                                    face_quadrature,
                                    update_values | update_normal_vectors);
        const FEValuesExtractors::Vector     velocities(0);
        std::vector<Tensor<1, 2>>            velocity(face_quadrature.size());
        std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
        // Ghost cells too, so that every rank constrains the same dofs.
        for (const auto &cell : dofs.active_cell_iterators())
          if (!cell->is_artificial() && cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                {
                  stokes_face.reinit(
                    DoFHandler<2>::active_cell_iterator(&cell->get_triangulation(),
                                                        cell->level(),
                                                        cell->index(),
                                                        &stokes->dof_handler()),
                    f);
                  stokes_face[velocities].get_function_values(stokes->solution(),
                                                              velocity);
                  double flux = 0;
                  for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                    flux += velocity[q] * stokes_face.normal_vector(q);
                  if (flux >= 0)
                    continue;
                  const double value =
                    boundary_conditions.boundaries[cell->face(f)->boundary_id()]
                      .volume_fraction;
                  cell->face(f)->get_dof_indices(face_dofs);
                  for (const auto dof : face_dofs)
                    if (!constraints.is_constrained(dof))
                      {
                        constraints.add_line(dof);
                        constraints.set_inhomogeneity(dof, value);
                      }
                }
      }
    constraints.close();
  }


  unsigned int
  VolumeFraction::advance(const StokesSolver &stokes,
                          const double        diffusion,
                          const double        time_step)
  {
    return step(&stokes, diffusion, time_step);
  }


  void
  VolumeFraction::soften(const double       diffusion,
                         const unsigned int n_steps,
                         const double       time_step)
  {
    for (unsigned int s = 0; s < n_steps; ++s)
      step(nullptr, diffusion, time_step);
  }


  unsigned int
  VolumeFraction::step(const StokesSolver *stokes,
                       const double        diffusion,
                       const double        time_step)
  {
    make_constraints(stokes);
    system_matrix = 0;
    system_rhs    = 0;

    const QGauss<2> quadrature(fe.degree + 1);
    FEValues<2>     fe_values(fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
    std::unique_ptr<FEValues<2>> stokes_values;
    if (stokes != nullptr)
      stokes_values = std::make_unique<FEValues<2>>(stokes->dof_handler().get_fe(),
                                                    quadrature,
                                                    update_values);
    const FEValuesExtractors::Vector velocities(0);

    const unsigned int n_dofs = fe.n_dofs_per_cell();
    const unsigned int n_q    = quadrature.size();
    FullMatrix<double> cell_matrix(n_dofs, n_dofs);
    Vector<double>     cell_rhs(n_dofs);
    std::vector<types::global_dof_index> local_dofs(n_dofs);
    std::vector<double>       phi_old(n_q);
    std::vector<Tensor<1, 2>> velocity(n_q);
    std::vector<double>       streamline(n_dofs); // ψ_i/k + u·∇ψ_i
    const double              k = time_step;

    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(current_solution, phi_old);
          if (stokes != nullptr)
            {
              stokes_values->reinit(DoFHandler<2>::active_cell_iterator(
                &cell->get_triangulation(),
                cell->level(),
                cell->index(),
                &stokes->dof_handler()));
              (*stokes_values)[velocities].get_function_values(stokes->solution(),
                                                               velocity);
            }
          const double h = cell->diameter() / std::sqrt(2.0);

          cell_matrix = 0;
          cell_rhs    = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const Tensor<1, 2> u = (stokes != nullptr ? velocity[q] : Tensor<1, 2>());
              double tau = 0;
              if (stokes != nullptr)
                tau = parameters.standard_tau ?
                        parameters.gls_parameter /
                          std::sqrt(4 / (k * k) + std::pow(2 * u.norm() / h, 2)) :
                        parameters.gls_parameter;
              // φ-scaled diffusion D φ^n (eq. 3.45), φ^n clipped at 0.
              const double kappa = k * diffusion * std::max(phi_old[q], 0.0);
              const double JxW   = fe_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                streamline[i] = fe_values.shape_value(i, q) / k +
                                u * fe_values.shape_grad(i, q);
              // eq. 3.49/3.50
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const double          psi_i      = fe_values.shape_value(i, q);
                  const Tensor<1, 2> &grad_psi_i = fe_values.shape_grad(i, q);
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) +=
                      (psi_i * fe_values.shape_value(j, q) +
                       kappa * (grad_psi_i * fe_values.shape_grad(j, q)) +
                       k * psi_i * (u * fe_values.shape_grad(j, q)) +
                       tau * k * streamline[i] * streamline[j]) *
                      JxW;
                  cell_rhs(i) += (phi_old[q] * psi_i + tau * phi_old[q] * streamline[i]) * JxW;
                }
            }
          cell->get_dof_indices(local_dofs);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, local_dofs, system_matrix, system_rhs);
        }
    system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);

    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              mpi_communicator);
    distributed = current_solution;
    SolverControl control(1000, 1e-12 * system_rhs.l2_norm());
    SolverGMRES<TrilinosWrappers::MPI::Vector> solver(control);
    TrilinosWrappers::PreconditionILU          preconditioner;
    preconditioner.initialize(system_matrix);
    try
      {
        solver.solve(system_matrix, distributed, system_rhs, preconditioner);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw ExcMessage("the volume fraction solver (GMRES) did not converge in " +
                         std::to_string(e.last_step) + " iterations: residual " +
                         to_text(e.last_residual));
      }
    constraints.distribute(distributed);
    AssertThrow(std::isfinite(distributed.l2_norm()),
                ExcMessage("the volume fraction is not finite (NaN or inf)"));
    current_solution = distributed;
    return control.last_step();
  }


  void
  VolumeFraction::interpolate(const Function<2> &initial)
  {
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              mpi_communicator);
    VectorTools::interpolate(dofs, initial, distributed);
    constraints.distribute(distributed);
    current_solution = distributed;
  }


  void
  VolumeFraction::add_output(DataOut<2> &data_out) const
  {
    data_out.add_data_vector(dofs, current_solution, "volume_fraction");
  }


  void
  VolumeFraction::prepare_for_refinement()
  {
    carrier.prepare(dofs, current_solution);
  }


  void
  VolumeFraction::finish_refinement()
  {
    setup_dofs();
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              mpi_communicator);
    carrier.finish(dofs, distributed);
    current_solution = distributed;
  }


  void
  VolumeFraction::prepare_for_checkpoint()
  {
    carrier.prepare_checkpoint(dofs, current_solution);
  }


  void
  VolumeFraction::checkpoint_written()
  {
    carrier.release();
  }


  const DoFHandler<2> &
  VolumeFraction::dof_handler() const
  {
    return dofs;
  }


  const TrilinosWrappers::MPI::Vector &
  VolumeFraction::solution() const
  {
    return current_solution;
  }


  double
  VolumeFraction::integral() const
  {
    const QGauss<2>     quadrature(fe.degree + 1);
    FEValues<2>         fe_values(fe, quadrature, update_values | update_JxW_values);
    std::vector<double> values(quadrature.size());
    double              sum = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(current_solution, values);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            sum += values[q] * fe_values.JxW(q);
        }
    return Utilities::MPI::sum(sum, mpi_communicator);
  }


  std::pair<double, double>
  VolumeFraction::range() const
  {
    double low  = std::numeric_limits<double>::max();
    double high = std::numeric_limits<double>::lowest();
    for (const auto i : dofs.locally_owned_dofs())
      {
        low  = std::min(low, current_solution[i]);
        high = std::max(high, current_solution[i]);
      }
    return {Utilities::MPI::min(low, mpi_communicator),
            Utilities::MPI::max(high, mpi_communicator)};
  }
} // namespace viscofilm
