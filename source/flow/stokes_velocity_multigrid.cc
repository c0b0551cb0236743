// Geometric multigrid for the Stokes velocity block (doc/numerics-stokes.md, "The
// velocity block's geometric multigrid"): the deal.II step-75 pattern
// (global coarsening, matrix-free levels, Chebyshev smoothing, CG with AMG
// on the coarse mesh) with a cell-wise viscosity. This file holds the mesh
// sequence, the constraints, the transfers and the viscosity's restriction;
// the level operators, compiled with SIMD, are VelocityMultigridLevels.
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/multigrid/mg_transfer_global_coarsening.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/flow/stokes_velocity_multigrid.h>
#include <viscofilm/flow/stokes_velocity_multigrid_levels.h>

namespace viscofilm
{
  namespace
  {
    using VectorType = LinearAlgebra::distributed::Vector<double>;
  }


  template <int dim>
  struct VelocityMultigrid<dim>::Levels
  {
    using Transfer = MGTransferGlobalCoarsening<dim, VectorType>;

    std::vector<std::shared_ptr<const Triangulation<dim>>> triangulations;
    unsigned int                                           min = 0, max = 0;
    MGLevelObject<DoFHandler<dim>>                         dofs;
    /// FE_DGQ(0) on each level: the cell mean of 2η, restricted from level
    /// to level.
    MGLevelObject<DoFHandler<dim>>                     cell_dofs;
    MGLevelObject<VectorType>                          viscosity;
    /// 2η at the quadrature points of each locally owned active cell (by its
    /// FE_DGQ(0) dof's local index): the finest level's coefficient.
    std::vector<std::vector<double>>                   point_viscosity;
    MGLevelObject<AffineConstraints<double>>           constraints;
    MGLevelObject<MGTwoLevelTransfer<dim, VectorType>> transfers;
    MGLevelObject<MGTwoLevelTransfer<dim, VectorType>> cell_transfers;
    std::unique_ptr<Transfer>                          transfer;
    std::unique_ptr<VelocityMultigridLevels<dim>>      operators;

    /// The finest level's local index of each locally owned Stokes velocity
    /// dof (by its position in the owned index set).
    std::vector<unsigned int> fine_index;
    mutable VectorType        fine_src, fine_dst;
  };


  template <int dim>
  VelocityMultigrid<dim>::VelocityMultigrid(const BoundaryConditions<dim> &boundary_conditions,
                                            const unsigned int             smoother_degree)
    : boundary_conditions(boundary_conditions)
    , smoother_degree(smoother_degree)
  {
    // Parameters<dim> refuses periodic boundaries with GMG by name.
    AssertThrow(!boundary_conditions.has_periodic_pair(), ExcInternalError());
  }


  template <int dim>
  VelocityMultigrid<dim>::~VelocityMultigrid() = default;


