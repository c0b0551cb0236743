// Stabilization/Volume fraction scheme = FCT: algebraic flux correction
// (Kuzmin's monolithic convex limiting) of the Galerkin convection of φ towards its
// discrete upwinding, SSP-RK3 in time (doc/numerics-transport.md, "Flux-corrected
// transport").
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/core/dof_cell.h>
#include <viscofilm/core/input.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/transport/volume_fraction.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <array>
#include <cstdlib>
#include <vector>

namespace viscofilm
{
  /// Rows are the owned free nodes; columns and rows are numbered within
  /// matrix_columns. [0]: at u^n, [1]: at u^{n+1}; every entry is
  /// linear in u, so a stage's operator is (1 − θ)[0] + θ[1].
  template <int dim>
  struct VolumeFraction<dim>::TransportOperator
  {
    std::vector<unsigned int>            rows;      // matrix_columns-local index
    std::vector<types::global_dof_index> row_dofs;  // global index
    std::vector<unsigned int>            row_start; // into columns
    std::vector<unsigned int>            columns;   // matrix_columns-local index
    std::array<std::vector<double>, 2>   k_ij, k_ji;
    std::vector<double>                  mass; // ∫ψ_i
    /// (m_i/|Ω|)^{1.5/dim}: how far the bounds may relax at a smooth extremum.
    std::vector<double> relaxation;
    /// Lumped inflow b_i = Σ_faces ∫ψ_i × (the face's mean u·n < 0) and
    /// b_i × the face's inflow value: the rate b_i φ_i − bφ_i pulls φ_i to
    /// the inflow value.
    std::array<std::vector<double>, 2> inflow, inflow_phi;
    /// ∫ψ_i u·n over the outflow faces (non-periodic, not inflow) and over
    /// the inflow faces: the exchange's bookkeeping.
    std::array<std::vector<double>, 2> outflow_weight, inflow_weight;
  };


  namespace
  {
    double
    at_theta(const std::array<std::vector<double>, 2> &values,
                const unsigned int                         i,
                const double                               theta)
    {
      return (1 - theta) * values[0][i] + theta * values[1][i];
    }

    /// d_ij = d_ji >= |k_ij|, |k_ji|: the bar states lie between φ_i and φ_j
    /// even where the discrete u is not divergence-free (k_ji ≠ −k_ij).
    double
    artificial_diffusion(const double k_ij, const double k_ji)
    {
      return std::max(std::abs(k_ij), std::abs(k_ji));
    }
  } // namespace


  template <int dim>
  double
  VolumeFraction<dim>::flux_corrected_step(const StokesFlow<dim> &stokes,
                                           const double             time_step,
                                           const bool               estimate_error)
  {
    // Hanging nodes (none) and periodicity only: inflow enters weakly, by
    // the boundary term, so that the mass balance is the boundary's flux.
    make_constraints(nullptr);
    const IndexSet &owned = dofs.locally_owned_dofs();
    const double    max_speed = stokes.max_velocity();

    TransportOperator op;
    std::array<TrilinosWrappers::MPI::Vector, 2> inflow, inflow_phi, out_w, in_w;
    TrilinosWrappers::MPI::Vector mass(owned, mpi_communicator);

    const QGauss<dim>     quadrature(fe.degree + 1);
    const QGauss<dim - 1> face_quadrature(fe.degree + 1);
    FEValues<dim>         phi_values(this->mapping(),
                             fe,
                             quadrature,
                             update_values | update_gradients | update_JxW_values);
    FEValues<dim> stokes_values(this->mapping(), stokes.dof_handler().get_fe(), quadrature, update_values);
    FEFaceValues<dim> phi_face(this->mapping(), fe, face_quadrature, update_values | update_JxW_values);
    FEFaceValues<dim> stokes_face(this->mapping(),
                                  stokes.dof_handler().get_fe(),
                                  face_quadrature,
                                  update_values | update_normal_vectors | update_JxW_values);
    const FEValuesExtractors::Vector     velocities(0);
    const unsigned int                   n_dofs = fe.n_dofs_per_cell();
    std::vector<Tensor<1, dim>>          velocity(quadrature.size());
    std::vector<Tensor<1, dim>>          face_velocity(face_quadrature.size());
    std::vector<types::global_dof_index> local_dofs(n_dofs);
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs), transposed(n_dofs, n_dofs);
    Vector<double> cell_mass(n_dofs), cell_inflow(n_dofs), cell_inflow_phi(n_dofs),
      cell_out(n_dofs), cell_in(n_dofs);

