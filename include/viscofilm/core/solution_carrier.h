// How a field's vectors survive a mesh change or a checkpoint.
#ifndef viscofilm_solution_carrier_h
#define viscofilm_solution_carrier_h

#include <deal.II/distributed/solution_transfer.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/affine_constraints.h>

#include <memory>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /**
   * Carries the solution vectors of a DoFHandler across a mesh change, with
   * one SolutionTransfer for all of them: prepare() before the
   * triangulation's execute_coarsening_and_refinement(), finish() after the
   * DoFHandler was distributed anew; finish() applies the new hanging-node
   * constraints. Likewise through a checkpoint: prepare_checkpoint() before
   * the triangulation's save(), release() after it, and finish() (with
   * nothing prepared) after load() and a new distribution of the dofs.
   */
  template <int dim, typename VectorType>
  class SolutionCarrier
  {
  public:
    void
    prepare(const DoFHandler<dim> &dofs, const std::vector<const VectorType *> &ghosted)
    {
      transfer =
        std::make_unique<parallel::distributed::SolutionTransfer<dim, VectorType>>(dofs);
      transfer->prepare_for_coarsening_and_refinement(ghosted);
    }

    void
    prepare_checkpoint(const DoFHandler<dim> &                  dofs,
                       const std::vector<const VectorType *> &ghosted)
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

    /// @p distributed: vectors without ghosts laid out for the new dofs, as
    /// many as were prepared, in their order.
    void
    finish(const DoFHandler<dim> &dofs, std::vector<VectorType *> &distributed)
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
      for (VectorType *vector : distributed)
        hanging.distribute(*vector);
    }

  private:
    std::unique_ptr<parallel::distributed::SolutionTransfer<dim, VectorType>> transfer;
  };
} // namespace viscofilm

#endif
