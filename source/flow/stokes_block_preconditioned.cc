// Stokes solver/Method = block preconditioned: FGMRES with a block
// triangular preconditioner, AMG or GMG for the velocity block and, for the
// Schur complement, the 1/η-weighted pressure mass matrix plus, with a mass
// term, the pressure Laplacian (Cahouet & Chabard; doc/numerics.md).
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/affine_constraints.templates.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q_iso_q1.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <viscofilm/flow/stokes_interface_solve.h>
#include <viscofilm/flow/stokes_linear_solver.h>
#include <viscofilm/flow/stokes_velocity_multigrid.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <type_traits>

namespace viscofilm
{
  namespace
  {
    /// What a user can do when the iterations do not converge.
    const std::string direct_hint =
      "; where the block preconditioner fails (viscosity ratios of 1e4 and "
      "more in 3D or without the interface solve, cell Reynolds numbers "
      "above about 10 with Eulerian convection), Stokes solver/Method = "
      "direct is robust on meshes its factorisation fits "
      "(doc/numerics-stokes.md)";

    /// cg.solve(…), or a message naming the inner solve @p what and its
    /// iteration limit @p parameter if it does not converge (not FGMRES's
    /// NoConvergence, which the outer loop answers with expensive iterations).
    template <typename Solve>
    void
    inner_solve(const Solve &solve, const std::string &what, const std::string &parameter)
    {
      try
        {
          solve();
        }
      catch (const SolverControl::NoConvergence &e)
        {
          throw ExcMessage("the Stokes preconditioner's " + what + " did not converge in " +
                           std::to_string(e.last_step) + " iterations: residual " +
                           Utilities::to_string(e.last_residual) +
                           " (Stokes solver/Preconditioner/" + parameter + ")" +
                           direct_hint);
        }
    }


    /// The Schur complement's mass-term part m L_p^{-1} (the pressure
    /// Laplacian, its AMG and m; m zero: no mass term, or no Laplacian) and
    /// the pressure scaling.
    struct PressureLaplacian
    {
      const TrilinosWrappers::SparseMatrix *  matrix           = nullptr;
      const TrilinosWrappers::PreconditionAMG *amg              = nullptr;
      double                                   mass_coefficient = 0;
      /// s of the system's scaled pressure p/s (BlockPreconditioned's
      /// pressure_scaling): its Schur complement is s² S.
      double pressure_scaling = 1;
    };


    /**
     * Block upper-triangular preconditioner for [A B^T; B 0] (step-55's
     * approach) with A = m M + A_η, m = ρ/k: the inverse of the Schur
     * complement B A^{-1} B^T is replaced by Cahouet & Chabard's
     * M_{1/η}^{-1} + m L_p^{-1}, the (1/η)-weighted pressure mass matrix
     * (spectrally equivalent to B A_η^{-1} B^T for variable viscosity) and
     * the pressure Laplacian L_p ≈ B M^{-1} B^T (the limit m A_η^{-1} → 0, a
     * water step much shorter than ρ h²/η), and A^{-1} by multigrid cycles (AMG or GMG,
     * cheap) or by a CG solve preconditioned with them (expensive, ASPECT's
     * fallback for hard cases such as hanging nodes at large viscosity
     * contrasts). FGMRES tolerates that the inner CG solves make it vary from
     * call to call.
     */
    template <int dim, typename VelocityPreconditioner>
    class BlockSchurPreconditioner : public Subscriptor
    {
    public:
      BlockSchurPreconditioner(
        const TrilinosWrappers::BlockSparseMatrix &system_matrix,
        const TrilinosWrappers::SparseMatrix &     weighted_mass,
        const VelocityPreconditioner &             velocity_amg,
        const TrilinosWrappers::PreconditionJacobi &mass_jacobi,
        const PressureLaplacian &                   laplacian,
        const typename StokesFlow<dim>::Parameters & parameters,
        const bool                                  expensive)
        : system_matrix(system_matrix)
        , weighted_mass(weighted_mass)
        , velocity_amg(velocity_amg)
        , mass_jacobi(mass_jacobi)
        , laplacian(laplacian)
        , parameters(parameters)
        , expensive(expensive)
        , velocity_rhs(system_matrix.block(0, 1).locally_owned_range_indices(),
                       system_matrix.get_mpi_communicator())
        , pressure_update(system_matrix.block(1, 0).locally_owned_range_indices(),
                          system_matrix.get_mpi_communicator())
      {}