    TrilinosWrappers::SparseMatrix convection, convection_t;
    for (unsigned int side = 0; side < 2; ++side)
      {
        const TrilinosWrappers::MPI::BlockVector &u =
          side == 0 ? stokes.start_of_step_solution() : stokes.solution();
        convection.reinit(system_matrix);
        convection_t.reinit(system_matrix);
        convection   = 0;
        convection_t = 0;
        for (auto *v : {&inflow[side], &inflow_phi[side], &out_w[side], &in_w[side]})
          v->reinit(owned, mpi_communicator);
        for (const auto &cell : dofs.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              phi_values.reinit(cell);
              stokes_values.reinit(cell_of(stokes.dof_handler(), cell));
              stokes_values[velocities].get_function_values(u, velocity);
              cell_matrix = 0;
              cell_mass   = 0;
              for (const unsigned int q : phi_values.quadrature_point_indices())
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    const double psi_i = phi_values.shape_value(i, q) * phi_values.JxW(q);
                    cell_mass(i) += psi_i;
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      cell_matrix(i, j) -= psi_i * (velocity[q] * phi_values.shape_grad(j, q));
                  }
              transposed.copy_transposed(cell_matrix);
              cell->get_dof_indices(local_dofs);
              constraints.distribute_local_to_global(cell_matrix, local_dofs, convection);
              constraints.distribute_local_to_global(transposed, local_dofs, convection_t);
              if (side == 0)
                constraints.distribute_local_to_global(cell_mass, local_dofs, mass);

              cell_inflow = 0;
              cell_inflow_phi = 0;
              cell_out = 0;
              cell_in  = 0;
              bool any_inflow = false;
              for (const unsigned int f : cell->face_indices())
                if (cell->at_boundary(f) &&
                    boundary_conditions.boundary(cell->face(f)->boundary_id()).type !=
                      BoundaryConditions<dim>::Type::periodic)
                  {
                    phi_face.reinit(cell, f);
                    stokes_face.reinit(cell_of(stokes.dof_handler(), cell), f);
                    stokes_face[velocities].get_function_values(u, face_velocity);
                    const double mean_un  = mean_normal_velocity(stokes_face, face_velocity);
                    const bool   entering = flow_enters(mean_un, max_speed);
                    const double value    = inflow_value(cell->face(f)->boundary_id());
                    for (const unsigned int q : phi_face.quadrature_point_indices())
                      for (unsigned int i = 0; i < n_dofs; ++i)
                        {
                          const double psi_i = phi_face.shape_value(i, q) * phi_face.JxW(q);
                          const double un    = face_velocity[q] * stokes_face.normal_vector(q);
                          (entering ? cell_in : cell_out)(i) += psi_i * un;
                          if (entering)
                            {
                              cell_inflow(i) += psi_i * mean_un;
                              cell_inflow_phi(i) += psi_i * mean_un * value;
                            }
                        }
                    any_inflow = any_inflow || entering;
                  }
              constraints.distribute_local_to_global(cell_out, local_dofs, out_w[side]);
              if (any_inflow)
                {
                  constraints.distribute_local_to_global(cell_inflow, local_dofs, inflow[side]);
                  constraints.distribute_local_to_global(cell_inflow_phi, local_dofs, inflow_phi[side]);
                  constraints.distribute_local_to_global(cell_in, local_dofs, in_w[side]);
                }
            }
        convection.compress(VectorOperation::add);
        convection_t.compress(VectorOperation::add);
        for (auto *v : {&inflow[side], &inflow_phi[side], &out_w[side], &in_w[side]})
          v->compress(VectorOperation::add);
        if (side == 0)
          mass.compress(VectorOperation::add);

