// The biofilm volume fraction φ on its own FE_Q(2) DoFHandler (MODEL.md §2).
#ifndef viscofilm_volume_fraction_h
#define viscofilm_volume_fraction_h

#include <deal.II/base/function.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

namespace viscofilm
{
  using namespace dealii;

  class VolumeFraction
  {
  public:
    explicit VolumeFraction(
      const parallel::distributed::Triangulation<2> &triangulation);

    void
    setup_dofs();

    /// φ := the interpolant of @p initial at the Q2 nodes.
    void
    interpolate(const Function<2> &initial);

    const DoFHandler<2> &
    dof_handler() const;

    /// φ with ghost values.
    const TrilinosWrappers::MPI::Vector &
    solution() const;

    /// ∫_Ω φ dx.
    double
    integral() const;

    /// Smallest and largest nodal value.
    std::pair<double, double>
    range() const;

  private:
    const MPI_Comm            mpi_communicator;
    const FE_Q<2>             fe;
    DoFHandler<2>             dofs;
    AffineConstraints<double> constraints;
    IndexSet                  locally_relevant_dofs;

    TrilinosWrappers::MPI::Vector current_solution; // ghosted
  };
} // namespace viscofilm

#endif