      void
      vmult(TrilinosWrappers::MPI::BlockVector &      dst,
            const TrilinosWrappers::MPI::BlockVector &src) const
      {
        // Pressure: −z_p = (M_{1/η}^{-1} + m L_p^{-1}) r_p / s². A loose
        // inner tolerance suffices: the sum is only an approximation of S^{-1}.
        {
          const auto schur_solve = [&](const TrilinosWrappers::SparseMatrix &matrix,
                                       const auto &                          preconditioner,
                                       const TrilinosWrappers::MPI::Vector & rhs,
                                       TrilinosWrappers::MPI::Vector &       result) {
            const double  norm = rhs.l2_norm();
            SolverControl control(parameters.schur_inner_iterations,
                                  parameters.schur_inner_tolerance * norm);
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            result = 0;
            if (norm > 0)
              inner_solve([&] { cg.solve(matrix, result, rhs, preconditioner); },
                          "Schur complement CG",
                          "Schur inner iterations = " +
                            std::to_string(parameters.schur_inner_iterations));
          };
          schur_solve(weighted_mass, mass_jacobi, src.block(1), dst.block(1));
          if (laplacian.mass_coefficient > 0)
            {
              schur_solve(*laplacian.matrix, *laplacian.amg, src.block(1), pressure_update);
              dst.block(1).add(laplacian.mass_coefficient, pressure_update);
            }
          dst.block(1) *= -1.0 / (laplacian.pressure_scaling * laplacian.pressure_scaling);
        }
        // Velocity: A z_u = r_u − B^T z_p.
        {
          system_matrix.block(0, 1).vmult(velocity_rhs, dst.block(1));
          velocity_rhs.sadd(-1.0, src.block(0));
          if (expensive)
            {
              SolverControl control(parameters.velocity_inner_iterations,
                                    parameters.velocity_inner_tolerance *
                                      velocity_rhs.l2_norm());
              dst.block(0) = 0;
              // Eulerian convection makes the block unsymmetric: GMRES.
              const bool symmetric =
                parameters.convection != StokesFlow<dim>::Convection::eulerian;
              inner_solve(
                [&] {
                  if (symmetric)
                    SolverCG<TrilinosWrappers::MPI::Vector>(control).solve(
                      system_matrix.block(0, 0), dst.block(0), velocity_rhs, velocity_amg);
                  else
                    SolverGMRES<TrilinosWrappers::MPI::Vector>(control).solve(
                      system_matrix.block(0, 0), dst.block(0), velocity_rhs, velocity_amg);
                },
                symmetric ? "velocity block CG" : "velocity block GMRES",
                "Velocity inner iterations = " +
                  std::to_string(parameters.velocity_inner_iterations));
            }
          else
            velocity_amg.vmult(dst.block(0), velocity_rhs);
        }
      }

    private:
      const TrilinosWrappers::BlockSparseMatrix & system_matrix;
      const TrilinosWrappers::SparseMatrix &      weighted_mass;
      const VelocityPreconditioner &              velocity_amg;
      const TrilinosWrappers::PreconditionJacobi &mass_jacobi;
      const PressureLaplacian &                   laplacian;
      const typename StokesFlow<dim>::Parameters & parameters;
      const bool                                  expensive;
      /// The velocity block's right-hand side and m L_p^{-1} r_p, one vector
      /// each for all calls (a new one per call costs its allocation every
      /// outer iteration).
      mutable TrilinosWrappers::MPI::Vector velocity_rhs;
      mutable TrilinosWrappers::MPI::Vector pressure_update;
    };


    /// The global indices of some of a cell's local dofs.
    std::vector<types::global_dof_index>
    global_indices(const std::vector<unsigned int> &           local,
                   const std::vector<types::global_dof_index> &cell_dofs)
    {
      std::vector<types::global_dof_index> indices;
      for (const unsigned int i : local)
        indices.push_back(cell_dofs[i]);
      return indices;
    }


    /**
     * The groups of local velocity dofs that couple in the AMG's sub-cell
     * matrix (AMG matrix = Q1 sub-cells …): group g lies in sub-cell
     * g / groups_per_subcell, the nodes in that sub-cell's closure, all
     * components or (by component) one each. Sub-cell s holds the nodes
     * whose coordinate d is in [0, ½] if bit d of s is 0, in [½, 1] if it
     * is 1. Checks that FE_Q_iso_Q1(2) numbers its dofs as @p fe does (the
     * sub-cell matrix shares the Q2 DoFHandler): the same components and
     * nodes.
     */
    template <int dim>
    std::vector<std::vector<unsigned int>>
    subcell_groups(const FiniteElement<dim> &fe, const unsigned int groups_per_subcell)
    {
      const FESystem<dim> subcell_fe(FE_Q_iso_Q1<dim>(2), dim, fe.base_element(1), 1);
      AssertThrow(subcell_fe.n_dofs_per_cell() == fe.n_dofs_per_cell(), ExcInternalError());
      const std::vector<Point<dim>> &nodes = fe.base_element(0).get_unit_support_points();
      const std::vector<Point<dim>> &subcell_nodes =
        subcell_fe.base_element(0).get_unit_support_points();
      std::vector<std::vector<unsigned int>> groups(
        GeometryInfo<dim>::max_children_per_cell * groups_per_subcell);
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        {
          const auto base = fe.system_to_base_index(i);
          AssertThrow(subcell_fe.system_to_base_index(i) == base, ExcInternalError());
          if (base.first.first != 0)
            continue; // a pressure dof
          const Point<dim> &node = nodes[base.second];
          AssertThrow(node.distance(subcell_nodes[base.second]) < 1e-12, ExcInternalError());
          const unsigned int group =
            (groups_per_subcell == 1 ? 0 : fe.system_to_component_index(i).first);
          for (unsigned int s = 0; s < GeometryInfo<dim>::max_children_per_cell; ++s)
            {
              bool inside = true;
              for (unsigned int d = 0; d < dim; ++d)
                inside &= (((s >> d) & 1) ? node[d] >= 0.5 : node[d] <= 0.5);
              if (inside)
                groups[s * groups_per_subcell + group].push_back(i);
            }
        }
      return groups;
    }


