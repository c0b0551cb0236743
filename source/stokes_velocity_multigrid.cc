// Geometric multigrid for the Stokes velocity block (doc/numerics.md, "The
// velocity block's geometric multigrid"): the deal.II step-75 pattern
// (global coarsening, matrix-free levels, Chebyshev smoothing, CG with AMG
// on the coarse mesh) with a cell-wise viscosity.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
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
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>

#include <viscofilm/dimension.h>
#include <viscofilm/stokes_velocity_multigrid.h>

namespace viscofilm
{
  namespace
  {
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /// (m u, v) + (2η D(u), D(v)) with Q2 velocities, η constant per cell.
    template <int dim>
    class ViscousOperator : public MatrixFreeOperators::Base<dim, VectorType>
    {
    public:
      using Evaluation = FEEvaluation<dim, 2, 3, dim, double>;

      /// @p viscosity: 2η per cell batch and quadrature point of the
      /// matrix-free data.
      void
      set_coefficients(Table<2, VectorizedArray<double>> &&viscosity, const double mass)
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
      apply_cells(const MatrixFree<dim, double> &             data,
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

      Table<2, VectorizedArray<double>> viscosity;
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
  } // namespace


  template <int dim>
  struct VelocityMultigrid<dim>::Levels
  {
    using Smoother = PreconditionChebyshev<ViscousOperator<dim>, VectorType, DiagonalMatrix<VectorType>>;
    using Transfer = MGTransferGlobalCoarsening<dim, VectorType>;

    std::vector<std::shared_ptr<const Triangulation<dim>>> triangulations;
    unsigned int                                           min = 0, max = 0;
    MGLevelObject<DoFHandler<dim>>                         dofs;
    /// FE_DGQ(0) on each level: the cell mean of 2η, restricted from level
    /// to level.
    MGLevelObject<DoFHandler<dim>>                    cell_dofs;
    MGLevelObject<VectorType>                         viscosity;
    /// 2η at the quadrature points of each locally owned active cell (by its
    /// FE_DGQ(0) dof's local index): the finest level's coefficient.
    std::vector<std::vector<double>>                  point_viscosity;
    MGLevelObject<AffineConstraints<double>>          constraints;
    MGLevelObject<MGTwoLevelTransfer<dim, VectorType>> transfers;
    MGLevelObject<MGTwoLevelTransfer<dim, VectorType>> cell_transfers;
    std::unique_ptr<Transfer>                          transfer;
    MGLevelObject<std::unique_ptr<ViscousOperator<dim>>> operators;

    /// The finest level's local index of each locally owned Stokes velocity
    /// dof (by its position in the owned index set).
    std::vector<unsigned int> fine_index;

    std::unique_ptr<mg::Matrix<VectorType>>                                 level_matrices;
    MGSmootherPrecondition<ViscousOperator<dim>, Smoother, VectorType>     smoother;
    std::unique_ptr<CoarseSolve<dim>>                                       coarse;
    std::unique_ptr<Multigrid<VectorType>>                                  multigrid;
    std::unique_ptr<PreconditionMG<dim, VectorType, Transfer>>              preconditioner;
    mutable VectorType                                                      fine_src, fine_dst;
  };


  template <int dim>
  VelocityMultigrid<dim>::VelocityMultigrid(const BoundaryConditions<dim> &boundary_conditions,
                                            const unsigned int             smoother_degree)
    : boundary_conditions(boundary_conditions)
    , smoother_degree(smoother_degree)
  {
    // Parameters<dim> refuses periodic boundaries with GMG by name.
    AssertThrow(!boundary_conditions.has_periodic_pair(), ExcInternalError());
  }


  template <int dim>
  VelocityMultigrid<dim>::~VelocityMultigrid() = default;


