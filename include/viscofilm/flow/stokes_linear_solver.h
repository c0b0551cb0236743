// The linear-solver strategies of the Stokes system (doc/structure.md): the
// assembly (stokes_assembly.cc) hands each cell's matrix to the strategy,
// which keeps whatever matrices and preconditioners it needs and solves.
#ifndef viscofilm_stokes_linear_solver_h
#define viscofilm_stokes_linear_solver_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <viscofilm/flow/stokes.h>

#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// One cell's part of the Stokes matrix, as the assembly computed it: the
  /// copy data of its WorkStream, filled on a worker thread and handed to
  /// the strategy's add_cell_matrix() on one thread, in the order of the cells.
  template <int dim>
  struct StokesCellMatrix
  {
    typename DoFHandler<dim>::active_cell_iterator cell;
    /// JxW at the quadrature points; η there, the implicit elastic viscosity
    /// included, and that elastic part alone (zero without it).
    std::vector<double> JxW;
    std::vector<double> viscosity;
    std::vector<double> elastic_viscosity;
    /// Res/k (times the BDF2 factor): the coefficient of (u, v).
    double                               mass_coefficient = 0;
    std::vector<types::global_dof_index> dof_indices;
    FullMatrix<double>                   matrix;
    /// The strategy's own cell matrices, from add_cell_preconditioner() on
    /// the worker thread (the block preconditioner's (1/η) M_p and, with a
    /// mass term, the pressure Laplacian (∇q, ∇p)); empty otherwise.
    FullMatrix<double> preconditioner_matrix;
    FullMatrix<double> pressure_laplacian;
  };


  /**
   * What a strategy knows of the rheology: the system's viscosity η as the
   * assembly computes it (the model at the interpolated φ, averaged over the
   * cell as Viscosity averaging says; without the implicit elastic
   * viscosity), at quadrature points of the strategy's own (the block
   * preconditioner's Q1 sub-cell matrix). StokesFlow hands one to each
   * start_matrix(), valid until the next: a strategy may put off its use
   * until a preconditioner is built.
   */
  template <int dim>
  class StokesViscosity
  {
  public:
    virtual ~StokesViscosity() = default;

    /// η at the quadrature points of @p values, a strategy's FEValues
    /// reinitialized on a cell of the Stokes mesh; its JxW weigh the
    /// average. Not thread-safe: it may keep scratch for the quadrature.
    virtual void
    evaluate(const FEValues<dim> &values, std::vector<double> &viscosity) = 0;
  };


  /// How the Stokes system is solved: one class per Stokes solver/Method.
  template <int dim>
  class StokesLinearSolver
  {
  public:
    /// The strategy of @p method (not automatic: StokesFlow decides).
    /// @p reference_viscosity: ηs(φ = 0), of the block preconditioner's
    /// pressure scaling.
    static std::unique_ptr<StokesLinearSolver<dim>>
    create(const typename StokesFlow<dim>::Method      method,
           const typename StokesFlow<dim>::Parameters &parameters,
           const double                                  reference_viscosity,
           const BoundaryConditions<dim> &               boundary_conditions);

    virtual ~StokesLinearSolver() = default;

    /// Whether the pressure's level must be fixed by a constraint (a
    /// factorisation needs a nonsingular matrix) where no boundary fixes it.
    virtual bool
    pins_pressure() const = 0;

    /// New dofs: sparsity patterns and matrices; drops preconditioners.
    /// Block 0: the velocity, block 1: the pressure.
    virtual void
    reinit(const DoFHandler<dim> &           dofs,
           const AffineConstraints<double> & constraints,
           const std::vector<IndexSet> &     owned_partitioning,
           const std::vector<IndexSet> &     relevant_partitioning) = 0;

    /// A new matrix: zero, add every owned cell, finish. @p viscosity: the
    /// system's η at points of the strategy's own, until the next matrix.
    virtual void
    start_matrix(StokesViscosity<dim> &viscosity) = 0;
    /// On an assembly thread, beside the cell matrix: the strategy's own
    /// cell matrices from @p fe_values (Q2–Q1 or P1disc values and JxW on
    /// cell.cell) into @p cell. Reads nothing but its arguments and the
    /// parameters.
    virtual void
    add_cell_preconditioner(const FEValues<dim> &, StokesCellMatrix<dim> &) const
    {}
    /// On one thread, in the order of the cells: @p cell into the matrices.
    virtual void
    add_cell_matrix(const StokesCellMatrix<dim> &    cell,
                    const AffineConstraints<double> &constraints) = 0;
    virtual void
    finish_matrix() = 0;

    /// Solve for @p solution (owned entries) from the first guess @p guess
    /// (ghosted) to the relative residual @p tolerance; returns the outer
    /// Krylov iterations (0 if direct). Throws with the residual if it does
    /// not converge.
    virtual unsigned int
    solve(const TrilinosWrappers::MPI::BlockVector &rhs,
          const TrilinosWrappers::MPI::BlockVector &guess,
          const AffineConstraints<double> &         constraints,
          TrilinosWrappers::MPI::BlockVector &      solution,
          double                                    tolerance) = 0;

    /// Statistics of the velocity AMG (block preconditioned; 0 otherwise).
    virtual unsigned int
    n_preconditioner_builds() const;
    virtual double
    viscosity_change_since_build() const;
    /// "AMG" or "GMG" on the current mesh (block preconditioned; empty
    /// otherwise).
    virtual std::string
    velocity_preconditioner() const;
  };


  /// The strategies (stokes_block_preconditioned.cc, stokes_monolithic.cc).
  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  make_block_preconditioned_solver(const typename StokesFlow<dim>::Parameters &parameters,
                                   const double                    reference_viscosity,
                                   const BoundaryConditions<dim> & boundary_conditions);
  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  make_direct_solver(const typename StokesFlow<dim>::Parameters &parameters);
  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  make_thesis_solver(const typename StokesFlow<dim>::Parameters &parameters);
} // namespace viscofilm

#endif
