// The vectorized half of the velocity block's geometric multigrid
// (stokes_velocity_multigrid.h): the matrix-free level operators, their
// Chebyshev smoothers, the coarse solve and the V-cycle. Its source is
// compiled with SIMD (VISCOFILM_SIMD_BITS, CMakeLists.txt) although Debian's
// deal.II is not, so this interface holds no type whose layout depends on
// deal.II's vectorization width (VectorizedArray<double>, MatrixFree<dim,
// double>, MGTwoLevelTransfer): the mesh sequence, the constraints and the
// transfers stay in stokes_velocity_multigrid.cc, compiled like the library.
#ifndef viscofilm_stokes_velocity_multigrid_levels_h
#define viscofilm_stokes_velocity_multigrid_levels_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/multigrid/mg_base.h>
#include <deal.II/base/mg_level_object.h>

#include <functional>
#include <memory>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class VelocityMultigridLevels
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /// Fills 2η at the QGauss(3) points (lexicographic) of @p cell of the
    /// level @p level.
    using Viscosity = std::function<void(const unsigned int                            level,
                                         const typename DoFHandler<dim>::cell_iterator &cell,
                                         std::vector<double> &                          values)>;

    /// The level operators on @p dofs (FE_Q(2)^dim) with @p constraints.
    VelocityMultigridLevels(const MGLevelObject<DoFHandler<dim>> &          dofs,
                            const MGLevelObject<AffineConstraints<double>> &constraints,
                            const unsigned int                              smoother_degree);
    ~VelocityMultigridLevels();

    void
    initialize_dof_vector(const unsigned int level, VectorType &vector) const;

    /// The operators with @p viscosity and the mass coefficient @p mass
    /// (Res/k), their smoothers, the coarse solve and the V-cycle over
    /// @p transfer, which must outlive the V-cycle.
    void
    build(const double                       mass,
          const Viscosity &                  viscosity,
          const MGTransferBase<VectorType> & transfer);

    /// dst := one V-cycle applied to src (finest-level vectors).
    void
    vmult(VectorType &dst, const VectorType &src) const;

  private:
    struct Data;
    const MGLevelObject<AffineConstraints<double>> &constraints;
    const unsigned int                              smoother_degree;
    std::unique_ptr<Data>                           data;
  };
} // namespace viscofilm

#endif