  template <int dim>
  void
  VelocityMultigrid<dim>::reinit(const DoFHandler<dim> &stokes_dofs, const IndexSet &owned_velocity)
  {
    AssertThrow(stokes_dofs.get_fe().base_element(0).degree == 2 &&
                  stokes_dofs.get_fe().element_multiplicity(0) == dim,
                ExcInternalError());
    levels = std::make_unique<Levels>();
    Levels &L = *levels;
    L.triangulations =
      MGTransferGlobalCoarseningTools::create_geometric_coarsening_sequence(
        stokes_dofs.get_triangulation());
    L.min = 0;
    L.max = L.triangulations.size() - 1;
    L.dofs.resize(L.min, L.max);
    L.cell_dofs.resize(L.min, L.max);
    L.viscosity.resize(L.min, L.max);
    L.constraints.resize(L.min, L.max);
    L.transfers.resize(L.min, L.max);
    L.cell_transfers.resize(L.min, L.max);
    L.operators.resize(L.min, L.max);

    const FESystem<dim> fe(FE_Q<dim>(2), dim);
    const FE_DGQ<dim>   cell_fe(0);
    const MappingQ1<dim> mapping;
    typename MatrixFree<dim, double>::AdditionalData data;
    data.tasks_parallel_scheme = MatrixFree<dim, double>::AdditionalData::none;
    data.mapping_update_flags  = update_values | update_gradients | update_JxW_values;
    for (unsigned int l = L.min; l <= L.max; ++l)
      {
        L.dofs[l].reinit(*L.triangulations[l]);
        L.dofs[l].distribute_dofs(fe);
        L.cell_dofs[l].reinit(*L.triangulations[l]);
        L.cell_dofs[l].distribute_dofs(cell_fe);
        L.viscosity[l].reinit(L.cell_dofs[l].locally_owned_dofs(),
                              DoFTools::extract_locally_relevant_dofs(L.cell_dofs[l]),
                              stokes_dofs.get_communicator());

        AffineConstraints<double> &constraints = L.constraints[l];
        constraints.reinit(DoFTools::extract_locally_relevant_dofs(L.dofs[l]));
        DoFTools::make_hanging_node_constraints(L.dofs[l], constraints);
        boundary_conditions.constrain_velocity(L.dofs[l], 0.0, constraints, true);
        constraints.close();

        auto matrix_free = std::make_shared<MatrixFree<dim, double>>();
        matrix_free->reinit(mapping, L.dofs[l], constraints, QGauss<1>(3), data);
        L.operators[l] = std::make_unique<ViscousOperator<dim>>();
        L.operators[l]->initialize(matrix_free);
      }
    for (unsigned int l = L.min; l < L.max; ++l)
      {
        L.transfers[l + 1].reinit(L.dofs[l + 1], L.dofs[l], L.constraints[l + 1], L.constraints[l]);
        L.cell_transfers[l + 1].reinit(L.cell_dofs[l + 1], L.cell_dofs[l]);
      }
    L.transfer = std::make_unique<typename Levels::Transfer>(
      L.transfers, [&L](const unsigned int l, VectorType &vector) {
        L.operators[l]->initialize_dof_vector(vector);
      });

    // The Stokes velocity dofs and the finest level's: the same nodes on the
    // same cells, owned by the same rank.
    const FiniteElement<dim> &           stokes_fe = stokes_dofs.get_fe();
    std::vector<types::global_dof_index> stokes_indices(stokes_fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
    const IndexSet &                     owned = L.dofs[L.max].locally_owned_dofs();
    L.fine_index.assign(owned_velocity.n_elements(), numbers::invalid_unsigned_int);
    for (const auto &stokes_cell : stokes_dofs.active_cell_iterators())
      if (stokes_cell->is_locally_owned())
        {
          const typename DoFHandler<dim>::active_cell_iterator cell(
            &stokes_dofs.get_triangulation(), stokes_cell->level(), stokes_cell->index(), &L.dofs[L.max]);
          stokes_cell->get_dof_indices(stokes_indices);
          cell->get_dof_indices(indices);
          for (unsigned int i = 0; i < stokes_fe.n_dofs_per_cell(); ++i)
            if (stokes_fe.system_to_base_index(i).first.first == 0 &&
                owned_velocity.is_element(stokes_indices[i]))
              {
                const auto component = stokes_fe.system_to_component_index(i);
                const types::global_dof_index index =
                  indices[fe.component_to_system_index(component.first, component.second)];
                AssertThrow(owned.is_element(index), ExcInternalError());
                L.fine_index[owned_velocity.index_within_set(stokes_indices[i])] =
                  owned.index_within_set(index);
              }
        }
    AssertThrow(std::find(L.fine_index.begin(), L.fine_index.end(), numbers::invalid_unsigned_int) ==
                  L.fine_index.end(),
                ExcInternalError());
    L.point_viscosity.resize(L.cell_dofs[L.max].locally_owned_dofs().n_elements());
    L.operators[L.max]->initialize_dof_vector(L.fine_src);
    L.operators[L.max]->initialize_dof_vector(L.fine_dst);
  }


  template <int dim>
  void
  VelocityMultigrid<dim>::set_cell_viscosity(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const std::vector<double> &                           viscosity,
    const std::vector<double> &                           JxW)
  {
    Levels &                                             L = *levels;
    const typename DoFHandler<dim>::active_cell_iterator cell_dof(
      &cell->get_triangulation(), cell->level(), cell->index(), &L.cell_dofs[L.max]);
    std::vector<types::global_dof_index> index(1);
    cell_dof->get_dof_indices(index);
    double integral = 0, volume = 0;
    for (unsigned int q = 0; q < JxW.size(); ++q)
      {
        integral += viscosity[q] * JxW[q];
        volume += JxW[q];
      }
    L.viscosity[L.max][index[0]] = integral / volume;
    L.point_viscosity[L.viscosity[L.max].get_partitioner()->global_to_local(index[0])] = viscosity;
  }


  template <int dim>
  void
  VelocityMultigrid<dim>::build(const double mass)
  {
    Levels &L = *levels;
    // Coarser levels: the mean of the children's 2η (DG0 restriction sums
    // them; so it does with ones, to count them).
    for (unsigned int l = L.max; l > L.min; --l)
      {
        VectorType ones(L.viscosity[l]), children(L.viscosity[l - 1]);
        ones = 1.0;
        ones.update_ghost_values();
        L.viscosity[l].update_ghost_values();
        L.viscosity[l - 1] = 0;
        L.cell_transfers[l].restrict_and_add(L.viscosity[l - 1], L.viscosity[l]);
        L.cell_transfers[l].restrict_and_add(children, ones);
        for (const auto i : L.viscosity[l - 1].locally_owned_elements())
          L.viscosity[l - 1][i] /= children[i];
      }

    MGLevelObject<typename Levels::Smoother::AdditionalData> smoother_data(L.min, L.max);
    std::vector<types::global_dof_index>                     index(1);
    for (unsigned int l = L.min; l <= L.max; ++l)
      {
        // The finest level at the quadrature points (the system's
        // quadrature, lexicographic as the matrix-free one), coarser ones
        // the cell means.
        const MatrixFree<dim, double> &  matrix_free = *L.operators[l]->get_matrix_free();
        const unsigned int               n_points    = Utilities::pow(3, dim);
        Table<2, VectorizedArray<double>> viscosity(matrix_free.n_cell_batches(), n_points);
        for (unsigned int batch = 0; batch < matrix_free.n_cell_batches(); ++batch)
          for (unsigned int v = 0; v < matrix_free.n_active_entries_per_cell_batch(batch); ++v)
            {
              const auto cell = matrix_free.get_cell_iterator(batch, v);
              const typename DoFHandler<dim>::active_cell_iterator cell_dof(
                &cell->get_triangulation(), cell->level(), cell->index(), &L.cell_dofs[l]);
              cell_dof->get_dof_indices(index);
              const std::vector<double> *points =
                (l == L.max ?
                   &L.point_viscosity[L.viscosity[l].get_partitioner()->global_to_local(index[0])] :
                   nullptr);
              for (unsigned int q = 0; q < n_points; ++q)
                viscosity(batch, q)[v] =
                  (points && points->size() == n_points ? (*points)[q] : L.viscosity[l][index[0]]);
            }
        L.operators[l]->set_coefficients(std::move(viscosity), mass);
        L.operators[l]->compute_diagonal();
        smoother_data[l].preconditioner      = L.operators[l]->get_matrix_diagonal_inverse();
        smoother_data[l].degree              = smoother_degree;
        smoother_data[l].smoothing_range     = 20;
        smoother_data[l].eig_cg_n_iterations = 10;
      }
    L.level_matrices = std::make_unique<mg::Matrix<VectorType>>(L.operators);
    L.smoother.initialize(L.operators, smoother_data);

    TrilinosWrappers::SparseMatrix coarse_matrix;
    L.operators[L.min]->compute_matrix(L.constraints[L.min], coarse_matrix);
    L.coarse = std::make_unique<CoarseSolve<dim>>(*L.operators[L.min], std::move(coarse_matrix));
    L.multigrid = std::make_unique<Multigrid<VectorType>>(
      *L.level_matrices, *L.coarse, *L.transfer, L.smoother, L.smoother, L.min, L.max);
    L.preconditioner = std::make_unique<PreconditionMG<dim, VectorType, typename Levels::Transfer>>(
      L.dofs[L.max], *L.multigrid, *L.transfer);
  }


  template <int dim>
  void
  VelocityMultigrid<dim>::vmult(TrilinosWrappers::MPI::Vector &      dst,
                                const TrilinosWrappers::MPI::Vector &src) const
  {
    const Levels &L = *levels;
    for (unsigned int k = 0; k < L.fine_index.size(); ++k)
      L.fine_src.local_element(L.fine_index[k]) = src.trilinos_vector()[0][k];
    L.preconditioner->vmult(L.fine_dst, L.fine_src);
    for (unsigned int k = 0; k < L.fine_index.size(); ++k)
      dst.trilinos_vector()[0][k] = L.fine_dst.local_element(L.fine_index[k]);
  }


  VISCOFILM_INSTANTIATE(VelocityMultigrid)
} // namespace viscofilm
