#include <viscofilm/core/field.h>

namespace viscofilm
{
  template <int dim, typename VectorType>
  Field<dim, VectorType>::Field(const Triangulation<dim> &triangulation, const Mapping<dim> &mapping)
    : cell_mapping(mapping)
    , dofs(triangulation)
    , carried{&current_solution}
  {}


  template <int dim, typename VectorType>
  const DoFHandler<dim> &
  Field<dim, VectorType>::dof_handler() const
  {
    return dofs;
  }


  template <int dim, typename VectorType>
  const Mapping<dim> &
  Field<dim, VectorType>::mapping() const
  {
    return cell_mapping;
  }


  template <int dim, typename VectorType>
  const VectorType &
  Field<dim, VectorType>::solution() const
  {
    return current_solution;
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::carry(VectorType &ghosted)
  {
    carried.push_back(&ghosted);
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::setup_vectors(const Partitioning &owned,
                                        const Partitioning &relevant)
  {
    owned_partitioning    = owned;
    relevant_partitioning = relevant;
    const MPI_Comm comm   = dofs.get_communicator();
    current_solution.reinit(owned, relevant, comm);
    old_solution.reinit(owned, relevant, comm);
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::transferred(VectorType &)
  {}


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::prepare_for_refinement()
  {
    carrier.prepare(dofs, std::vector<const VectorType *>(carried.begin(), carried.end()));
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::finish_refinement()
  {
    this->setup_dofs();
    const MPI_Comm          comm = dofs.get_communicator();
    std::vector<VectorType> distributed(carried.size(), VectorType(owned_partitioning, comm));
    std::vector<VectorType *> targets;
    for (VectorType &vector : distributed)
      targets.push_back(&vector);
    carrier.finish(dofs, targets);
    transferred(distributed[0]);
    for (unsigned int i = 0; i < carried.size(); ++i)
      {
        carried[i]->reinit(owned_partitioning, relevant_partitioning, comm);
        *carried[i] = distributed[i];
      }
    old_solution = current_solution;
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::prepare_for_checkpoint()
  {
    carrier.prepare_checkpoint(dofs,
                               std::vector<const VectorType *>(carried.begin(), carried.end()));
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::checkpoint_written()
  {
    carrier.release();
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::advance_time()
  {
    old_solution = current_solution;
  }


  template <int dim, typename VectorType>
  void
  Field<dim, VectorType>::restore_old()
  {
    current_solution = old_solution;
  }


#define INSTANTIATE(dim)                                            \
  template class Field<dim, TrilinosWrappers::MPI::Vector>;        \
  template class Field<dim, TrilinosWrappers::MPI::BlockVector>;
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
