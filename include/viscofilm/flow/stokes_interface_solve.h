// The velocity block's exact solve on the biofilm's edge (Stokes solver/
// Preconditioner/Interface solve viscosity ratio): what lets the block
// preconditioner converge at viscosity contrasts of 1e4 and more in 2D
// (doc/numerics-stokes.md, "Sharp viscosity contrasts").
#ifndef viscofilm_stokes_interface_solve_h
#define viscofilm_stokes_interface_solve_h

#include <deal.II/base/index_set.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /**
   * A sparse LU of the velocity block A restricted to a band of dofs along
   * the edge of the high-viscosity region: the dofs of cells whose η exceeds
   * a multiple of the water's that couple to a dof outside them, and those
   * that couple to these (two rings on the viscous side). Multigrid cycles,
   * rediscretised or algebraic, leave tens of error modes at such an edge
   * unreduced (their coarse spaces cannot follow a jump of η by 1e6 within
   * one cell); the band solve removes them. Its cost grows with the edge's
   * area, not with the region's volume.
   */
  class InterfaceSolve
  {
  public:
    /// After a mesh change: the columns of @p matrix's (the velocity block's)
    /// locally owned rows, where build() reads the flags; with hanging nodes
    /// they may reach beyond the locally relevant dofs.
    void
    reinit(const TrilinosWrappers::SparseMatrix &matrix);

    /// Select the band of @p matrix (the velocity block) among the dofs
    /// flagged in @p viscous (a vector of the block's layout, non-zero at
    /// the dofs of the high-viscosity cells) and factorise its submatrix
    /// with the Amesos package @p direct_solver. An empty band leaves the
    /// solve off.
    void
    build(const TrilinosWrappers::SparseMatrix &matrix,
          const TrilinosWrappers::MPI::Vector & viscous,
          const std::string &                   direct_solver);

    /// Whether build() found a band.
    bool
    active() const
    {
      return factorization != nullptr;
    }

    /// dst += Rᵀ B⁻¹ R src: the band's exact solve with the residual @p src.
    void
    add_solve(TrilinosWrappers::MPI::Vector &dst, const TrilinosWrappers::MPI::Vector &src) const;

  private:
    /// The locally owned band dofs' positions in the owned part of the
    /// block's vectors, in the band's order.
    std::vector<types::global_dof_index>            band_positions;
    IndexSet                                        columns;
    TrilinosWrappers::SparseMatrix                  band_matrix;
    SolverControl                                   control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> factorization;
    mutable TrilinosWrappers::MPI::Vector           band_rhs, band_solution;
  };


  /**
   * The multigrid cycle @p Inner with the interface solve around it, as a
   * symmetric multiplicative (block Gauss–Seidel) correction: band solve,
   * cycle on the new residual, band solve on the next one. Symmetric, so
   * it serves the inner CG as well as FGMRES.
   */
  template <class Inner>
  class WithInterfaceSolve
  {
  public:
    WithInterfaceSolve(const Inner &                         inner,
                       const InterfaceSolve &                band,
                       const TrilinosWrappers::SparseMatrix &matrix)
      : inner(inner)
      , band(band)
      , matrix(matrix)
    {}

    void
    vmult(TrilinosWrappers::MPI::Vector &dst, const TrilinosWrappers::MPI::Vector &src) const
    {
      if (residual.size() != src.size())
        {
          residual.reinit(src, true);
          correction.reinit(src, true);
        }
      dst = 0;
      band.add_solve(dst, src);
      update_residual(dst, src);
      inner.vmult(correction, residual);
      dst += correction;
      update_residual(dst, src);
      band.add_solve(dst, residual);
    }

  private:
    /// residual = src − A dst.
    void
    update_residual(const TrilinosWrappers::MPI::Vector &dst,
                    const TrilinosWrappers::MPI::Vector &src) const
    {
      matrix.vmult(residual, dst);
      residual.sadd(-1.0, src);
    }

    const Inner &                                 inner;
    const InterfaceSolve &                        band;
    const TrilinosWrappers::SparseMatrix &        matrix;
    mutable TrilinosWrappers::MPI::Vector         residual, correction;
  };
} // namespace viscofilm

#endif
