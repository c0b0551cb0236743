// The Stokes system's assembly (MODEL.md §3 step 2a): the momentum equation
// with the elastic stress, the velocity at the departure feet and the
// boundary tractions on the right; each cell's matrix goes to the linear-
// solver strategy (stokes_linear_solver.h).
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/affine_constraints.templates.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>

#include <viscofilm/dof_cell.h>
#include <viscofilm/geometry.h>
#include <viscofilm/stokes.h>
#include <viscofilm/stokes_linear_solver.h>

#include <algorithm>
#include <cmath>

namespace viscofilm
{
  template <int dim>
  void
  StokesSolver<dim>::average_viscosity(const Averaging       averaging,
                                  const std::vector<double> &JxW,
                                  std::vector<double> &      viscosity)
  {
    if (averaging == Averaging::none)
      return;
    double weight = 0, sum = 0;
    for (unsigned int q = 0; q < JxW.size(); ++q)
      {
        weight += JxW[q];
        switch (averaging)
          {
            case Averaging::arithmetic:
              sum += JxW[q] * viscosity[q];
              break;
            case Averaging::harmonic:
              sum += JxW[q] / viscosity[q];
              break;
            default:
              sum += JxW[q] * std::log(viscosity[q]);
          }
      }
    const double mean =
      (averaging == Averaging::arithmetic ? sum / weight :
       averaging == Averaging::harmonic   ? weight / sum :
                                            std::exp(sum / weight));
    std::fill(viscosity.begin(), viscosity.end(), mean);
  }


  template <int dim>
  void
  StokesSolver<dim>::assemble(const Coefficients &coefficients)
  {
    make_constraints(coefficients.time);

    const bool assemble_matrix = !matrix_is_current;
    if (assemble_matrix)
      linear_solver->start_matrix();
    system_rhs = 0;

    const Quadrature<dim> quadrature = this->quadrature();
    const Mapping<dim> &  mapping    = Geometry<dim>::mapping(triangulation);
    FEValues<dim>     fe_values(mapping,
                          fe,
                          quadrature,
                          update_values | update_gradients |
                            update_quadrature_points | update_JxW_values);
    FEValues<dim>     phi_fe_values(mapping,
                              coefficients.volume_fraction_dof_handler->get_fe(),
                              quadrature,
                              update_values);
    // The prescribed normal traction −P n of pressure boundaries.
    const QGauss<dim - 1> face_quadrature(fe.degree + 1);
    FEFaceValues<dim>     fe_face_values(mapping,
                                     fe,
                                     face_quadrature,
                                     update_values | update_normal_vectors |
                                       update_quadrature_points | update_JxW_values);

    const unsigned int dofs_per_cell = fe.n_dofs_per_cell();
    const unsigned int n_q_points    = quadrature.size();
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(dim);

    FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
    Vector<double>     cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);

    std::vector<double>                volume_fraction(n_q_points);
    std::vector<double>                viscosity(n_q_points);
    std::vector<Tensor<1, dim>>          old_velocity(n_q_points);
    std::vector<Tensor<1, dim>>        older_velocity(n_q_points); // zero unless BDF2
    std::vector<Vector<double>>        body_force(n_q_points, Vector<double>(dim));
    std::vector<SymmetricTensor<2, dim>> tau(n_q_points);
    std::vector<double>                elastic_viscosity(n_q_points, 0.0);
    std::vector<SymmetricTensor<2, dim>> iterate_strain_rate(n_q_points);
    const bool implicit_elastic =
      parameters.implicit_elastic_viscosity && model.viscoelastic;
    if (implicit_elastic && assemble_matrix)
      elastic_viscosity_cache.resize(triangulation.n_locally_owned_active_cells() *
                                     n_q_points);
    std::size_t cached = 0;
    const bool                         use_feet = !old_velocity_at_feet.empty();
    unsigned int                       foot     = 0;

    std::vector<Tensor<1, dim>>          phi_u(dofs_per_cell);
    std::vector<SymmetricTensor<2, dim>> symgrad_phi_u(dofs_per_cell);
    std::vector<double>                div_phi_u(dofs_per_cell);
    std::vector<double>                phi_p(dofs_per_cell);

