// Adaptive refinement at the biofilm interface: which cells to refine or
// coarsen, and how solution vectors survive the mesh change.
#ifndef viscofilm_mesh_refinement_h
#define viscofilm_mesh_refinement_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/affine_constraints.h>

#include <viscofilm/dimension.h>

#include <memory>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesSolver;
  template <int dim>
  class VolumeFraction;

  template <int dim>
  class MeshRefinement
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    /// @p initial_level: Geometry/Initial global refinement, which must lie
    /// between the minimum and maximum level.
    void
    parse_parameters(ParameterHandler &prm, const unsigned int initial_level);

    /// The input φ at t = 0 when it has detail between φ's nodes (an
    /// image): the φ indicators take its values on a grid of @p spacing
    /// (the pixel size) in each cell as well, so that a feature thinner
    /// than a cell refines it.
    struct InitialInput
    {
      const Function<dim> &phi;
      double               spacing;
    };

    /// Flag for refinement the cells where a chosen indicator exceeds its
    /// threshold: φ's variation across the cell (interface), also φ itself
    /// (biofilm), the velocity error indicator (velocity); for coarsening
    /// those where all are below a quarter of it (if @p coarsen); within
    /// the level bounds. The φ indicators look at the detached fraction
    /// @p detached (if not null) as at φ, each on its own. Returns whether
    /// any cell was flagged (collective).
    bool
    flag_cells(parallel::distributed::Triangulation<dim> &triangulation,
               const VolumeFraction<dim> &              volume_fraction,
               const VolumeFraction<dim> *              detached,
               const StokesSolver<dim> &                stokes,
               const bool                               coarsen,
               const InitialInput *                     input = nullptr) const;

    bool         adaptive  = false;
    unsigned int interval  = 10;
    unsigned int min_level = 0;
    unsigned int max_level = 0;
    double       threshold = 0.005;
    bool         interface_indicator = false;
    bool         biofilm_indicator   = true;
    bool         velocity_indicator  = true;
    double       velocity_threshold = 0.002;
  };


  /**
   * Carries one solution vector of a DoFHandler across a mesh change:
   * prepare() before the triangulation's execute_coarsening_and_refinement(),
   * finish() after the DoFHandler was distributed anew; finish() applies the
   * new hanging-node constraints. Likewise through a checkpoint:
   * prepare_checkpoint() before the triangulation's save(), release() after
   * it, and finish() (with nothing prepared) after load() and a new
   * distribution of the dofs.
   */
  template <int dim, typename VectorType>
  class SolutionCarrier
  {
  public:
    void
    prepare(const DoFHandler<dim> &dofs, const VectorType &ghosted)
    {
      transfer =
        std::make_unique<parallel::distributed::SolutionTransfer<dim, VectorType>>(dofs);
      transfer->prepare_for_coarsening_and_refinement(ghosted);
    }

    void
    prepare_checkpoint(const DoFHandler<dim> &dofs, const VectorType &ghosted)
    {
      transfer =
        std::make_unique<parallel::distributed::SolutionTransfer<dim, VectorType>>(dofs);
      transfer->prepare_for_serialization(ghosted);
    }

    void
    release()
    {
      transfer.reset();
    }

    /// @p distributed: a vector without ghosts laid out for the new dofs.
    void
    finish(const DoFHandler<dim> &dofs, VectorType &distributed)
    {
      if (transfer)
        transfer->interpolate(distributed);
      else
        {
          transfer = std::make_unique<
            parallel::distributed::SolutionTransfer<dim, VectorType>>(dofs);
          transfer->deserialize(distributed);
        }
      transfer.reset();
      AffineConstraints<double> hanging(DoFTools::extract_locally_relevant_dofs(dofs));
      DoFTools::make_hanging_node_constraints(dofs, hanging);
      hanging.close();
      hanging.distribute(distributed);
    }

  private:
    std::unique_ptr<parallel::distributed::SolutionTransfer<dim, VectorType>> transfer;
  };
} // namespace viscofilm

#endif
