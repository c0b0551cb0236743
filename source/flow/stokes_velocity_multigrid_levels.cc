// The vectorized half of the velocity block's geometric multigrid
// (stokes_velocity_multigrid_levels.h). Debian's deal.II 9.4.1 is configured
// without SIMD (DEAL_II_VECTORIZATION_WIDTH_IN_BITS 0), which makes a
// matrix-free Q2 operator cost about what a sparse one does (doc/performance.md,
// session 27). This file alone raises the width to VISCOFILM_SIMD_BITS (256 with
// AVX2 where the build machine runs it, else 128 with x86-64's SSE2;
// CMakeLists.txt) and instantiates the matrix-free templates the library holds
// only for width 1 (benchmarks/matrix_free_simd measured 2.4x in 2D, 3.8x in 3D).
#include <deal.II/base/config.h>
#if VISCOFILM_SIMD_BITS > 0
#  undef DEAL_II_VECTORIZATION_WIDTH_IN_BITS
#  define DEAL_II_VECTORIZATION_WIDTH_IN_BITS VISCOFILM_SIMD_BITS
#endif

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/matrix_free/operators.h>
#include <deal.II/matrix_free/tools.h>

#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/multigrid.h>

#if VISCOFILM_SIMD_BITS > 0
#  include <deal.II/matrix_free/mapping_info.templates.h>
#  include <deal.II/matrix_free/matrix_free.templates.h>
#  include <deal.II/matrix_free/shape_info.templates.h>
#  define FE_EVAL_FACTORY_DEGREE_MAX 2
#  include <deal.II/matrix_free/evaluation_template_factory.templates.h>
// deal.II 9.4 gives the cell and face factories' templates one include guard.
#  undef dealii_matrix_free_evaluation_template_factory_templates_h
#  include <deal.II/matrix_free/evaluation_template_face_factory.templates.h>
#  include <deal.II/matrix_free/evaluation_template_factory_hanging_nodes.templates.h>
#endif

#include <viscofilm/core/dimension.h>
#include <viscofilm/flow/stokes_velocity_multigrid_levels.h>

#include <algorithm>

namespace
{
  // Named explicitly: deal.II's default width is fixed in config.h, before
  // the macro above is raised.
  using Number = dealii::VectorizedArray<double, std::max(VISCOFILM_SIMD_BITS / 64, 1)>;
} // namespace

#if VISCOFILM_SIMD_BITS > 0
#  define VISCOFILM_INSTANTIATE_MATRIX_FREE(dim)                                             \
    template class dealii::MatrixFree<dim, double, Number>;                                  \
    template struct dealii::internal::MatrixFreeFunctions::MappingInfo<dim, double, Number>; \
    template struct dealii::internal::FEEvaluationFactory<dim, Number>;                      \
    template struct dealii::internal::FEFaceEvaluationFactory<dim, Number>;                  \
    template struct dealii::internal::FEEvaluationHangingNodesFactory<dim, double, Number>;
template struct dealii::internal::MatrixFreeFunctions::ShapeInfo<Number>;
VISCOFILM_INSTANTIATE_MATRIX_FREE(2)
VISCOFILM_INSTANTIATE_MATRIX_FREE(3)
#endif

namespace viscofilm
{
  namespace
  {
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /// (m u, v) + (2η D(u), D(v)) with Q2 velocities, η given per quadrature
    /// point.
    template <int dim>
    class ViscousOperator : public MatrixFreeOperators::Base<dim, VectorType, Number>
    {
    public:
      using Evaluation = FEEvaluation<dim, 2, 3, dim, double, Number>;

      /// @p viscosity: 2η per cell batch and quadrature point of the
      /// matrix-free data.
      void
      set_coefficients(Table<2, Number> &&viscosity, const double mass)
      {
        this->viscosity = std::move(viscosity);
        this->mass      = mass;
      }

      void
      compute_diagonal() override
      {
        this->inverse_diagonal_entries = std::make_shared<DiagonalMatrix<VectorType>>();
        VectorType &diagonal           = this->inverse_diagonal_entries->get_vector();
        this->data->initialize_dof_vector(diagonal);
        MatrixFreeTools::compute_diagonal(*this->data,
                                          diagonal,
                                          &ViscousOperator::apply_cell,
                                          this);
        // Constrained rows are the identity (Base::vmult).
        for (double &entry : diagonal)
          entry = (entry > 0 ? 1.0 / entry : 1.0);
      }

      /// The level's matrix, for the coarse mesh's AMG.
      void
      compute_matrix(const AffineConstraints<double> &constraints,
                     TrilinosWrappers::SparseMatrix & matrix) const
      {
        const DoFHandler<dim> &dofs = this->data->get_dof_handler();
        TrilinosWrappers::SparsityPattern sparsity(dofs.locally_owned_dofs(),
                                                   dofs.get_communicator());
        DoFTools::make_sparsity_pattern(dofs, sparsity, constraints, false);
        sparsity.compress();
        matrix.reinit(sparsity);
        MatrixFreeTools::compute_matrix(
          *this->data, constraints, matrix, &ViscousOperator::apply_cell, this);
      }