    // Res ∂u/∂t (ρ ∂u/∂t in SI) by implicit Euler, (Res/k)(u − u^n, v), or
    // with u^{n-1} by BDF2 with variable steps, ω = k_n/k_{n-1}:
    // (Res/k)((1+2ω)/(1+ω) u − (1+ω) u^n + ω²/(1+ω) u^{n-1}, v).
    const bool   bdf2  = !previous_velocity_at_feet.empty();
    const double omega = bdf2 ? coefficients.time_step / previous_step : 0;
    const double mass_coefficient =
      model.density / coefficients.time_step * (bdf2 ? (1 + 2 * omega) / (1 + omega) : 1);
    const double old_coefficient =
      model.density / coefficients.time_step * (bdf2 ? 1 + omega : 1);
    const double older_coefficient =
      model.density / coefficients.time_step * omega * omega / (1 + omega);
    const ExpressionAt<dim> body_force_now = coefficients.body_force->at(coefficients.time);

    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          const auto phi_cell = cell_of(*coefficients.volume_fraction_dof_handler, cell);
          phi_fe_values.reinit(phi_cell);
          phi_fe_values.get_function_values(*coefficients.volume_fraction,
                                            volume_fraction);
          for (unsigned int q = 0; q < n_q_points; ++q)
            viscosity[q] = model.viscosity(volume_fraction[q]);
          if (coefficients.elastic_stress)
            coefficients.elastic_stress(cell, volume_fraction, tau);
          average_viscosity(parameters.averaging, fe_values.get_JxW_values(), viscosity);
          if (implicit_elastic)
            {
              // From τ^n (the stress iterate when the matrix is built, at the
              // step's first Picard iteration), kept for the step: matrix and
              // right-hand side must use the same η_e for the two to cancel (added
              // after the averaging, which is a model of ηs only).
              fe_values[velocities].get_function_symmetric_gradients(current_solution,
                                                                     iterate_strain_rate);
              for (unsigned int q = 0; q < n_q_points; ++q, ++cached)
                {
                  if (assemble_matrix)
                    elastic_viscosity_cache[cached] =
                      model.elastic_viscosity(volume_fraction[q],
                                              coefficients.time_step,
                                              tau[q]);
                  elastic_viscosity[q] = elastic_viscosity_cache[cached];
                  viscosity[q] += elastic_viscosity[q];
                }
            }

          if (use_feet)
            for (unsigned int q = 0; q < n_q_points; ++q, ++foot)
              {
                old_velocity[q] = old_velocity_at_feet[foot];
                if (bdf2)
                  older_velocity[q] = previous_velocity_at_feet[foot];
              }
          else
            fe_values[velocities].get_function_values(old_solution, old_velocity);
          body_force_now.vector_value_list(fe_values.get_quadrature_points(), body_force);