        // The owned free rows into the operator's arrays.
        if (side == 0)
          op.row_start.push_back(0);
        for (const auto i : owned)
          if (!constraints.is_constrained(i))
            {
              if (side == 0)
                {
                  op.rows.push_back(matrix_columns.index_within_set(i));
                  op.row_dofs.push_back(i);
                }
              // Epetra's row views (deal.II's row iterators are slow): the two
              // matrices share one graph, so their columns are in one order.
              const Epetra_CrsMatrix &matrix   = convection.trilinos_matrix();
              const int               row      = matrix.RowMap().LID(static_cast<TrilinosWrappers::types::int_type>(i));
              int                     n        = 0, n_t = 0;
              double *                values   = nullptr, *values_t = nullptr;
              int *                   columns  = nullptr, *columns_t = nullptr;
              matrix.ExtractMyRowView(row, n, values, columns);
              convection_t.trilinos_matrix().ExtractMyRowView(row, n_t, values_t, columns_t);
              AssertThrow(n == n_t && std::equal(columns, columns + n, columns_t),
                          ExcInternalError());
              for (int e = 0; e < n; ++e)
                {
                  if (side == 0)
                    op.columns.push_back(
                      matrix_columns.index_within_set(matrix.ColMap().GID64(columns[e])));
                  op.k_ij[side].push_back(values[e]);
                  op.k_ji[side].push_back(values_t[e]);
                }
              if (side == 0)
                op.row_start.push_back(op.columns.size());
            }
      }
    for (const auto i : op.row_dofs)
      {
        op.mass.push_back(mass[i]);
        for (unsigned int side = 0; side < 2; ++side)
          {
            op.inflow[side].push_back(inflow[side][i]);
            op.inflow_phi[side].push_back(inflow_phi[side][i]);
            op.outflow_weight[side].push_back(out_w[side][i]);
            op.inflow_weight[side].push_back(in_w[side][i]);
          }
      }

    // The free nodes' shape functions with their hanging nodes' shares,
    // Σ_h c_hi ψ_h, sum to one, so the rows of k_ij sum to zero on adapted
    // meshes too; the low-order stage is a convex combination as long as
    // each ∫ψ_i is positive, which the Q2 weights (3/8, 3/4, −1/8 per
    // direction) leave it on the meshes we make: checked, not assumed.
    for (unsigned int r = 0; r < op.rows.size(); ++r)
      AssertThrow(op.mass[r] > 0,
                  ExcMessage("Volume fraction scheme = FCT: the lumped mass of node " +
                             std::to_string(op.row_dofs[r]) + " is " + to_text(op.mass[r]) +
                             " (not positive), so the scheme would not stay bounded "
                             "on this mesh; use Volume fraction scheme = semi-Lagrangian"));
    const double volume = Utilities::MPI::sum(
      std::accumulate(op.mass.begin(), op.mass.end(), 0.0), mpi_communicator);
    for (const double m : op.mass)
      op.relaxation.push_back(std::pow(m / volume, 1.5 / dim));

    // Positivity of a forward Euler stage: k ≤ m_i / (Σ_{j≠i} 2d_ij − b_i).
    // d_ij is convex in u and b_i linear, so the limit over a step is that
    // at u^n or u^{n+1}.
    double rate = 0;
    for (unsigned int r = 0; r < op.rows.size(); ++r)
      for (unsigned int side = 0; side < 2; ++side)
        {
          double sum = -op.inflow[side][r];
          for (unsigned int e = op.row_start[r]; e < op.row_start[r + 1]; ++e)
            if (op.columns[e] != op.rows[r])
              sum += 2 * artificial_diffusion(op.k_ij[side][e], op.k_ji[side][e]);
          rate = std::max(rate, sum / op.mass[r]);
        }
    rate          = Utilities::MPI::max(rate, mpi_communicator);
    last_substeps = std::max(1u, static_cast<unsigned int>(std::ceil(time_step * rate * (1 - 1e-12))));
    const double k = time_step / last_substeps;

    // SSP-RK3 (Shu-Osher) in each sub-step s: stages at θ_s, θ_{s+1},
    // θ_{s+1/2}, weights 1/6, 1/6, 2/3 of the boundary's rates. With
    // @p first_order every stage takes u^{n+1} (θ = 1): first order in k, as
    // the semi-Lagrangian feet with u^{n+1}, the error estimate's embedded
    // update.
    TrilinosWrappers::MPI::Vector start(owned, mpi_communicator), stage(start), next(start);
    TrilinosWrappers::MPI::Vector ghosted(owned, matrix_columns, mpi_communicator);
    const auto substeps = [&](const bool first_order, Exchange &flux) {
      for (unsigned int s = 0; s < last_substeps; ++s)
        {
          const double theta0 = first_order ? 1.0 : double(s) / last_substeps;
          const double theta1 = first_order ? 1.0 : double(s + 1) / last_substeps;
          start               = current_solution;
          ghosted             = start;
          flux_corrected_stage(op, theta0, k, ghosted, stage, 1.0 / 6, flux);
          ghosted = stage;
          flux_corrected_stage(op, theta1, k, ghosted, next, 1.0 / 6, flux);
          stage.equ(0.75, start);
          stage.add(0.25, next);
          ghosted = stage;
          flux_corrected_stage(op, (theta0 + theta1) / 2, k, ghosted, next, 2.0 / 3, flux);
          start *= 1.0 / 3;
          start.add(2.0 / 3, next);
          current_solution = start;
        }
    };
    TrilinosWrappers::MPI::Vector first_order;
    if (estimate_error)
      {
        const TrilinosWrappers::MPI::Vector phi_old = current_solution;
        Exchange                            unused;
        substeps(true, unused);
        first_order.reinit(owned, mpi_communicator);
        first_order      = current_solution;
        current_solution = phi_old;
      }
    Exchange flux;
    substeps(false, flux);
    const double leaving  = k * Utilities::MPI::sum(flux.outflow, mpi_communicator);
    const double entering = k * Utilities::MPI::sum(flux.inflow, mpi_communicator);
    exchange.outflow += leaving;
    exchange.inflow += entering;
    exchange.net = exchange.outflow - exchange.inflow;
    if (estimate_error)
      last_error_estimate = max_difference(current_solution, first_order);

    return leaving - entering;
  }


  template <int dim>
  void
  VolumeFraction<dim>::flux_corrected_stage(const TransportOperator &           op,
                                            const double                        theta,
                                            const double                        k,
                                            const TrilinosWrappers::MPI::Vector &phi,
                                            TrilinosWrappers::MPI::Vector &      result,
                                            const double                        weight,
                                            Exchange &                          flux) const
  {
    const unsigned int  n_rows = op.rows.size();
    const IndexSet &    owned  = dofs.locally_owned_dofs();
    std::vector<double> value(matrix_columns.n_elements());
    {
      unsigned int l = 0;
      for (const auto i : matrix_columns)
        value[l++] = phi[i];
    }
    const auto convection = [&](const unsigned int e) {
      const double k_ij = (1 - theta) * op.k_ij[0][e] + theta * op.k_ij[1][e];
      const double k_ji = (1 - theta) * op.k_ji[0][e] + theta * op.k_ji[1][e];
      return std::array<double, 3>{{k_ij, k_ji, artificial_diffusion(k_ij, k_ji)}};
    };

    // The data's range: φ's nodal values and the inflow values.
    double data_low  = std::numeric_limits<double>::max();
    double data_high = std::numeric_limits<double>::lowest();
    for (unsigned int r = 0; r < n_rows; ++r)
      {
        const double b = at_theta(op.inflow, r, theta);
        for (const double v :
             {value[op.rows[r]], b < 0 ? at_theta(op.inflow_phi, r, theta) / b : value[op.rows[r]]})
          {
            data_low  = std::min(data_low, v);
            data_high = std::max(data_high, v);
          }
      }
    data_low  = Utilities::MPI::min(data_low, mpi_communicator);
    data_high = Utilities::MPI::max(data_high, mpi_communicator);

    // Each node's bounds: the range of its stencil (and of the inflow value
    // the boundary term pulls it to), relaxed at smooth extrema (Guermond,
    // Nazarov, Popov, Tomas 2018) by the mean second difference there
    // (O(h²)), at most (m_i/|Ω|)^{1.5/dim} of the value (O(h^1.5) at a
    // jump), within the data's range: else every extremum is clipped.
    TrilinosWrappers::MPI::Vector lower(owned, mpi_communicator), upper(lower);
    for (unsigned int r = 0; r < n_rows; ++r)
      {
        const double phi_i = value[op.rows[r]];
        const double b     = at_theta(op.inflow, r, theta);
        double       low = phi_i, high = phi_i, second_difference = 0;
        unsigned int n_neighbours = 0;
        if (b < 0)
          {
            const double inflow = at_theta(op.inflow_phi, r, theta) / b;
            low                 = std::min(low, inflow);
            high                = std::max(high, inflow);
          }
        for (unsigned int e = op.row_start[r]; e < op.row_start[r + 1]; ++e)
          if (op.columns[e] != op.rows[r] && convection(e)[2] > 0)
            {
              const double phi_j = value[op.columns[e]];
              low                = std::min(low, phi_j);
              high               = std::max(high, phi_j);
              second_difference += phi_i - phi_j;
              ++n_neighbours;
            }
        if (n_neighbours > 0)
          {
            const double relax = std::abs(second_difference) / n_neighbours;
            high = std::min(data_high, high + std::min(relax, op.relaxation[r] * std::abs(high)));
            low  = std::max(data_low, low - std::min(relax, op.relaxation[r] * std::abs(low)));
          }
        lower[op.row_dofs[r]] = low;
        upper[op.row_dofs[r]] = high;
      }
    lower.compress(VectorOperation::insert);
    upper.compress(VectorOperation::insert);
    // The neighbours' bounds, from their owners.
    TrilinosWrappers::MPI::Vector ghosted(owned, matrix_columns, mpi_communicator);
    std::vector<double>           lower_of(value.size()), upper_of(value.size());
    for (auto [bound, local] : {std::pair(&lower, &lower_of), std::pair(&upper, &upper_of)})
      {
        ghosted        = *bound;
        unsigned int l = 0;
        for (const auto i : matrix_columns)
          (*local)[l++] = ghosted[i];
      }

    // Monolithic convex limiting (Kuzmin 2020): with d_ij (zero row sums)
    // the low-order rate is Σ_j 2d_ij (φ̄_ij − φ_i), the bar states φ̄_ij =
    // φ_i + (k_ij + d_ij)(φ_j − φ_i)/(2d_ij) between φ_i and φ_j; the
    // Galerkin antidiffusion f_ij = d_ij (φ_i − φ_j) is cut so that φ̄_ij +
    // f_ij/(2d_ij) stays in i's bounds and φ̄_ji − f_ij/(2d_ij) in j's. The
    // cut is the same from both sides (conservative) and does not depend on
    // k, so SSP-RK3 keeps its order in k; a forward Euler stage within the
    // positivity limit is a convex combination of φ_i, limited bar states
    // and the inflow value.
    result.reinit(owned, mpi_communicator);
    for (unsigned int r = 0; r < n_rows; ++r)
      {
        const unsigned int i     = op.rows[r];
        const double       phi_i = value[i];
        const double       b     = at_theta(op.inflow, r, theta);
        double             rate  = b * phi_i - at_theta(op.inflow_phi, r, theta);
        for (unsigned int e = op.row_start[r]; e < op.row_start[r + 1]; ++e)
          {
            const unsigned int j = op.columns[e];
            const auto [k_ij, k_ji, d_ij] = convection(e);
            if (j == i || d_ij == 0)
              continue;
            const double phi_j  = value[j];
            const double bar_ij = phi_i + (k_ij + d_ij) * (phi_j - phi_i) / (2 * d_ij);
            const double bar_ji = phi_j + (k_ji + d_ij) * (phi_i - phi_j) / (2 * d_ij);
            const double f      = d_ij * (phi_i - phi_j);
            const double limited =
              f > 0 ? std::min({f, 2 * d_ij * (upper_of[i] - bar_ij), 2 * d_ij * (bar_ji - lower_of[j])}) :
                      std::max({f, 2 * d_ij * (lower_of[i] - bar_ij), 2 * d_ij * (bar_ji - upper_of[j])});
            rate += 2 * d_ij * (bar_ij - phi_i) + limited;
          }
        result[op.row_dofs[r]] = phi_i + k / op.mass[r] * rate;

        flux.outflow += weight * phi_i * at_theta(op.outflow_weight, r, theta);
        flux.inflow += weight * ((b - at_theta(op.inflow_weight, r, theta)) * phi_i -
                                 at_theta(op.inflow_phi, r, theta));
      }
    result.compress(VectorOperation::insert);
    constraints.distribute(result);
  }


  // The class is instantiated once, in volume_fraction.cc; each file instantiates the
  // members it defines (an explicit instantiation of the whole class in two
  // files would be ill-formed).
#define INSTANTIATE(dim)                                                          \
  template double VolumeFraction<dim>::flux_corrected_step(const StokesFlow<dim> &, \
                                                          const double,            \
                                                          const bool);             \
  template void VolumeFraction<dim>::flux_corrected_stage(                        \
    const TransportOperator &,                                                    \
    const double,                                                                 \
    const double,                                                                 \
    const TrilinosWrappers::MPI::Vector &,                                        \
    TrilinosWrappers::MPI::Vector &,                                              \
    const double,                                                                 \
    Exchange &) const;

  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