      void
      apply_cell(Evaluation &velocity) const
      {
        const unsigned int cell      = velocity.get_current_cell_index();
        const bool         with_mass = (mass != 0);
        velocity.evaluate(with_mass ? EvaluationFlags::values | EvaluationFlags::gradients :
                                      EvaluationFlags::gradients);
        for (unsigned int q = 0; q < velocity.n_q_points; ++q)
          {
            velocity.submit_symmetric_gradient(viscosity(cell, q) *
                                                 velocity.get_symmetric_gradient(q),
                                               q);
            if (with_mass)
              velocity.submit_value(mass * velocity.get_value(q), q);
          }
        velocity.integrate(with_mass ? EvaluationFlags::values | EvaluationFlags::gradients :
                                       EvaluationFlags::gradients);
      }

    private:
      void
      apply_add(VectorType &dst, const VectorType &src) const override
      {
        this->data->cell_loop(&ViscousOperator::apply_cells, this, dst, src);
      }

      void
      apply_cells(const MatrixFree<dim, double, Number> &             data,
                  VectorType &                                dst,
                  const VectorType &                          src,
                  const std::pair<unsigned int, unsigned int> &cells) const
      {
        Evaluation velocity(data);
        for (unsigned int cell = cells.first; cell < cells.second; ++cell)
          {
            velocity.reinit(cell);
            velocity.read_dof_values(src);
            apply_cell(velocity);
            velocity.distribute_local_to_global(dst);
          }
      }

      Table<2, Number> viscosity;
      double                            mass = 0;
    };


    /// CG with AMG on the coarse mesh, to a residual reduction of 1e-4. Its
    /// failure is reported as its own: a SolverControl::NoConvergence let
    /// through would be taken for the outer FGMRES's.
    template <int dim>
    class CoarseSolve : public MGCoarseGridBase<VectorType>
    {
    public:
      CoarseSolve(const ViscousOperator<dim> &operator_, TrilinosWrappers::SparseMatrix &&matrix)
        : level_operator(operator_)
        , matrix(std::move(matrix))
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
        DoFTools::extract_constant_modes(level_operator.get_matrix_free()->get_dof_handler(),
                                         ComponentMask(dim, true),
                                         amg_data.constant_modes);
        amg_data.elliptic              = true;
        amg_data.higher_order_elements = true;
        amg.initialize(this->matrix, amg_data);
      }

      void
      operator()(const unsigned int, VectorType &dst, const VectorType &src) const override
      {
        ReductionControl     control(max_iterations, 1e-14, 1e-4);
        SolverCG<VectorType> cg(control);
        dst = 0;
        try
          {
            cg.solve(level_operator, dst, src, amg);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            AssertThrow(false,
                        ExcMessage("the geometric multigrid's coarse-mesh solve (CG with AMG, " +
                                   std::to_string(matrix.m()) +
                                   " velocity dofs) did not converge in " +
                                   std::to_string(max_iterations) + " iterations: residual " +
                                   Utilities::to_string(e.last_residual) +
                                   " (Stokes solver/Preconditioner/Velocity "
                                   "preconditioner = GMG; AMG is the robust choice)"));
          }
      }

    private:
      static constexpr unsigned int     max_iterations = 1000;
      const ViscousOperator<dim> &      level_operator;
      TrilinosWrappers::SparseMatrix    matrix;
      TrilinosWrappers::PreconditionAMG amg;
    };


    /// PreconditionMG's copies between the finest level and the global
    /// vector (the same partition), as MGTransferGlobalCoarsening's, which
    /// stays in the unvectorized file.
    template <int dim>
    class FinestLevelCopy : public Subscriptor
    {
    public:
      explicit FinestLevelCopy(const MGLevelObject<std::unique_ptr<ViscousOperator<dim>>> &operators)
        : operators(operators)
      {}

      void
      copy_to_mg(const DoFHandler<dim> &, MGLevelObject<VectorType> &dst, const VectorType &src) const
      {
        for (unsigned int level = dst.min_level(); level <= dst.max_level(); ++level)
          {
            operators[level]->initialize_dof_vector(dst[level]);
            if (level == dst.max_level())
              dst[level].copy_locally_owned_data_from(src);
            else
              dst[level] = 0.0;
          }
      }

      void
      copy_from_mg(const DoFHandler<dim> &, VectorType &dst, const MGLevelObject<VectorType> &src) const
      {
        dst.copy_locally_owned_data_from(src[src.max_level()]);
      }

