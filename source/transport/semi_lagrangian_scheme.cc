// Stabilization/Volume fraction scheme = semi-Lagrangian: φ^n at the
// departure feet of φ's nodes, clipped to the nodal range of the cell
// holding the foot, then the bounded diffusion step and the mass fixer
// (doc/numerics-transport.md). Bounded.
#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/core/dof_cell.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/transport/transport_scheme.h>

#include <algorithm>

namespace viscofilm
{
  namespace
  {
    /// (@p a + @p b)/2 with the ghost layout of @p a.
    TrilinosWrappers::MPI::BlockVector
    average(const TrilinosWrappers::MPI::BlockVector &a,
            const TrilinosWrappers::MPI::BlockVector &b)
    {
      std::vector<IndexSet> owned;
      for (unsigned int block = 0; block < a.n_blocks(); ++block)
        owned.push_back(a.block(block).locally_owned_elements());
      TrilinosWrappers::MPI::BlockVector sum(owned, a.block(0).get_mpi_communicator());
      TrilinosWrappers::MPI::BlockVector other(sum);
      sum   = a;
      other = b;
      sum.add(1.0, other);
      sum *= 0.5;
      TrilinosWrappers::MPI::BlockVector result(a);
      result = sum;
      return result;
    }


    template <int dim>
    class SemiLagrangianScheme : public BoundedTransportScheme<dim>
    {
    public:
      explicit SemiLagrangianScheme(VolumeFraction<dim> &phi)
        : BoundedTransportScheme<dim>(phi)
      {}

      /// The feet of φ's nodes, traced by @p feet with u^{n+1} (order 1) or
      /// by the midpoint rule with (u^n + u^{n+1})/2 (order 2); the
      /// inflow values where a characteristic enters; then the bounded
      /// diffusion and the mass fixer. @p estimate_error (order 2): also
      /// the first-order feet.
      unsigned int
      advance(const StokesFlow<dim> &stokes,
              DepartureFeet<dim> &   feet,
              const double           diffusion,
              const double           time_step,
              const unsigned int     order,
              const bool             estimate_error) override;

    private:
      /// @p advected := φ^n at the feet of the nodes along @p velocity (on
      /// @p stokes_dofs), clipped to the nodal range of the cell holding the
      /// foot, which goes to @p lower and @p upper; owned values,
      /// constraints distributed.
      void
      advect(const DoFHandler<dim> &                   stokes_dofs,
             const TrilinosWrappers::MPI::BlockVector &velocity,
             DepartureFeet<dim> &                      feet,
             const double                              time_step,
             TrilinosWrappers::MPI::Vector &           advected,
             TrilinosWrappers::MPI::Vector &           lower,
             TrilinosWrappers::MPI::Vector &           upper);

    };


    template <int dim>
    unsigned int
    SemiLagrangianScheme<dim>::advance(const StokesFlow<dim> &stokes,
                                       DepartureFeet<dim> &   feet,
                                       const double           diffusion,
                                       const double           time_step,
                                       const unsigned int     order,
                                       const bool             estimate_error)
    {
      VolumeFraction<dim> &phi = this->phi;
      this->last_error_estimate      = 0;
      // Second order: the feet by the midpoint rule, with u^{n+1/2} ≈ (u^n +
      // u^{n+1})/2 (local error O(k³)); first order: with u^{n+1}, as the
      // thesis transports φ with it.
      const bool                         midpoint_rule = (order == 2);
      const DoFHandler<dim> &            stokes_dofs   = stokes.dof_handler();
      TrilinosWrappers::MPI::BlockVector midpoint;
      if (midpoint_rule)
        midpoint = average(stokes.start_of_step_solution(), stokes.solution());
      const TrilinosWrappers::MPI::BlockVector &velocity =
        midpoint_rule ? midpoint : stokes.solution();
      // The mass balance of the step: M^{n+1} = M^n − k ∫_∂Ω φ^n u·n (+ k
      // ∫φ^n ∇·u where growth expands the flow: the advective form's), and
      // what of it leaves and what enters (the statistics' totals).
      const typename VolumeFraction<dim>::Exchange flux = phi.boundary_flux(stokes_dofs, velocity);
      phi.add_exchange(flux, time_step);
      const double mass =
        phi.integral() - time_step * flux.net + time_step * phi.expansion_integral();
      phi.make_constraints(&stokes);
      TrilinosWrappers::MPI::Vector advected, lower, upper;
      if (estimate_error && midpoint_rule)
        {
          advect(stokes_dofs, stokes.solution(), feet, time_step, advected, lower, upper);
          const TrilinosWrappers::MPI::Vector first_order = advected;
          advect(stokes_dofs, velocity, feet, time_step, advected, lower, upper);
          this->last_error_estimate = phi.max_difference(advected, first_order);
        }
      else
        advect(stokes_dofs, velocity, feet, time_step, advected, lower, upper);
      this->solution()              = advected;
      const unsigned int iterations = phi.bounded_diffusion_step(diffusion, time_step);
      this->record_mass_defect(phi.restore_mass(mass, lower, upper));
      return iterations;
    }


