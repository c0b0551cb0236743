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
#include <viscofilm/postprocess/output.h>
#include <viscofilm/transport/transport_scheme.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <array>
#include <cstdlib>
#include <vector>

namespace viscofilm
{
  namespace
  {
    /// Rows are the owned free nodes; columns and rows are numbered within
    /// matrix_columns. [0]: at u^n, [1]: at u^{n+1}; every entry is
    /// linear in u, so a stage's operator is (1 − θ)[0] + θ[1].
    struct TransportOperator
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


    /// Eulerian transport: the Galerkin convection limited towards its
    /// discrete upwinding, SSP-RK3 with u interpolated between u^n and
    /// u^{n+1}, sub-stepped to the positivity limit; then the bounded
    /// diffusion step and the mass fixer. Bounded and conservative.
    template <int dim>
    class FluxCorrectedScheme : public BoundedTransportScheme<dim>
    {
    public:
      explicit FluxCorrectedScheme(VolumeFraction<dim> &phi)
        : BoundedTransportScheme<dim>(phi)
      {}

      /// Either @p order (the stages interpolate u in time); @p feet
      /// unused. @p estimate_error: also the stages with u^{n+1}.
      unsigned int
      advance(const StokesFlow<dim> &stokes,
              DepartureFeet<dim> &,
              const double diffusion,
              const double time_step,
              const unsigned int,
              const bool estimate_error) override;

      /// volume_fraction_substeps: the sub-steps the last advance() took.
      void
      add_statistics(CsvFile &statistics) const override;

    private:
      using Exchange = typename VolumeFraction<dim>::Exchange;

      /// φ^{n+1} from φ^n by SSP-RK3 with the velocity interpolated
      /// linearly between u^n and u^{n+1} at each stage, every stage
      /// limited. @p estimate_error: also the step with u^{n+1} in every
      /// stage (first order), for error_estimate(). Returns the step's
      /// outflow − inflow of ∫φ, added to the field's exchange.
      double
      step(const StokesFlow<dim> &stokes, const double time_step, const bool estimate_error);

      /// One limited forward Euler stage: @p result := φ + k M_L^{-1}
      /// (low-order rate + limited antidiffusion) from the ghosted @p phi_in
      /// with the operator @p theta of the way from u^n to u^{n+1}; @p flux
      /// gets its boundary rates (outflow, inflow) × @p weight.
      void
      stage(const TransportOperator &       op,
            const double                         theta,
            const double                         time_step,
            const TrilinosWrappers::MPI::Vector &phi_in,
            TrilinosWrappers::MPI::Vector &      result,
            const double                         weight,
            Exchange &                           flux) const;

      unsigned int last_substeps = 1;
    };


    template <int dim>
    unsigned int
    FluxCorrectedScheme<dim>::advance(const StokesFlow<dim> &stokes,
                                      DepartureFeet<dim> &,
                                      const double diffusion,
                                      const double time_step,
                                      const unsigned int,
                                      const bool estimate_error)
    {
      // The limiter's fluxes and d_ij cancel in ∫φ, but the advective
      // form's column sums leave ∫φ ∇·u: the Taylor–Hood u is
      // divergence-free against Q1, not against φ's Q2. The diffusion step
      // keeps the sub-cells' lumped mass, not ∫φ. And a hanging node takes
      // the coarse face's Q2 interpolant, which can leave the free nodes'
      // range by 1/8 of a jump. The fixer puts all three right at the
      // fronts, within the free nodes' range: ∫φ + outflow − inflow is
      // kept to round-off (it gained 1.0e-5 of ∫φ over the default case
      // without), plus k ∫φ^n ∇·u where growth expands the flow.
      this->last_error_estimate = 0;
      VolumeFraction<dim> &phi    = this->phi;
      const double         before = phi.integral();
      const double         mass   = before - step(stokes, time_step, estimate_error) +
                          time_step * phi.expansion_integral();
      const unsigned int   iterations =
        diffusion > 0 ? phi.bounded_diffusion_step(diffusion, time_step) : 0;
      const auto [low, high] = phi.range(true);
      this->record_mass_defect(phi.restore_mass(mass, low, high));
      return iterations;
    }


    template <int dim>
    void
    FluxCorrectedScheme<dim>::add_statistics(CsvFile &statistics) const
    {
      statistics.set("volume_fraction_substeps", last_substeps);
    }