    /**
     * The velocity block (Res/k)(u, v) + (2η D(u), D(v)) with Q1 on the
     * 2^dim sub-cells of each cell (FE_Q_iso_Q1(2)), for the AMG: only the
     * dofs of a group couple (the sparsity of BlockPreconditioned::reinit()). Two Gauss
     * points per direction and sub-cell integrate it exactly on
     * parallelograms. η is the system's at these points (StokesViscosity);
     * the implicit elastic viscosity, known at the Q2 points only, enters
     * with its cell mean.
     */
    template <int dim>
    class SubcellAssembler
    {
    public:
      SubcellAssembler(const FiniteElement<dim> &                     pressure_fe,
                       const std::vector<std::vector<unsigned int>> &groups)
        : fe(FE_Q_iso_Q1<dim>(2), dim, pressure_fe, 1)
        , quadrature(QGauss<1>(2), 2)
        , values(fe, quadrature, update_values | update_gradients | update_JxW_values)
        , groups(groups)
        , groups_per_subcell(groups.size() / GeometryInfo<dim>::max_children_per_cell)
        , viscosity(quadrature.size())
        , velocity_index(fe.n_dofs_per_cell(), numbers::invalid_unsigned_int)
        , dof_indices(fe.n_dofs_per_cell())
        , phi_u(groups[0].size())
        , symgrad_phi_u(groups[0].size())
      {
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          if (fe.system_to_base_index(i).first.first == 0)
            {
              velocity_index[i] = velocity_dofs.size();
              velocity_dofs.push_back(i);
            }
        cell_matrix.reinit(velocity_dofs.size(), velocity_dofs.size());
        velocity_dof_indices.resize(velocity_dofs.size());
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            unsigned int s = 0;
            for (unsigned int d = 0; d < dim; ++d)
              s |= (quadrature.point(q)[d] > 0.5 ? 1u : 0u) << d;
            subcell_of_point.push_back(s);
          }
      }