    template <int dim>
    void
    SemiLagrangianScheme<dim>::advect(const DoFHandler<dim> &                   stokes_dofs,
                                      const TrilinosWrappers::MPI::BlockVector &velocity,
                                      DepartureFeet<dim> &                      feet,
                                      const double                              time_step,
                                      TrilinosWrappers::MPI::Vector &           advected,
                                      TrilinosWrappers::MPI::Vector &           lower,
                                      TrilinosWrappers::MPI::Vector &           upper)
    {
      const DoFHandler<dim> &          dofs        = this->dofs();
      const FE_Q<dim> &                fe          = this->fe();
      const AffineConstraints<double> &constraints = this->constraints();
      const TrilinosWrappers::MPI::Vector &phi_old = this->solution();
      // The free nodes this rank owns, each with a cell around it as the hint.
      const IndexSet &                owned        = dofs.locally_owned_dofs();
      const std::vector<Point<dim>> & unit_support = fe.get_unit_support_points();
      std::vector<bool>               seen(owned.n_elements());
      std::vector<Point<dim>>         nodes;
      std::vector<typename Triangulation<dim>::active_cell_iterator> cells;
      std::vector<types::global_dof_index> node_dofs, local_dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(local_dofs);
            for (unsigned int i = 0; i < local_dofs.size(); ++i)
              if (owned.is_element(local_dofs[i]) && !constraints.is_constrained(local_dofs[i]) &&
                  !seen[owned.index_within_set(local_dofs[i])])
                {
                  seen[owned.index_within_set(local_dofs[i])] = true;
                  nodes.push_back(
                    this->phi.mapping().transform_unit_to_real_cell(cell, unit_support[i]));
                  cells.push_back(cell);
                  node_dofs.push_back(local_dofs[i]);
                }
          }

      feet.compute(nodes, cells, stokes_dofs, velocity, time_step);
      std::vector<double> cell_values(fe.n_dofs_per_cell());
      auto                at_feet = feet.at_feet().template evaluate<3>(
        [&](const typename Triangulation<dim>::active_cell_iterator &cell,
            const ArrayView<const Point<dim>> &                      unit_points,
            const ArrayView<std::array<double, 3>> &                 values) {
          cell_of(dofs, cell)->get_dof_values(phi_old, cell_values.begin(), cell_values.end());
          const auto [low, high] = std::minmax_element(cell_values.begin(), cell_values.end());
          for (unsigned int p = 0; p < unit_points.size(); ++p)
            {
              double value = 0;
              for (unsigned int i = 0; i < cell_values.size(); ++i)
                value += cell_values[i] * fe.shape_value(i, unit_points[p]);
              values[p] = {{value, *low, *high}};
            }
        });
      // A characteristic entering through boundary b brings b's inflow value.
      const std::vector<types::boundary_id> &inflow = feet.inflow_boundaries();
      for (unsigned int n = 0; n < nodes.size(); ++n)
        if (inflow[n] != numbers::invalid_boundary_id)
          at_feet[n].fill(this->phi.inflow_value(inflow[n]));

      const MPI_Comm communicator = this->mpi_communicator();
      advected.reinit(owned, communicator);
      lower.reinit(owned, communicator);
      upper.reinit(owned, communicator);
      for (unsigned int n = 0; n < nodes.size(); ++n)
        {
          const auto &[value, low, high] = at_feet[n];
          advected[node_dofs[n]]         = std::clamp(value, low, high);
          lower[node_dofs[n]]            = low;
          upper[node_dofs[n]]            = high;
        }
      constraints.distribute(advected);
    }
  } // namespace


  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  make_semi_lagrangian_scheme(VolumeFraction<dim> &phi)
  {
    return std::make_unique<SemiLagrangianScheme<dim>>(phi);
  }


#define INSTANTIATE(dim)                                                                       \
  template std::unique_ptr<TransportScheme<dim>> make_semi_lagrangian_scheme<dim>(               \
    VolumeFraction<dim> &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
