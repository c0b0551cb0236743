// Geometric multigrid for the Stokes velocity block (Stokes solver/
// Preconditioner/Velocity preconditioner = GMG): matrix-free level operators
// on a sequence of globally coarsened meshes (doc/numerics.md).
#ifndef viscofilm_stokes_velocity_multigrid_h
#define viscofilm_stokes_velocity_multigrid_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <viscofilm/geometry/boundary_conditions.h>

#include <memory>

namespace viscofilm
{
  using namespace dealii;

  /**
   * One V-cycle for (m u, v) + (2 η D(u), D(v)), the velocity block A of the
   * Stokes system, as its approximate inverse: Chebyshev smoothing (Jacobi)
   * with matrix-free Q2 operators on every level of the globally coarsened
   * mesh sequence, CG with AMG on the coarse mesh. η is the system's at the
   * quadrature points on the active mesh and the mean of the children's
   * cell means on coarser ones. Each level has the active
   * mesh's hanging-node and (homogeneous) velocity constraints, so every
   * boundary type is treated as in the system, periodic pairs excepted.
   */
  template <int dim>
  class VelocityMultigrid
  {
  public:
    VelocityMultigrid(const BoundaryConditions<dim> &boundary_conditions,
                      const unsigned int             smoother_degree);
    ~VelocityMultigrid();

    /// After a mesh change: the level meshes, their dofs, constraints and
    /// transfers, and the map from @p stokes_dofs' velocity dofs (whose
    /// locally owned ones are @p owned_velocity) to the finest level's.
    void
    reinit(const DoFHandler<dim> &stokes_dofs, const IndexSet &owned_velocity);

    /// 2η (η with the implicit elastic viscosity) at the QGauss(3) points
    /// of the locally owned active cell @p cell (of the Stokes DoFHandler),
    /// their weights @p JxW.
    void
    set_cell_viscosity(const typename DoFHandler<dim>::active_cell_iterator &cell,
                       const std::vector<double> &                           viscosity,
                       const std::vector<double> &                           JxW);

    /// The level operators with the cell viscosities set since the last
    /// build and the mass coefficient @p mass (Res/k), their smoothers and
    /// the coarse solver.
    void
    build(const double mass);

    /// dst := one V-cycle applied to src (velocity block vectors).
    void
    vmult(TrilinosWrappers::MPI::Vector &dst, const TrilinosWrappers::MPI::Vector &src) const;

  private:
    struct Levels;
    const BoundaryConditions<dim> &boundary_conditions;
    const unsigned int             smoother_degree;
    std::unique_ptr<Levels>        levels;
  };
} // namespace viscofilm

#endif
