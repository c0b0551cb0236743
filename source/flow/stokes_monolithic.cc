// Stokes solver/Method = direct and thesis: the whole saddle-point system as
// one matrix, factorised (Amesos MUMPS or KLU) or solved by the thesis'
// GMRES with ILU(0), a baseline for benchmarks.
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/affine_constraints.templates.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <viscofilm/flow/stokes_linear_solver.h>

namespace viscofilm
{
  namespace
  {
    /// The matrix and the copies between the block vectors and one vector;
    /// the solve itself is the derived class'.
    template <int dim>
    class Monolithic : public StokesLinearSolver<dim>
    {
    public:
      explicit Monolithic(const typename StokesFlow<dim>::Parameters &parameters)
        : parameters(parameters)
      {}

      /// A factorisation needs a nonsingular matrix; so does ILU.
      bool
      pins_pressure() const override
      {
        return true;
      }

      void
      reinit(const DoFHandler<dim> &           dofs,
             const AffineConstraints<double> & constraints,
             const std::vector<IndexSet> &     ,
             const std::vector<IndexSet> &     ) override
      {
        owned            = dofs.locally_owned_dofs();
        mpi_communicator = dofs.get_communicator();
        matrix.clear();
        TrilinosWrappers::SparsityPattern sparsity(owned,
                                                   owned,
                                                   DoFTools::extract_locally_relevant_dofs(dofs),
                                                   mpi_communicator);
        DoFTools::make_sparsity_pattern(dofs,
                                        sparsity,
                                        constraints,
                                        false,
                                        Utilities::MPI::this_mpi_process(mpi_communicator));
        sparsity.compress();
        matrix.reinit(sparsity);
      }

      void
      start_matrix(StokesViscosity<dim> &) override
      {
        matrix = 0;
      }

      void
      add_cell_matrix(const StokesCellMatrix<dim> &    cell,
                      const AffineConstraints<double> &constraints) override
      {
        constraints.distribute_local_to_global(cell.matrix, cell.dof_indices, matrix);
      }

      void
      finish_matrix() override
      {
        matrix.compress(VectorOperation::add);
      }

      unsigned int
      solve(const TrilinosWrappers::MPI::BlockVector &rhs,
            const TrilinosWrappers::MPI::BlockVector &guess,
            const AffineConstraints<double> &,
            TrilinosWrappers::MPI::BlockVector &solution,
            const double                        tolerance) override
      {
        TrilinosWrappers::MPI::Vector b(owned, mpi_communicator);
        TrilinosWrappers::MPI::Vector x(owned, mpi_communicator);
        for (const auto i : owned)
          {
            b(i) = rhs(i);
            x(i) = guess(i);
          }
        b.compress(VectorOperation::insert);
        x.compress(VectorOperation::insert);
        const unsigned int iterations = solve_system(x, b, tolerance);
        for (const auto i : owned)
          solution(i) = x(i);
        solution.compress(VectorOperation::insert);
        return iterations;
      }

    protected:
      virtual unsigned int
      solve_system(TrilinosWrappers::MPI::Vector &      x,
                   const TrilinosWrappers::MPI::Vector &b,
                   double                               tolerance) = 0;

      const typename StokesFlow<dim>::Parameters &parameters;
      TrilinosWrappers::SparseMatrix  matrix;

    private:
      IndexSet owned;
      MPI_Comm mpi_communicator = MPI_COMM_SELF;
    };


    /// Sparse LU (Amesos: MUMPS or KLU) of the whole system, factorised once
    /// per assembled matrix: the Picard iterations of a step, which change
    /// only the right-hand side, reuse it.
    template <int dim>
    class Direct : public Monolithic<dim>
    {
    public:
      using Monolithic<dim>::Monolithic;

      void
      finish_matrix() override
      {
        Monolithic<dim>::finish_matrix();
        factorization.reset();
      }

    protected:
      unsigned int
      solve_system(TrilinosWrappers::MPI::Vector &x,
                   const TrilinosWrappers::MPI::Vector &b,
                   double) override
      {
        if (!factorization)
          {
            factorization = std::make_unique<TrilinosWrappers::SolverDirect>(
              control,
              TrilinosWrappers::SolverDirect::AdditionalData(false,
                                                             this->parameters.direct_solver));
            factorization->initialize(this->matrix);
          }
        factorization->solve(x, b);
        return 0;
      }

    private:
      SolverControl                                   control{1, 0};
      std::unique_ptr<TrilinosWrappers::SolverDirect> factorization;
    };


    /// The thesis' solver: GMRES(100) with ILU(0) of the whole system.
    template <int dim>
    class Thesis : public Monolithic<dim>
    {
    public:
      using Monolithic<dim>::Monolithic;

    protected:
      unsigned int
      solve_system(TrilinosWrappers::MPI::Vector &      x,
                   const TrilinosWrappers::MPI::Vector &b,
                   const double                         tolerance) override
      {
        // The zero pressure diagonal needs the absolute diagonal shift
        // ilu_atol to factorise.
        TrilinosWrappers::PreconditionILU ilu;
        ilu.initialize(this->matrix, TrilinosWrappers::PreconditionILU::AdditionalData(0, 1e-8));
        SolverControl control(this->parameters.max_iterations, tolerance * b.l2_norm());
        TrilinosWrappers::SolverGMRES solver(
          control, TrilinosWrappers::SolverGMRES::AdditionalData(false, 100));
        try
          {
            solver.solve(this->matrix, x, b, ilu);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            throw ExcMessage("the Stokes solver (thesis: GMRES + ILU) did not "
                             "converge in " +
                             std::to_string(e.last_step) + " iterations: residual " +
                             Utilities::to_string(e.last_residual) +
                             " (Stokes solver/Maximum iterations = " +
                             std::to_string(this->parameters.max_iterations) + ")");
          }
        return control.last_step();
      }
    };
  } // namespace


  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  make_direct_solver(const typename StokesFlow<dim>::Parameters &parameters)
  {
    return std::make_unique<Direct<dim>>(parameters);
  }


  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  make_thesis_solver(const typename StokesFlow<dim>::Parameters &parameters)
  {
    return std::make_unique<Thesis<dim>>(parameters);
  }


#define INSTANTIATE(dim)                                                  \
  template std::unique_ptr<StokesLinearSolver<dim>> make_direct_solver<dim>( \
    const typename StokesFlow<dim>::Parameters &);                                 \
  template std::unique_ptr<StokesLinearSolver<dim>> make_thesis_solver<dim>( \
    const typename StokesFlow<dim>::Parameters &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