          // With the matrix current, the cell matrix is needed only to move
          // the inhomogeneities of constrained dofs to the right-hand side:
          // boundary values, and hanging dofs constrained to boundary dofs,
          // which interior cells touching the wall at a vertex also hold.
          cell->get_dof_indices(local_dof_indices);
          const bool need_matrix =
            assemble_matrix ||
            std::any_of(local_dof_indices.begin(),
                        local_dof_indices.end(),
                        [this](const types::global_dof_index i) {
                          return constraints.is_inhomogeneously_constrained(i);
                        });
          cell_matrix = 0;
          cell_rhs    = 0;
          for (unsigned int q = 0; q < n_q_points; ++q)
            {
              for (unsigned int k = 0; k < dofs_per_cell; ++k)
                {
                  phi_u[k]         = fe_values[velocities].value(k, q);
                  symgrad_phi_u[k] = fe_values[velocities].symmetric_gradient(k, q);
                  div_phi_u[k]     = fe_values[velocities].divergence(k, q);
                  phi_p[k]         = fe_values[pressure].value(k, q);
                }
              const double       JxW = fe_values.JxW(q);
              Tensor<1, dim> force;
              for (unsigned int d = 0; d < dim; ++d)
                force[d] = body_force[q][d];
              const Tensor<1, dim> rhs_vector =
                old_coefficient * old_velocity[q] + force -
                older_coefficient * older_velocity[q];
              // s(φ) τ: φ τ in the thesis (eq. 2.34), τ for phases.
              // With the implicit elastic viscosity η_e in the matrix, its
              // explicit twin 2 η_e D(u^l) joins s τ on the right.
              const SymmetricTensor<2, dim> phi_tau =
                model.stress_coupling(volume_fraction[q]) * tau[q] -
                2 * elastic_viscosity[q] * iterate_strain_rate[q];

              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  for (unsigned int j = 0; j < dofs_per_cell && need_matrix; ++j)
                    {
                      cell_matrix(i, j) +=
                        (mass_coefficient * phi_u[i] * phi_u[j] +
                         2 * viscosity[q] * (symgrad_phi_u[i] * symgrad_phi_u[j]) -
                         div_phi_u[i] * phi_p[j] - phi_p[i] * div_phi_u[j]) *
                        JxW;
                    }
                  cell_rhs(i) += (rhs_vector * phi_u[i] -
                                  phi_tau * symgrad_phi_u[i]) *
                                 JxW;
                }
            }

          // −∫ P n·v ds (Type = pressure; outflow has P = 0).
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() &&
                boundary_conditions.boundary(face->boundary_id()).type ==
                  BoundaryConditions<dim>::Type::pressure)
              {
                const ParsedExpression<dim> &pressure =
                  boundary_conditions.boundary(face->boundary_id()).pressure;
                fe_face_values.reinit(cell, face);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const double traction =
                      pressure.value(fe_face_values.quadrature_point(q), coefficients.time) *
                      fe_face_values.JxW(q);
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      cell_rhs(i) -= traction * (fe_face_values[velocities].value(i, q) *
                                                 fe_face_values.normal_vector(q));
                  }
              }

          if (assemble_matrix)
            linear_solver->add_cell_matrix({cell,
                                            fe_values,
                                            viscosity,
                                            elastic_viscosity,
                                            mass_coefficient,
                                            phi_cell,
                                            *coefficients.volume_fraction,
                                            local_dof_indices,
                                            cell_matrix},
                                           constraints);
          constraints.distribute_local_to_global(cell_rhs,
                                                 local_dof_indices,
                                                 system_rhs,
                                                 cell_matrix);
        }

    if (assemble_matrix)
      {
        linear_solver->finish_matrix();
        matrix_is_current = true;
      }
    system_rhs.compress(VectorOperation::add);
    // Constrained rows are decoupled (their values come from distribute()).
    // With zero right-hand side and first guess there they stay zero in the
    // Krylov space; otherwise their diagonal, of the size of η, meets the
    // preconditioner's pressure mass, of the size of h²/η, at hanging pressure
    // nodes and stalls FGMRES at large viscosity contrasts.
    constraints.set_zero(system_rhs);
  }


  template <int dim>
  Quadrature<dim>
  StokesSolver<dim>::quadrature() const
  {
    return QGauss<dim>(fe.degree + 1);
  }


  template <int dim>
  void
  StokesSolver<dim>::trace_back(DepartureFeet<dim> &feet, const double time_step)
  {
    step_length = time_step;
    old_velocity_at_feet.clear();
    previous_velocity_at_feet.clear();
    if (model.density == 0)
      return;
    FEValues<dim> fe_values(Geometry<dim>::mapping(triangulation), fe, quadrature(), update_quadrature_points);
    std::vector<Point<dim>>                               points;
    std::vector<typename Triangulation<dim>::active_cell_iterator> cells;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const Point<dim> &p : fe_values.get_quadrature_points())
            {
              points.push_back(p);
              cells.push_back(cell);
            }
        }
    // Order 1: feet by u^n. Order 2: u^n at the feet one step back and, for
    // BDF2, u^{n-1} at the feet two steps back, each traced with the velocity
    // at the middle of its interval, t_{n+1} − duration/2 (second order).
    const auto at_feet = [&](const double                              duration,
                             const TrilinosWrappers::MPI::BlockVector &values,
                             std::vector<Tensor<1, dim>> &               result) {
      feet.compute(points,
                   cells,
                   dofs,
                   order == 2 ? extrapolated_solution(time_step - 0.5 * duration) :
                                old_solution,
                   duration);
      for (const auto &value : evaluate_velocity(feet.at_feet(), dofs, values))
        {
          Tensor<1, dim> u;
          for (unsigned int d = 0; d < dim; ++d)
            u[d] = value[d];
          result.push_back(u);
        }
    };
    at_feet(time_step, old_solution, old_velocity_at_feet);
    if (order == 2 && previous_step > 0)
      at_feet(time_step + previous_step, older_solution, previous_velocity_at_feet);
  }


  VISCOFILM_INSTANTIATE(StokesSolver)
} // namespace viscofilm
