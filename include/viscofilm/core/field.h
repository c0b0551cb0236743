// What every field (u and p, c, φ, φ_d) shares: a DoFHandler on the one mesh,
// its constraints, the solution at t_{n+1} and at t_n, and their life cycle
// through a time step, a mesh change and a checkpoint. The numerics stay in
// the fields' own classes; Problem loops over its fields for the life cycle.
#ifndef viscofilm_field_h
#define viscofilm_field_h

#include <deal.II/base/index_set.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/core/reporter.h>
#include <viscofilm/core/solution_carrier.h>

#include <type_traits>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// The life cycle of a field, what Problem calls on each of its fields;
  /// a field reports (Reporter) when Problem lists it among its reporters.
  template <int dim>
  class FieldBase : public Reporter<dim>
  {
  public:
    virtual ~FieldBase() = default;

    /// Distribute the dofs, build the constraints, the vectors (zero) and
    /// the class's matrices.
    virtual void
    setup_dofs() = 0;

    /// Before the triangulation's execute_coarsening_and_refinement().
    virtual void
    prepare_for_refinement() = 0;
    /// After it, and after a checkpoint's mesh was loaded: the dofs set up
    /// anew, the carried vectors on them, old := new.
    virtual void
    finish_refinement() = 0;
    /// Before the triangulation's save(); checkpoint_written() after it.
    virtual void
    prepare_for_checkpoint() = 0;
    virtual void
    checkpoint_written() = 0;

    /// An accepted step: old := new (t_n := t_{n+1}).
    virtual void
    advance_time() = 0;
    /// A rejected step: new := old.
    virtual void
    restore_old() = 0;
  };


  /**
   * A field's DoFHandler, constraints and ghosted vectors (the solution at
   * t_{n+1} and at t_n) and the life cycle of FieldBase on them. A class
   * derives from it, implements setup_dofs() (calling setup_vectors()) and
   * adds to a hook what is its own (φ's range through a mesh change, c's
   * positivity, u^{n-1}).
   */
  template <int dim, typename VectorType>
  class Field : public FieldBase<dim>
  {
  public:
    /// The dofs owned and relevant on this rank: an IndexSet, or one per
    /// block of a block vector.
    using Partitioning =
      std::conditional_t<std::is_same_v<VectorType, TrilinosWrappers::MPI::BlockVector>,
                         std::vector<IndexSet>,
                         IndexSet>;

    const DoFHandler<dim> &
    dof_handler() const;

    /// The map from the reference cell (Problem's, one for every field).
    const Mapping<dim> &
    mapping() const;

    /// The solution at t_{n+1} (the current iterate) with ghost values.
    const VectorType &
    solution() const;

    /// Carry @p ghosted, a vector of another component on this field's dofs
    /// (the detachment's clock), through mesh changes and checkpoints: it is
    /// reinitialised and refilled by finish_refinement().
    void
    carry(VectorType &ghosted);

    void
    prepare_for_refinement() override;
    void
    finish_refinement() override;
    void
    prepare_for_checkpoint() override;
    void
    checkpoint_written() override;
    void
    advance_time() override;
    void
    restore_old() override;

  protected:
    Field(const Triangulation<dim> &triangulation, const Mapping<dim> &mapping);

    /// After the dofs are distributed: the partitionings, and the solution
    /// at t_{n+1} and t_n laid out on them (zero).
    void
    setup_vectors(const Partitioning &owned, const Partitioning &relevant);

    /// The solution's values on the new mesh (owned, hanging nodes
    /// distributed), before they become the solution at t_{n+1} and t_n:
    /// a class corrects them here. Nothing by default.
    virtual void
    transferred(VectorType &distributed);

    const Mapping<dim> &      cell_mapping;
    DoFHandler<dim>           dofs;
    IndexSet                  locally_relevant_dofs;
    Partitioning              owned_partitioning;
    Partitioning              relevant_partitioning;
    AffineConstraints<double> constraints;
    VectorType                current_solution; // ghosted, t_{n+1}
    VectorType                old_solution;     // ghosted, t_n

  private:
    /// The vectors carried through a mesh change, the solution first (a
    /// checkpoint stores them in this order), and their carrier.
    std::vector<VectorType *>         carried;
    SolutionCarrier<dim, VectorType> carrier;
  };
} // namespace viscofilm

#endif