    private:
      const MGLevelObject<std::unique_ptr<ViscousOperator<dim>>> &operators;
    };
  } // namespace


  template <int dim>
  struct VelocityMultigridLevels<dim>::Data
  {
    using Smoother = PreconditionChebyshev<ViscousOperator<dim>, VectorType, DiagonalMatrix<VectorType>>;

    explicit Data(const unsigned int min, const unsigned int max)
      : operators(min, max)
      , copy(operators)
    {}

    MGLevelObject<std::unique_ptr<ViscousOperator<dim>>>                operators;
    FinestLevelCopy<dim>                                                copy;
    std::unique_ptr<mg::Matrix<VectorType>>                             level_matrices;
    MGSmootherPrecondition<ViscousOperator<dim>, Smoother, VectorType> smoother;
    std::unique_ptr<CoarseSolve<dim>>                                   coarse;
    std::unique_ptr<Multigrid<VectorType>>                              multigrid;
    std::unique_ptr<PreconditionMG<dim, VectorType, FinestLevelCopy<dim>>> preconditioner;
  };


  template <int dim>
  VelocityMultigridLevels<dim>::VelocityMultigridLevels(
    const MGLevelObject<DoFHandler<dim>> &          dofs,
    const MGLevelObject<AffineConstraints<double>> &constraints,
    const unsigned int                              smoother_degree)
    : constraints(constraints)
    , smoother_degree(smoother_degree)
    , data(std::make_unique<Data>(dofs.min_level(), dofs.max_level()))
  {
    const MappingQ1<dim>                             mapping;
    typename MatrixFree<dim, double, Number>::AdditionalData additional_data;
    additional_data.tasks_parallel_scheme = MatrixFree<dim, double, Number>::AdditionalData::none;
    additional_data.mapping_update_flags  = update_values | update_gradients | update_JxW_values;
    for (unsigned int l = dofs.min_level(); l <= dofs.max_level(); ++l)
      {
        auto matrix_free = std::make_shared<MatrixFree<dim, double, Number>>();
        matrix_free->reinit(mapping, dofs[l], constraints[l], QGauss<1>(3), additional_data);
        data->operators[l] = std::make_unique<ViscousOperator<dim>>();
        data->operators[l]->initialize(matrix_free);
      }
  }


  template <int dim>
  VelocityMultigridLevels<dim>::~VelocityMultigridLevels() = default;


  template <int dim>
  void
  VelocityMultigridLevels<dim>::initialize_dof_vector(const unsigned int level,
                                                      VectorType &       vector) const
  {
    data->operators[level]->initialize_dof_vector(vector);
  }


  template <int dim>
  void
  VelocityMultigridLevels<dim>::build(const double                      mass,
                                      const Viscosity &                 viscosity,
                                      const MGTransferBase<VectorType> &transfer)
  {
    Data &             D   = *data;
    const unsigned int min = D.operators.min_level(), max = D.operators.max_level();
    MGLevelObject<typename Data::Smoother::AdditionalData> smoother_data(min, max);
    const unsigned int                                     n_points = Utilities::pow(3, dim);
    std::vector<double>                                    values(n_points);
    for (unsigned int l = min; l <= max; ++l)
      {
        const MatrixFree<dim, double, Number> &   matrix_free = *D.operators[l]->get_matrix_free();
        Table<2, Number> coefficient(matrix_free.n_cell_batches(), n_points);
        for (unsigned int batch = 0; batch < matrix_free.n_cell_batches(); ++batch)
          for (unsigned int v = 0; v < matrix_free.n_active_entries_per_cell_batch(batch); ++v)
            {
              viscosity(l, matrix_free.get_cell_iterator(batch, v), values);
              for (unsigned int q = 0; q < n_points; ++q)
                coefficient(batch, q)[v] = values[q];
            }
        D.operators[l]->set_coefficients(std::move(coefficient), mass);
        D.operators[l]->compute_diagonal();
        smoother_data[l].preconditioner      = D.operators[l]->get_matrix_diagonal_inverse();
        smoother_data[l].degree              = smoother_degree;
        smoother_data[l].smoothing_range     = 20;
        smoother_data[l].eig_cg_n_iterations = 10;
      }
    D.level_matrices = std::make_unique<mg::Matrix<VectorType>>(D.operators);
    D.smoother.initialize(D.operators, smoother_data);

    TrilinosWrappers::SparseMatrix coarse_matrix;
    D.operators[min]->compute_matrix(constraints[min], coarse_matrix);
    D.coarse    = std::make_unique<CoarseSolve<dim>>(*D.operators[min], std::move(coarse_matrix));
    D.multigrid = std::make_unique<Multigrid<VectorType>>(
      *D.level_matrices, *D.coarse, transfer, D.smoother, D.smoother, min, max);
    D.preconditioner = std::make_unique<PreconditionMG<dim, VectorType, FinestLevelCopy<dim>>>(
      D.operators[max]->get_matrix_free()->get_dof_handler(), *D.multigrid, D.copy);
  }


  template <int dim>
  void
  VelocityMultigridLevels<dim>::vmult(VectorType &dst, const VectorType &src) const
  {
    data->preconditioner->vmult(dst, src);
  }


  VISCOFILM_INSTANTIATE(VelocityMultigridLevels)
} // namespace viscofilm