    template <int dim>
    double
    FluxCorrectedScheme<dim>::step(const StokesFlow<dim> &stokes,
                                   const double           time_step,
                                   const bool             estimate_error)
    {
      const DoFHandler<dim> &          dofs             = this->dofs();
      const FE_Q<dim> &                fe               = this->fe();
      const AffineConstraints<double> &constraints      = this->constraints();
      const IndexSet &                 matrix_columns   = this->matrix_columns();
      const Mapping<dim> &             mapping          = this->phi.mapping();
      const MPI_Comm                   mpi_communicator = this->mpi_communicator();
      // Hanging nodes (none) and periodicity only: inflow enters weakly, by
      // the boundary term, so that the mass balance is the boundary's flux.
      this->phi.make_constraints(nullptr);
      const IndexSet &owned = dofs.locally_owned_dofs();
      const double    max_speed = stokes.max_velocity();

      TransportOperator op;
      std::array<TrilinosWrappers::MPI::Vector, 2> inflow, inflow_phi, out_w, in_w;
      TrilinosWrappers::MPI::Vector mass(owned, mpi_communicator);

      const QGauss<dim>     quadrature(fe.degree + 1);
      const QGauss<dim - 1> face_quadrature(fe.degree + 1);
      FEValues<dim>         phi_values(mapping,
                               fe,
                               quadrature,
                               update_values | update_gradients | update_JxW_values);
      FEValues<dim>     stokes_values(mapping,
                                  stokes.dof_handler().get_fe(),
                                  quadrature,
                                  update_values);
      FEFaceValues<dim> phi_face(mapping, fe, face_quadrature, update_values | update_JxW_values);
      FEFaceValues<dim> stokes_face(mapping,
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
          convection.reinit(this->system_matrix());
          convection_t.reinit(this->system_matrix());
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
                      this->boundary_conditions().boundary(cell->face(f)->boundary_id()).type !=
                        BoundaryConditions<dim>::Type::periodic)
                    {
                      phi_face.reinit(cell, f);
                      stokes_face.reinit(cell_of(stokes.dof_handler(), cell), f);
                      stokes_face[velocities].get_function_values(u, face_velocity);
                      const double mean_un  = mean_normal_velocity(stokes_face, face_velocity);
                      const bool   entering = flow_enters(mean_un, max_speed);
                      const double value    = this->phi.inflow_value(cell->face(f)->boundary_id());
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
      TrilinosWrappers::MPI::Vector start(owned, mpi_communicator), middle(start), next(start);
      TrilinosWrappers::MPI::Vector ghosted(owned, matrix_columns, mpi_communicator);
      const auto substeps = [&](const bool first_order, Exchange &flux) {
        for (unsigned int s = 0; s < last_substeps; ++s)
          {
            const double theta0 = first_order ? 1.0 : double(s) / last_substeps;
            const double theta1 = first_order ? 1.0 : double(s + 1) / last_substeps;
            start               = this->solution();
            ghosted             = start;
            stage(op, theta0, k, ghosted, middle, 1.0 / 6, flux);
            ghosted = middle;
            stage(op, theta1, k, ghosted, next, 1.0 / 6, flux);
            middle.equ(0.75, start);
            middle.add(0.25, next);
            ghosted = middle;
            stage(op, (theta0 + theta1) / 2, k, ghosted, next, 2.0 / 3, flux);
            start *= 1.0 / 3;
            start.add(2.0 / 3, next);
            this->solution() = start;
          }
      };
      TrilinosWrappers::MPI::Vector first_order;
      if (estimate_error)
        {
          const TrilinosWrappers::MPI::Vector phi_old = this->solution();
          Exchange                            unused;
          substeps(true, unused);
          first_order.reinit(owned, mpi_communicator);
          first_order      = this->solution();
          this->solution() = phi_old;
        }
      Exchange flux;
      substeps(false, flux);
      const double leaving  = k * Utilities::MPI::sum(flux.outflow, mpi_communicator);
      const double entering = k * Utilities::MPI::sum(flux.inflow, mpi_communicator);
      this->phi.add_exchange({leaving - entering, leaving, entering}, 1.0);
      if (estimate_error)
        this->last_error_estimate = this->phi.max_difference(this->solution(), first_order);

      return leaving - entering;
    }


    template <int dim>
    void
    FluxCorrectedScheme<dim>::stage(const TransportOperator &            op,
                                    const double                         theta,
                                    const double                         k,
                                    const TrilinosWrappers::MPI::Vector &phi_in,
                                    TrilinosWrappers::MPI::Vector &      result,
                                    const double                         weight,
                                    Exchange &                           flux) const
    {
      const AffineConstraints<double> &constraints      = this->constraints();
      const IndexSet &                 matrix_columns   = this->matrix_columns();
      const MPI_Comm                   mpi_communicator = this->mpi_communicator();
      const unsigned int  n_rows = op.rows.size();
      const IndexSet &    owned  = this->dofs().locally_owned_dofs();
      std::vector<double> value(matrix_columns.n_elements());
      {
        unsigned int l = 0;
        for (const auto i : matrix_columns)
          value[l++] = phi_in[i];
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
  } // namespace


  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  make_flux_corrected_scheme(VolumeFraction<dim> &phi)
  {
    return std::make_unique<FluxCorrectedScheme<dim>>(phi);
  }


#define INSTANTIATE(dim)                                                                       \
  template std::unique_ptr<TransportScheme<dim>> make_flux_corrected_scheme<dim>(                \
    VolumeFraction<dim> &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