      /// The sub-cell matrix of @p cell.
      void
      add(const typename DoFHandler<dim>::active_cell_iterator &cell,
          const double                                          elastic_viscosity,
          const double                                          mass_coefficient,
          StokesViscosity<dim> &                                system_viscosity,
          const AffineConstraints<double> &                     constraints,
          TrilinosWrappers::SparseMatrix &                      matrix)
      {
        values.reinit(typename Triangulation<dim>::cell_iterator(cell));
        system_viscosity.evaluate(values, viscosity);
        const FEValuesExtractors::Vector velocities(0);
        const unsigned int               n = groups[0].size();
        // One matrix for the cell's velocity dofs: entries of dofs in no
        // common group stay zero, and distribute_local_to_global() skips
        // zeros. (Not the pressure dofs: a hanging one would get a diagonal
        // entry outside the velocity block.)
        cell_matrix = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const double mass = mass_coefficient * values.JxW(q);
            const double stiffness =
              2 * (viscosity[q] + elastic_viscosity) * values.JxW(q);
            for (unsigned int g = subcell_of_point[q] * groups_per_subcell;
                 g < (subcell_of_point[q] + 1) * groups_per_subcell;
                 ++g)
              {
                for (unsigned int a = 0; a < n; ++a)
                  {
                    phi_u[a]         = values[velocities].value(groups[g][a], q);
                    symgrad_phi_u[a] = values[velocities].symmetric_gradient(groups[g][a], q);
                  }
                for (unsigned int a = 0; a < n; ++a)
                  for (unsigned int b = 0; b < n; ++b)
                    cell_matrix(velocity_index[groups[g][a]], velocity_index[groups[g][b]]) +=
                      mass * (phi_u[a] * phi_u[b]) +
                      stiffness * (symgrad_phi_u[a] * symgrad_phi_u[b]);
              }
          }
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < velocity_dofs.size(); ++i)
          velocity_dof_indices[i] = dof_indices[velocity_dofs[i]];
        constraints.distribute_local_to_global(cell_matrix, velocity_dof_indices, matrix);
      }

    private:
      const FESystem<dim>                           fe;
      const QIterated<dim>                          quadrature;
      FEValues<dim>                                 values;
      const std::vector<std::vector<unsigned int>> &groups;
      const unsigned int                            groups_per_subcell;
      std::vector<unsigned int>                     subcell_of_point;
      std::vector<double>                           viscosity;
      /// The cell's velocity dofs (local indices), the position of each
      /// local dof among them, their global indices.
      std::vector<unsigned int>                     velocity_dofs;
      std::vector<unsigned int>                     velocity_index;
      FullMatrix<double>                            cell_matrix;
      std::vector<types::global_dof_index>          dof_indices;
      std::vector<types::global_dof_index>          velocity_dof_indices;
      std::vector<Tensor<1, dim>>                   phi_u;
      std::vector<SymmetricTensor<2, dim>>          symgrad_phi_u;
    };


    template <int dim>
    class BlockPreconditioned : public StokesLinearSolver<dim>
    {
    public:
      BlockPreconditioned(const typename StokesFlow<dim>::Parameters &parameters,
                          const double                                  reference_viscosity,
                          const BoundaryConditions<dim> &               boundary_conditions)
        : parameters(parameters)
        , reference_viscosity(reference_viscosity)
        , boundary_conditions(boundary_conditions)
      {}

      bool
      pins_pressure() const override
      {
        return false;
      }

      void
      reinit(const DoFHandler<dim> &           dofs,
             const AffineConstraints<double> & constraints,
             const std::vector<IndexSet> &     owned_partitioning,
             const std::vector<IndexSet> &     relevant_partitioning) override;

      void
      start_matrix(StokesViscosity<dim> &viscosity) override;
      void
      add_cell_preconditioner(const FEValues<dim> &   fe_values,
                              StokesCellMatrix<dim> &cell) const override;
      void
      add_cell_matrix(const StokesCellMatrix<dim> &    cell,
                      const AffineConstraints<double> &constraints) override;
      void
      finish_matrix() override;

      unsigned int
      solve(const TrilinosWrappers::MPI::BlockVector &rhs,
            const TrilinosWrappers::MPI::BlockVector &guess,
            const AffineConstraints<double> &         constraints,
            TrilinosWrappers::MPI::BlockVector &      solution,
            double                                    tolerance) override;

      unsigned int
      n_preconditioner_builds() const override
      {
        return n_builds;
      }

      double
      viscosity_change_since_build() const override
      {
        return viscosity_change;
      }

      std::string
      velocity_preconditioner() const override
      {
        return multigrid ? "GMG" : "AMG";
      }

    private:
      void
      build_preconditioner();
      void
      build_interface_solve();
      void
      assemble_subcell_matrix();

      using AMGMatrix = typename StokesFlow<dim>::AMGMatrix;

      /// Velocity preconditioner = auto: GMG from this many Stokes dofs, where
      /// its time per solve falls below the AMG's (doc/performance.md).
      static constexpr types::global_dof_index automatic_multigrid_dofs =
        (dim == 2 ? 20000 : 10000);

      /// Whether the velocity AMG is built from the Q1 sub-cell matrix.
      bool
      uses_subcell_matrix() const
      {
        return !multigrid && parameters.amg_matrix != AMGMatrix::q2;
      }

      /// Whether a velocity preconditioner was built for this mesh.
      bool
      has_velocity_preconditioner() const
      {
        return velocity_amg || multigrid_built;
      }

      const typename StokesFlow<dim>::Parameters &parameters;
      const double                    reference_viscosity; // ηs(φ = 0)
      const BoundaryConditions<dim> & boundary_conditions;
      const DoFHandler<dim> *         dofs = nullptr;
      /// The pressure shape functions of a cell (local indices).
      std::vector<unsigned int> pressure_dofs;
      MPI_Comm                        mpi_communicator = MPI_COMM_SELF;

      TrilinosWrappers::BlockSparseMatrix system_matrix;
      TrilinosWrappers::BlockSparseMatrix preconditioner_matrix; // (1/η) M_p
      /// The velocity block with Q1 on sub-cells (AMG matrix = Q1 sub-cells
      /// …) and its coupling groups (subcell_groups()). It serves only to
      /// build the AMG, so it is assembled only for a build
      /// (assemble_subcell_matrix()): at the end of the matrix assembly that
      /// decides on one (finish_matrix()), or when a solve finds a kept AMG
      /// too weak; from what that assembly recorded of each cell (its mean
      /// elastic viscosity), its η (system_viscosity) and mass coefficient.
      TrilinosWrappers::SparseMatrix         subcell_matrix;
      std::vector<std::vector<unsigned int>> groups;
      struct SubcellSource
      {
        typename DoFHandler<dim>::active_cell_iterator cell;
        double                                         elastic_viscosity;
      };
      std::vector<SubcellSource>        subcell_sources;
      StokesViscosity<dim> *            system_viscosity = nullptr;
      double                            mass_coefficient = 0;
      const AffineConstraints<double> * constraints      = nullptr;

      bool preconditioner_is_current      = false; // the velocity AMG
      bool mass_preconditioner_is_current = false; // Jacobi of (1/η) M_p
      bool interface_is_current           = false; // interface_solve

      /// Reuse of the AMG: η at each owned cell's quadrature points when it
      /// was built and while the matrix is
      /// assembled, the integrals of |ln(η/η_built)| and of 1 then, the
      /// outer iterations of the first solve after the build, whether the
      /// next solve is the first with a newly assembled matrix, and whether
      /// that solve asked for a rebuild at the next assembly.
      std::vector<double> viscosity_at_build;
      std::vector<double> viscosity_now;
      double              change_integrals[2]     = {0, 0};
      unsigned int        iterations_after_build  = 0;
      bool                first_solve_with_matrix = false;
      bool                rebuild_requested       = false;
      unsigned int        n_builds                = 0;
      double              viscosity_change        = 0;

      std::unique_ptr<TrilinosWrappers::PreconditionAMG>    velocity_amg;
      /// The GMG, built from the cell viscosities that add_cell_matrix()
      /// hands it, where it serves on this mesh (Velocity preconditioner =
      /// GMG, or auto from automatic_multigrid_dofs without periodic
      /// boundaries; decided in reinit()); null where the AMG does.
      std::unique_ptr<VelocityMultigrid<dim>>               multigrid;
      bool                                                  multigrid_built = false;
      std::unique_ptr<TrilinosWrappers::PreconditionJacobi> mass_jacobi;

      /// The exact solve on the edge of the viscous region (Interface solve
      /// viscosity ratio), from the velocity dofs of the cells above the
      /// ratio: for each assembled matrix, even where the multigrid is kept
      /// (Reuse), since η at the edge moves by orders of magnitude when φ
      /// moves a little.
      InterfaceSolve                       interface_solve;
      std::vector<types::global_dof_index> viscous_cell_dofs;
      IndexSet                             relevant_velocity;

      /// The pressure Laplacian L_p (block (1, 1)) of the Schur complement's
      /// mass-term part: Neumann where the velocity is given, zero pressure
      /// where the normal traction is, the first pressure dof pinned where no
      /// boundary fixes the pressure level (laplacian_constraints). It
      /// depends on the mesh only: assembled with the first matrix that has a
      /// mass term. Not for a discontinuous pressure, whose cell-wise
      /// (∇q, ∇p) is no Laplacian.
      bool                                               continuous_pressure = true;
      AffineConstraints<double>                          laplacian_constraints;
      TrilinosWrappers::BlockSparseMatrix                laplacian_matrix;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG> laplacian_amg;

      /**
       * The system is solved for (u, p/s), its divergence rows times s, s =
       * ηs(φ = 0) / L with L the smallest extent of the coarse mesh's
       * bounding box (ASPECT's pressure scaling): both blocks of the residual
       * are then of one size, so FGMRES's relative residual (`Tolerance`)
       * means the same in any units, and a problem in SI takes the
       * iterations of its dimensionless twin.
       */
      double pressure_scaling = 1;

      bool
      assembles_laplacian(const double mass) const
      {
        return continuous_pressure && mass > 0 && !laplacian_amg;
      }
    };


    template <int dim>
    void
    BlockPreconditioned<dim>::reinit(const DoFHandler<dim> &      dofs,
                                const AffineConstraints<double> & constraints,
                                const std::vector<IndexSet> &     owned_partitioning,
                                const std::vector<IndexSet> &     relevant_partitioning)
    {
      this->dofs       = &dofs;
      mpi_communicator = dofs.get_communicator();
      pressure_dofs.clear();
      for (unsigned int k = 0; k < dofs.get_fe().n_dofs_per_cell(); ++k)
        if (dofs.get_fe().system_to_component_index(k).first == dim)
          pressure_dofs.push_back(k);
      const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);

      // The AMG refers to the matrix it was built from: drop it first.
      velocity_amg.reset();
      multigrid_built = false;
      relevant_velocity = relevant_partitioning[0];
      using VelocityPreconditioner = typename StokesFlow<dim>::VelocityPreconditioner;
      if (parameters.velocity_preconditioner == VelocityPreconditioner::gmg ||
          (parameters.velocity_preconditioner == VelocityPreconditioner::automatic &&
           !boundary_conditions.has_periodic_pair() &&
           dofs.n_dofs() >= automatic_multigrid_dofs))
        {
          if (!multigrid)
            multigrid = std::make_unique<VelocityMultigrid<dim>>(boundary_conditions,
                                                                 parameters.gmg_smoother_degree);
          multigrid->reinit(dofs, owned_partitioning[0]);
        }
      else
        multigrid.reset();
      mass_jacobi.reset();
      laplacian_amg.reset();
      viscosity_at_build.clear();
      rebuild_requested = false;
      system_matrix.clear();
      preconditioner_matrix.clear();
      subcell_matrix.clear();

      // Components 0 … dim − 1: u; dim: p.
      Table<2, DoFTools::Coupling> coupling(dim + 1, dim + 1);
      Table<2, DoFTools::Coupling> mass_coupling(dim + 1, dim + 1);
      for (unsigned int c = 0; c < dim + 1; ++c)
        for (unsigned int d = 0; d < dim + 1; ++d)
          {
            coupling[c][d] = (c == dim && d == dim) ? DoFTools::none : DoFTools::always;
            mass_coupling[c][d] = (c == dim && d == dim) ? DoFTools::always : DoFTools::none;
          }
      const auto reinit = [&](const Table<2, DoFTools::Coupling> &couplings,
                              TrilinosWrappers::BlockSparseMatrix &matrix) {
        TrilinosWrappers::BlockSparsityPattern sparsity(owned_partitioning,
                                                        owned_partitioning,
                                                        relevant_partitioning,
                                                        mpi_communicator);
        DoFTools::make_sparsity_pattern(dofs, couplings, sparsity, constraints, false, rank);
        sparsity.compress();
        matrix.reinit(sparsity);
      };
      reinit(coupling, system_matrix);
      reinit(mass_coupling, preconditioner_matrix);
      if (parameters.interface_solve_ratio > 0)
        interface_solve.reinit(system_matrix.block(0, 0));

      // Level 0 is on every rank.
      std::vector<Point<dim>> coarse_vertices;
      for (const auto &cell : dofs.get_triangulation().cell_iterators_on_level(0))
        for (const unsigned int v : cell->vertex_indices())
          coarse_vertices.push_back(cell->vertex(v));
      const BoundingBox<dim> box(coarse_vertices);
      double                 extent = box.side_length(0);
      for (unsigned int d = 1; d < dim; ++d)
        extent = std::min(extent, box.side_length(d));
      pressure_scaling = reference_viscosity / extent;

      continuous_pressure = dofs.get_fe().base_element(1).conforms(FiniteElementData<dim>::H1);
      laplacian_matrix.clear();
      if (continuous_pressure)
        {
          reinit(mass_coupling, laplacian_matrix);
          // The Stokes constraints' locally relevant dofs.
          const IndexSet &relevant = constraints.get_local_lines();
          laplacian_constraints.clear();
          laplacian_constraints.reinit(relevant);
          DoFTools::make_hanging_node_constraints(dofs, laplacian_constraints);
          const std::set<types::boundary_id> traction = boundary_conditions.traction_boundary_ids();
          // (No traction boundary: none; deal.II reads an empty set as all.)
          const IndexSet boundary_pressure =
            traction.empty() ?
              IndexSet(dofs.n_dofs()) :
              DoFTools::extract_boundary_dofs(dofs,
                                              dofs.get_fe().component_mask(
                                                FEValuesExtractors::Scalar(dim)),
                                              traction);
          for (const types::global_dof_index i : boundary_pressure)
            if (!laplacian_constraints.is_constrained(i))
              laplacian_constraints.add_line(i);
          // As StokesFlow::make_constraints pins it for a factorisation: a
          // coarse-mesh vertex, never hanging.
          const types::global_dof_index first_pressure_dof = owned_partitioning[0].size();
          if (traction.empty() && relevant.is_element(first_pressure_dof))
            laplacian_constraints.add_line(first_pressure_dof);
          boundary_conditions.constrain_periodic(dofs, laplacian_constraints);
          laplacian_constraints.close();
        }

      if (uses_subcell_matrix())
        {
          groups = subcell_groups(dofs.get_fe(),
                                  parameters.amg_matrix == AMGMatrix::q1_subcells_by_component ?
                                    dim :
                                    1);
          // The velocity dofs come first, so their global indices are the
          // velocity block's.
          TrilinosWrappers::SparsityPattern subcell_sparsity(owned_partitioning[0],
                                                             owned_partitioning[0],
                                                             relevant_partitioning[0],
                                                             mpi_communicator);
          std::vector<types::global_dof_index> cell_dofs(dofs.get_fe().n_dofs_per_cell());
          for (const auto &cell : dofs.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                cell->get_dof_indices(cell_dofs);
                for (const std::vector<unsigned int> &group : groups)
                  constraints.add_entries_local_to_global(global_indices(group, cell_dofs),
                                                          subcell_sparsity,
                                                          false);
              }
          subcell_sparsity.compress();
          subcell_matrix.reinit(subcell_sparsity);
        }
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::start_matrix(StokesViscosity<dim> &viscosity)
    {
      system_viscosity      = &viscosity;
      system_matrix         = 0;
      preconditioner_matrix = 0;
      if (continuous_pressure && !laplacian_amg)
        laplacian_matrix = 0;
      subcell_sources.clear();
      viscous_cell_dofs.clear();
      viscosity_now.clear();
      change_integrals[0] = change_integrals[1] = 0;
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::add_cell_preconditioner(const FEValues<dim> &    fe_values,
                                                      StokesCellMatrix<dim> &cell) const
    {
      const FEValuesExtractors::Scalar pressure(dim);
      const unsigned int               dofs_per_cell = cell.dof_indices.size();

      // (1/η) M_p, the Schur complement's stand-in: its pressure rows and
      // columns only, the others are zero.
      FullMatrix<double> &cell_mass = cell.preconditioner_matrix;
      cell_mass.reinit(dofs_per_cell, dofs_per_cell);
      std::vector<double> phi_p(pressure_dofs.size());
      for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
        {
          for (unsigned int k = 0; k < pressure_dofs.size(); ++k)
            phi_p[k] = fe_values[pressure].value(pressure_dofs[k], q);
          for (unsigned int i = 0; i < pressure_dofs.size(); ++i)
            for (unsigned int j = 0; j < pressure_dofs.size(); ++j)
              cell_mass(pressure_dofs[i], pressure_dofs[j]) +=
                phi_p[i] * phi_p[j] / cell.viscosity[q] * fe_values.JxW(q);
        }

      FullMatrix<double> &cell_laplacian = cell.pressure_laplacian;
      const unsigned int  n_laplacian =
        assembles_laplacian(cell.mass_coefficient) ? dofs_per_cell : 0;
      cell_laplacian.reinit(n_laplacian, n_laplacian);
      for (unsigned int q = 0; q < fe_values.n_quadrature_points && n_laplacian > 0; ++q)
        for (const unsigned int i : pressure_dofs)
          for (const unsigned int j : pressure_dofs)
            cell_laplacian(i, j) += fe_values[pressure].gradient(i, q) *
                                    fe_values[pressure].gradient(j, q) * fe_values.JxW(q);
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::add_cell_matrix(const StokesCellMatrix<dim> & cell,
                                         const AffineConstraints<double> &constraints)
    {
      constraints.distribute_local_to_global(cell.matrix, cell.dof_indices, system_matrix);
      constraints.distribute_local_to_global(cell.preconditioner_matrix,
                                             cell.dof_indices,
                                             preconditioner_matrix);
      if (!cell.pressure_laplacian.empty())
        laplacian_constraints.distribute_local_to_global(cell.pressure_laplacian,
                                                         cell.dof_indices,
                                                         laplacian_matrix);
      mass_coefficient = cell.mass_coefficient;

      if (parameters.interface_solve_ratio > 0 &&
          *std::max_element(cell.viscosity.begin(), cell.viscosity.end()) >
            parameters.interface_solve_ratio * reference_viscosity)
        for (const types::global_dof_index i : cell.dof_indices)
          if (i < relevant_velocity.size())
            viscous_cell_dofs.push_back(i);

      if (multigrid)
        {
          // 2η (the assembly's η holds the implicit elastic viscosity), the
          // level operators' coefficient.
          std::vector<double> viscosity(cell.JxW.size());
          for (unsigned int q = 0; q < cell.JxW.size(); ++q)
            viscosity[q] = 2 * cell.viscosity[q];
          multigrid->set_cell_viscosity(cell.cell, viscosity, cell.JxW);
        }
      else if (uses_subcell_matrix())
        {
          subcell_sources.push_back(
            {cell.cell,
             std::accumulate(cell.elastic_viscosity.begin(), cell.elastic_viscosity.end(), 0.0) /
               cell.elastic_viscosity.size()});
          this->constraints = &constraints;
        }

      // η at the quadrature points, for the AMG's rebuild criterion (Reuse).
      if (parameters.reuse_preconditioner)
        for (unsigned int q = 0; q < cell.JxW.size(); ++q)
          {
            if (has_velocity_preconditioner() &&
                viscosity_now.size() < viscosity_at_build.size())
              {
                change_integrals[0] +=
                  std::abs(std::log(cell.viscosity[q] /
                                    viscosity_at_build[viscosity_now.size()])) *
                  cell.JxW[q];
                change_integrals[1] += cell.JxW[q];
              }
            viscosity_now.push_back(cell.viscosity[q]);
          }
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::finish_matrix()
    {
      system_matrix.compress(VectorOperation::add);
      system_matrix.block(0, 1) *= pressure_scaling;
      system_matrix.block(1, 0) *= pressure_scaling;
      preconditioner_matrix.compress(VectorOperation::add);
      // The same on every rank, one without cells too (collective solves).
      mass_coefficient = Utilities::MPI::max(mass_coefficient, mpi_communicator);
      if (assembles_laplacian(mass_coefficient))
        {
          laplacian_matrix.compress(VectorOperation::add);
          TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
          amg_data.elliptic = true;
          laplacian_amg     = std::make_unique<TrilinosWrappers::PreconditionAMG>();
          laplacian_amg->initialize(laplacian_matrix.block(1, 1), amg_data);
        }

      mass_preconditioner_is_current = false;
      first_solve_with_matrix        = true;
      interface_is_current           = false;
      // Keep the AMG while it still fits the new matrix (Reuse); not at a
      // sharp contrast (an interface solve), where η at the edge moves by
      // orders of magnitude while its mean over the domain hardly does
      // (a kept GMG took 1.8 times the iterations in the SI bulb).
      // A collective decision: a rank without cells has no η of its own
      // but must join the sum.
      const bool compared = parameters.reuse_preconditioner && has_velocity_preconditioner() &&
                            !interface_solve.active();
      viscosity_change = 0;
      if (compared)
        {
          Utilities::MPI::sum(change_integrals, mpi_communicator, change_integrals);
          viscosity_change = change_integrals[0] / change_integrals[1];
        }
      if (!compared || rebuild_requested ||
          viscosity_change > parameters.rebuild_viscosity_change)
        {
          preconditioner_is_current = false;
          viscosity_at_build.swap(viscosity_now);
          // A matrix for the preconditioner belongs to the assembly (as
          // step-55's does), not to the solve that builds the AMG from it.
          if (uses_subcell_matrix())
            assemble_subcell_matrix();
        }
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::assemble_subcell_matrix()
    {
      subcell_matrix = 0;
      if (!subcell_sources.empty())
        {
          SubcellAssembler<dim> subcells(dofs->get_fe().base_element(1), groups);
          for (const SubcellSource &source : subcell_sources)
            subcells.add(source.cell,
                         source.elastic_viscosity,
                         mass_coefficient,
                         *system_viscosity,
                         *constraints,
                         subcell_matrix);
        }
      subcell_matrix.compress(VectorOperation::add);
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::build_interface_solve()
    {
      // (Without the Direct solver's package in Trilinos: off, as Method =
      // auto falls back to the block preconditioner then.)
      if (parameters.interface_solve_ratio == 0 || !parameters.direct_available)
        return;
      const TrilinosWrappers::SparseMatrix &velocity_block = system_matrix.block(0, 0);
      TrilinosWrappers::MPI::Vector         viscous;
      viscous.reinit(velocity_block.locally_owned_range_indices(),
                     relevant_velocity,
                     mpi_communicator,
                     true);
      for (const types::global_dof_index i : viscous_cell_dofs)
        viscous(i) += 1;
      viscous.compress(VectorOperation::add);
      interface_solve.build(velocity_block, viscous, parameters.direct_solver);
    }


    template <int dim>
    void
    BlockPreconditioned<dim>::build_preconditioner()
    {
      preconditioner_is_current = true;
      rebuild_requested         = false;
      ++n_builds;
      if (multigrid)
        {
          multigrid->build(mass_coefficient);
          multigrid_built = true;
          return;
        }
      TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
      DoFTools::extract_constant_modes(*dofs,
                                       dofs->get_fe().component_mask(
                                         FEValuesExtractors::Vector(0)),
                                       amg_data.constant_modes);
      amg_data.elliptic              = true;
      amg_data.higher_order_elements = (parameters.amg_matrix == AMGMatrix::q2);
      amg_data.smoother_sweeps       = parameters.amg_smoother_sweeps;
      amg_data.smoother_type         = parameters.amg_smoother.c_str();
      amg_data.aggregation_threshold = parameters.amg_aggregation_threshold;
      amg_data.w_cycle               = parameters.amg_w_cycle;
      amg_data.n_cycles              = parameters.amg_cycles;
      velocity_amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      velocity_amg->initialize(parameters.amg_matrix == AMGMatrix::q2 ?
                                 system_matrix.block(0, 0) :
                                 subcell_matrix,
                               amg_data);
    }


    template <int dim>
    unsigned int
    BlockPreconditioned<dim>::solve(const TrilinosWrappers::MPI::BlockVector &rhs,
                               const TrilinosWrappers::MPI::BlockVector &guess,
                               const AffineConstraints<double> &         constraints,
                               TrilinosWrappers::MPI::BlockVector &      solution,
                               const double                              tolerance)
    {
      bool built = !preconditioner_is_current;
      if (built)
        build_preconditioner();
      if (!interface_is_current)
        {
          build_interface_solve();
          interface_is_current = true;
        }
      if (!mass_preconditioner_is_current)
        {
          mass_jacobi = std::make_unique<TrilinosWrappers::PreconditionJacobi>();
          mass_jacobi->initialize(preconditioner_matrix.block(1, 1));
          mass_preconditioner_is_current = true;
        }

      // FGMRES from `solution` with at most n_cheap cheap iterations, then
      // (if `go_on`) expensive ones; true if it converged.
      const PressureLaplacian laplacian{laplacian_amg ? &laplacian_matrix.block(1, 1) : nullptr,
                                        laplacian_amg.get(),
                                        laplacian_amg ? mass_coefficient : 0.0,
                                        pressure_scaling};
      // The divergence rows times s, as the matrix's (pressure_scaling).
      TrilinosWrappers::MPI::BlockVector scaled_rhs = rhs;
      scaled_rhs.block(1) *= pressure_scaling;
      const double target     = tolerance * scaled_rhs.l2_norm();
      unsigned int iterations = 0;
      const auto   fgmres     = [&](const unsigned int n_cheap, const bool go_on) {
        for (const bool expensive : {false, true})
          {
            SolverControl control(expensive ? parameters.max_iterations : n_cheap, target);
            SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(
              control,
              SolverFGMRES<TrilinosWrappers::MPI::BlockVector>::AdditionalData(
                parameters.krylov_basis));
            const auto solve_with = [&](const auto &velocity_preconditioner) {
              const BlockSchurPreconditioner<dim, std::decay_t<decltype(velocity_preconditioner)>>
                preconditioner(system_matrix,
                               preconditioner_matrix.block(1, 1),
                               velocity_preconditioner,
                               *mass_jacobi,
                               laplacian,
                               parameters,
                               expensive);
              solver.solve(system_matrix, solution, scaled_rhs, preconditioner);
            };
            try
              {
                const auto with_interface = [&](const auto &cycle) {
                  if (interface_solve.active())
                    solve_with(WithInterfaceSolve<std::decay_t<decltype(cycle)>>(
                      cycle, interface_solve, system_matrix.block(0, 0)));
                  else
                    solve_with(cycle);
                };
                if (multigrid)
                  with_interface(*multigrid);
                else
                  with_interface(*velocity_amg);
                iterations += control.last_step();
                return true;
              }
            catch (const SolverControl::NoConvergence &e)
              {
                iterations += e.last_step;
                if (expensive)
                  throw ExcMessage("the Stokes solver (FGMRES) did not converge in " +
                                   std::to_string(iterations) + " iterations: residual " +
                                   Utilities::to_string(e.last_residual) + ", target " +
                                   Utilities::to_string(control.tolerance()) +
                                   " (Stokes solver/Maximum iterations = " +
                                   std::to_string(parameters.max_iterations) + ")" +
                                   direct_hint);
                if (!go_on)
                  return false;
              }
          }
        return false;
      };

      if (target > 0)
        {
          solution = guess; // the last solution as first guess
          constraints.set_zero(solution);
          solution.block(1) /= pressure_scaling;
          const unsigned int n_cheap =
            std::min(parameters.max_iterations, parameters.cheap_iterations);
          // A reused AMG gets twice Rebuild iteration growth × the iterations
          // after its build; if it cannot do with those (η moved too far: it
          // can stall altogether), it is rebuilt at once and FGMRES goes on
          // from where it got.
          const unsigned int reuse_limit = static_cast<unsigned int>(
            2 * parameters.rebuild_iteration_growth * std::max(iterations_after_build, 1u));
          if (built || !fgmres(std::min(n_cheap, reuse_limit), false))
            {
              if (!built)
                {
                  if (uses_subcell_matrix())
                    assemble_subcell_matrix();
                  build_preconditioner();
                  built = true;
                }
              // Cheap iterations first; if they stall, go on from where they
              // got with expensive ones (ASPECT's strategy).
              fgmres(n_cheap, true);
            }
          solution.block(1) *= pressure_scaling;
        }
      // The iteration criterion of Reuse, on like solves: the first with each
      // new matrix (later Picard iterations start from better guesses).
      if (first_solve_with_matrix)
        {
          if (built)
            iterations_after_build = iterations;
          else if (iterations > parameters.rebuild_iteration_growth *
                                  std::max(iterations_after_build, 1u))
            rebuild_requested = true;
          first_solve_with_matrix = false;
        }
      return iterations;
    }
  } // namespace


  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  make_block_preconditioned_solver(const typename StokesFlow<dim>::Parameters &parameters,
                                   const double                    reference_viscosity,
                                   const BoundaryConditions<dim> & boundary_conditions)
  {
    return std::make_unique<BlockPreconditioned<dim>>(parameters,
                                                      reference_viscosity,
                                                      boundary_conditions);
  }


#define INSTANTIATE(dim)                                                 \
  template std::unique_ptr<StokesLinearSolver<dim>>                        \
  make_block_preconditioned_solver<dim>(const typename StokesFlow<dim>::Parameters &, \
                                        const double,                                  \
                                        const BoundaryConditions<dim> &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