  template <int dim>
  void
  VelocityMultigrid<dim>::reinit(const DoFHandler<dim> &stokes_dofs, const IndexSet &owned_velocity)
  {
    AssertThrow(stokes_dofs.get_fe().base_element(0).degree == 2 &&
                  stokes_dofs.get_fe().element_multiplicity(0) == dim,
                ExcInternalError());
    levels = std::make_unique<Levels>();
    Levels &L = *levels;
    L.triangulations =
      MGTransferGlobalCoarseningTools::create_geometric_coarsening_sequence(
        stokes_dofs.get_triangulation());
    L.min = 0;
    L.max = L.triangulations.size() - 1;
    L.dofs.resize(L.min, L.max);
    L.cell_dofs.resize(L.min, L.max);
    L.viscosity.resize(L.min, L.max);
    L.constraints.resize(L.min, L.max);
    L.transfers.resize(L.min, L.max);
    L.cell_transfers.resize(L.min, L.max);

    const FESystem<dim> fe(FE_Q<dim>(2), dim);
    const FE_DGQ<dim>   cell_fe(0);
    for (unsigned int l = L.min; l <= L.max; ++l)
      {
        L.dofs[l].reinit(*L.triangulations[l]);
        L.dofs[l].distribute_dofs(fe);
        L.cell_dofs[l].reinit(*L.triangulations[l]);
        L.cell_dofs[l].distribute_dofs(cell_fe);
        L.viscosity[l].reinit(L.cell_dofs[l].locally_owned_dofs(),
                              DoFTools::extract_locally_relevant_dofs(L.cell_dofs[l]),
                              stokes_dofs.get_communicator());

        AffineConstraints<double> &constraints = L.constraints[l];
        constraints.reinit(DoFTools::extract_locally_relevant_dofs(L.dofs[l]));
        DoFTools::make_hanging_node_constraints(L.dofs[l], constraints);
        // The bilinear map of the level operators (a preconditioner's).
        boundary_conditions.constrain_velocity(
          StaticMappingQ1<dim>::mapping, L.dofs[l], 0.0, constraints, true);
        constraints.close();
      }
    L.operators =
      std::make_unique<VelocityMultigridLevels<dim>>(L.dofs, L.constraints, smoother_degree);
    for (unsigned int l = L.min; l < L.max; ++l)
      {
        L.transfers[l + 1].reinit(L.dofs[l + 1], L.dofs[l], L.constraints[l + 1], L.constraints[l]);
        L.cell_transfers[l + 1].reinit(L.cell_dofs[l + 1], L.cell_dofs[l]);
      }
    L.transfer = std::make_unique<typename Levels::Transfer>(
      L.transfers, [&L](const unsigned int l, VectorType &vector) {
        L.operators->initialize_dof_vector(l, vector);
      });

    // The Stokes velocity dofs and the finest level's: the same nodes on the
    // same cells, owned by the same rank.
    const FiniteElement<dim> &           stokes_fe = stokes_dofs.get_fe();
    std::vector<types::global_dof_index> stokes_indices(stokes_fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
    const IndexSet &                     owned = L.dofs[L.max].locally_owned_dofs();
    L.fine_index.assign(owned_velocity.n_elements(), numbers::invalid_unsigned_int);
    for (const auto &stokes_cell : stokes_dofs.active_cell_iterators())
      if (stokes_cell->is_locally_owned())
        {
          const typename DoFHandler<dim>::active_cell_iterator cell(
            &stokes_dofs.get_triangulation(), stokes_cell->level(), stokes_cell->index(), &L.dofs[L.max]);
          stokes_cell->get_dof_indices(stokes_indices);
          cell->get_dof_indices(indices);
          for (unsigned int i = 0; i < stokes_fe.n_dofs_per_cell(); ++i)
            if (stokes_fe.system_to_base_index(i).first.first == 0 &&
                owned_velocity.is_element(stokes_indices[i]))
              {
                const auto component = stokes_fe.system_to_component_index(i);
                const types::global_dof_index index =
                  indices[fe.component_to_system_index(component.first, component.second)];
                AssertThrow(owned.is_element(index), ExcInternalError());
                L.fine_index[owned_velocity.index_within_set(stokes_indices[i])] =
                  owned.index_within_set(index);
              }
        }
    AssertThrow(std::find(L.fine_index.begin(), L.fine_index.end(), numbers::invalid_unsigned_int) ==
                  L.fine_index.end(),
                ExcInternalError());
    L.point_viscosity.resize(L.cell_dofs[L.max].locally_owned_dofs().n_elements());
    L.operators->initialize_dof_vector(L.max, L.fine_src);
    L.operators->initialize_dof_vector(L.max, L.fine_dst);
  }


  template <int dim>
  void
  VelocityMultigrid<dim>::set_cell_viscosity(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const std::vector<double> &                           viscosity,
    const std::vector<double> &                           JxW)
  {
    Levels &                                             L = *levels;
    const typename DoFHandler<dim>::active_cell_iterator cell_dof(
      &cell->get_triangulation(), cell->level(), cell->index(), &L.cell_dofs[L.max]);
    std::vector<types::global_dof_index> index(1);
    cell_dof->get_dof_indices(index);
    double integral = 0, volume = 0;
    for (unsigned int q = 0; q < JxW.size(); ++q)
      {
        integral += viscosity[q] * JxW[q];
        volume += JxW[q];
      }
    L.viscosity[L.max][index[0]] = integral / volume;
    L.point_viscosity[L.viscosity[L.max].get_partitioner()->global_to_local(index[0])] = viscosity;
  }


  template <int dim>
  void
  VelocityMultigrid<dim>::build(const double mass)
  {
    Levels &L = *levels;
    // Coarser levels: the mean of the children's 2η (DG0 restriction sums
    // them; so it does with ones, to count them). The count starts from
    // zero, not from the last build's means.
    for (unsigned int l = L.max; l > L.min; --l)
      {
        VectorType ones, children;
        ones.reinit(L.viscosity[l]);
        children.reinit(L.viscosity[l - 1]);
        ones = 1.0;
        ones.update_ghost_values();
        L.viscosity[l].update_ghost_values();
        L.viscosity[l - 1] = 0;
        L.cell_transfers[l].restrict_and_add(L.viscosity[l - 1], L.viscosity[l]);
        L.cell_transfers[l].restrict_and_add(children, ones);
        for (const auto i : L.viscosity[l - 1].locally_owned_elements())
          L.viscosity[l - 1][i] /= children[i];
      }

    // The finest level at the quadrature points (the system's quadrature,
    // lexicographic as the matrix-free one), coarser ones the cell means.
    std::vector<types::global_dof_index> index(1);
    const auto                           viscosity =
      [&L, &index](const unsigned int                             l,
                   const typename DoFHandler<dim>::cell_iterator &cell,
                   std::vector<double> &                          values) {
        const typename DoFHandler<dim>::active_cell_iterator cell_dof(
          &cell->get_triangulation(), cell->level(), cell->index(), &L.cell_dofs[l]);
        cell_dof->get_dof_indices(index);
        const std::vector<double> *points =
          (l == L.max ? &L.point_viscosity[L.viscosity[l].get_partitioner()->global_to_local(index[0])] :
                        nullptr);
        if (points && points->size() == values.size())
          values = *points;
        else
          std::fill(values.begin(), values.end(), L.viscosity[l][index[0]]);
      };
    L.operators->build(mass, viscosity, *L.transfer);
  }


  template <int dim>
  void
  VelocityMultigrid<dim>::vmult(TrilinosWrappers::MPI::Vector &      dst,
                                const TrilinosWrappers::MPI::Vector &src) const
  {
    const Levels &L = *levels;
    for (unsigned int k = 0; k < L.fine_index.size(); ++k)
      L.fine_src.local_element(L.fine_index[k]) = src.trilinos_vector()[0][k];
    L.operators->vmult(L.fine_dst, L.fine_src);
    for (unsigned int k = 0; k < L.fine_index.size(); ++k)
      dst.trilinos_vector()[0][k] = L.fine_dst.local_element(L.fine_index[k]);
  }


  VISCOFILM_INSTANTIATE(VelocityMultigrid)
} // namespace viscofilm
