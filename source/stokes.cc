#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgp.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/affine_constraints.templates.h>
#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <viscofilm/dof_cell.h>
#include <viscofilm/input.h>
#include <viscofilm/stokes.h>

#include <algorithm>
#include <cmath>

namespace viscofilm
{
  namespace
  {
    /// ∇·u, the vorticity ∇×u (2D: the scalar ∂v/∂x − ∂u/∂y) and |u·∇u|
    /// from the Stokes solution.
    class FlowPostprocessor : public DataPostprocessor<dim>
    {
    public:
      static constexpr unsigned int n_vorticity_components = dim == 2 ? 1 : dim;

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        for (unsigned int q = 0; q < inputs.solution_values.size(); ++q)
          {
            const auto &   grad = inputs.solution_gradients[q];
            Tensor<1, dim> u;
            for (unsigned int d = 0; d < dim; ++d)
              u[d] = inputs.solution_values[q][d];
            Tensor<1, dim> convection;
            double         divergence = 0;
            for (unsigned int i = 0; i < dim; ++i)
              {
                convection[i] = u * grad[i];
                divergence += grad[i][i];
              }
            computed[q][0] = divergence;
            // (∇×u)_i = ∂_j u_k − ∂_k u_j for (i, j, k) cyclic; 2D: i = z.
            for (unsigned int i = 0; i < n_vorticity_components; ++i)
              {
                const unsigned int j = (dim == 2 ? 0 : (i + 1) % 3), k = (j + 1) % dim;
                computed[q][1 + i] = grad[k][j] - grad[j][k];
              }
            computed[q][1 + n_vorticity_components] = convection.norm();
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names = {"divergence"};
        for (unsigned int i = 0; i < n_vorticity_components; ++i)
          names.push_back("vorticity");
        names.push_back("inertia");
        return names;
      }

      /// The vorticity is a vector in 3D (one dataset of three components).
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        std::vector<DataComponentInterpretation::DataComponentInterpretation>
          interpretation(2 + n_vorticity_components,
                         DataComponentInterpretation::component_is_scalar);
        if (dim == 3)
          for (unsigned int i = 0; i < n_vorticity_components; ++i)
            interpretation[1 + i] = DataComponentInterpretation::component_is_part_of_vector;
        return interpretation;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values | update_gradients;
      }
    };


    /**
     * Block upper-triangular preconditioner for [A B^T; B 0] (step-55's
     * approach): the Schur complement B A^{-1} B^T is replaced by the
     * (1/η)-weighted pressure mass matrix, which is spectrally equivalent to
     * it for variable viscosity, and A^{-1} by one AMG V-cycle (cheap) or by
     * an AMG-preconditioned CG solve (expensive, ASPECT's fallback for hard
     * cases such as hanging nodes at large viscosity contrasts). FGMRES
     * tolerates that the inner CG solves make it vary from call to call.
     */
    class BlockSchurPreconditioner : public Subscriptor
    {
    public:
      BlockSchurPreconditioner(
        const TrilinosWrappers::BlockSparseMatrix &system_matrix,
        const TrilinosWrappers::SparseMatrix &     weighted_mass,
        const TrilinosWrappers::PreconditionAMG &  velocity_amg,
        const TrilinosWrappers::PreconditionJacobi &mass_jacobi,
        const StokesSolver::Parameters &            parameters,
        const bool                                  expensive)
        : system_matrix(system_matrix)
        , weighted_mass(weighted_mass)
        , velocity_amg(velocity_amg)
        , mass_jacobi(mass_jacobi)
        , parameters(parameters)
        , expensive(expensive)
      {}

      void
      vmult(TrilinosWrappers::MPI::BlockVector &      dst,
            const TrilinosWrappers::MPI::BlockVector &src) const
      {
        // Pressure: −S z_p = r_p with S ≈ (1/η) M_p. A loose inner tolerance
        // suffices: the mass matrix is only an approximation of S anyway.
        {
          SolverControl control(parameters.schur_inner_iterations,
                                parameters.schur_inner_tolerance *
                                  src.block(1).l2_norm());
          SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
          dst.block(1) = 0;
          if (src.block(1).l2_norm() > 0)
            cg.solve(weighted_mass, dst.block(1), src.block(1), mass_jacobi);
          dst.block(1) *= -1.0;
        }
        // Velocity: A z_u = r_u − B^T z_p.
        {
          TrilinosWrappers::MPI::Vector rhs(src.block(0));
          system_matrix.block(0, 1).vmult(rhs, dst.block(1));
          rhs.sadd(-1.0, src.block(0));
          if (expensive)
            {
              SolverControl control(parameters.velocity_inner_iterations,
                                    parameters.velocity_inner_tolerance *
                                      rhs.l2_norm());
              SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
              dst.block(0) = 0;
              cg.solve(system_matrix.block(0, 0), dst.block(0), rhs, velocity_amg);
            }
          else
            velocity_amg.vmult(dst.block(0), rhs);
        }
      }

    private:
      const TrilinosWrappers::BlockSparseMatrix & system_matrix;
      const TrilinosWrappers::SparseMatrix &      weighted_mass;
      const TrilinosWrappers::PreconditionAMG &   velocity_amg;
      const TrilinosWrappers::PreconditionJacobi &mass_jacobi;
      const StokesSolver::Parameters &            parameters;
      const bool                                  expensive;
    };


    /// The cell's viscosities replaced by one average (or left as they are).
    void
    average_viscosity(const StokesSolver::Averaging averaging,
                      const std::vector<double> &   JxW,
                      std::vector<double> &         viscosity)
    {
      if (averaging == StokesSolver::Averaging::none)
        return;
      double weight = 0, sum = 0;
      for (unsigned int q = 0; q < JxW.size(); ++q)
        {
          weight += JxW[q];
          switch (averaging)
            {
              case StokesSolver::Averaging::arithmetic:
                sum += JxW[q] * viscosity[q];
                break;
              case StokesSolver::Averaging::harmonic:
                sum += JxW[q] / viscosity[q];
                break;
              default:
                sum += JxW[q] * std::log(viscosity[q]);
            }
        }
      const double mean =
        (averaging == StokesSolver::Averaging::arithmetic ? sum / weight :
         averaging == StokesSolver::Averaging::harmonic   ? weight / sum :
                                                            std::exp(sum / weight));
      std::fill(viscosity.begin(), viscosity.end(), mean);
    }


    std::unique_ptr<FiniteElement<dim>>
    pressure_element(const StokesSolver::PressureElement element)
    {
      if (element == StokesSolver::PressureElement::discontinuous)
        return std::make_unique<FE_DGP<dim>>(1);
      return std::make_unique<FE_Q<dim>>(1);
    }
  } // namespace


  void
  StokesSolver::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stokes solver");
    prm.declare_entry("Method",
                      "block preconditioned",
                      Patterns::Selection("block preconditioned|direct|thesis"),
                      "block preconditioned: FGMRES with AMG on the velocity "
                      "block and the 1/η-weighted pressure mass matrix for the "
                      "Schur complement (scales to large meshes). direct: "
                      "sparse LU (Amesos KLU) of the whole system, for tiny "
                      "meshes and debugging. thesis: the thesis' solver, GMRES "
                      "(AztecOO) with an incomplete LU factorisation of the "
                      "whole system, as a baseline for benchmarks.");
    prm.declare_entry("Tolerance",
                      "1e-8",
                      Patterns::Double(0, 1),
                      "Relative residual reduction of the Krylov solve, in (0, 1).");
    prm.declare_entry("Maximum iterations",
                      "1000",
                      Patterns::Integer(1),
                      "Maximum FGMRES iterations before the run stops with an "
                      "error.");
    prm.declare_entry("Viscosity averaging",
                      "none",
                      Patterns::Selection("none|arithmetic|harmonic|geometric"),
                      "none: η(φ) at every quadrature point. The others "
                      "replace it in each cell by its cell mean (ASPECT's "
                      "trick against large viscosity contrasts), which changes "
                      "the model by O(Δx) at the biofilm's edge: on the bulb at "
                      "Δx = 1/32 harmonic averaging triples the error for the "
                      "same solver cost (doc/numerics.md); at ratios of 1e4 "
                      "it saves a fifth of the iterations (doc/performance.md).");
    prm.declare_entry("Pressure element",
                      "continuous",
                      Patterns::Selection("continuous|discontinuous"),
                      "continuous: Q2 × Q1 Taylor–Hood (the thesis), which "
                      "leaves a cell-wise divergence of up to 0.4 max|u| at the "
                      "biofilm's edge. discontinuous: Q2 × P1disc (ASPECT's "
                      "locally conservative discretisation), whose pressure may "
                      "jump between cells as the true one does at the viscosity "
                      "jump: ∫_K ∇·u = 0 on every cell K. See doc/numerics.md.");
    prm.declare_entry("Implicit elastic viscosity",
                      "false",
                      Patterns::Bool(),
                      "false: the Picard loop puts the elastic stress on the "
                      "right-hand side only (the thesis); it contracts only "
                      "where the viscosity with which one step's stress update "
                      "answers a velocity gradient, about ηp k/(λ + k), is "
                      "below the solvent viscosity ηs, which the thesis "
                      "mixture always meets and a biofilm with ηs << ηp "
                      "(Model/Rheology = phases) does not. true: that "
                      "viscosity is added to the matrix and, times the current "
                      "iterate's 2D(u), to the right-hand side; both cancel "
                      "when the loop has converged (doc/numerics.md).");
    prm.enter_subsection("Preconditioner");
    prm.declare_entry("Krylov basis",
                      "100",
                      Patterns::Integer(1),
                      "FGMRES restart length (vectors kept), >= 1.");
    prm.declare_entry("Cheap iterations",
                      "100",
                      Patterns::Integer(0),
                      "FGMRES iterations with one AMG application for the "
                      "velocity block before the solver goes on with an inner "
                      "CG solve per application (expensive, for hard cases), "
                      ">= 0.");
    prm.declare_entry("AMG cycle",
                      "W",
                      Patterns::Selection("V|W"),
                      "Multigrid cycle of the velocity block's AMG (Trilinos ML).");
    prm.declare_entry("AMG cycles",
                      "2",
                      Patterns::Integer(1),
                      "AMG cycles per application, >= 1. Two W-cycles keep "
                      "FGMRES below 40 iterations up to Δx = 1/256 at viscosity "
                      "ratio 1e4 (doc/performance.md).");
    prm.declare_entry("AMG smoother sweeps",
                      "2",
                      Patterns::Integer(1),
                      "Smoother sweeps on each AMG level, >= 1.");
    prm.declare_entry("AMG aggregation threshold",
                      "0.02",
                      Patterns::Double(0, 1),
                      "Couplings weaker than this (relative) are dropped when "
                      "ML builds the coarse levels, in [0, 1].");
    prm.declare_entry("Velocity inner tolerance",
                      "1e-2",
                      Patterns::Double(0, 1),
                      "Relative tolerance of the inner CG solve of the velocity "
                      "block in the expensive iterations, in (0, 1).");
    prm.declare_entry("Velocity inner iterations",
                      "1000",
                      Patterns::Integer(1),
                      "Iterations of the velocity block's inner CG solve at "
                      "most, >= 1.");
    prm.declare_entry("Schur inner tolerance",
                      "1e-3",
                      Patterns::Double(0, 1),
                      "Relative tolerance of the inner CG solve with the "
                      "1/η-weighted pressure mass matrix (the Schur complement's "
                      "stand-in), in (0, 1).");
    prm.declare_entry("Schur inner iterations",
                      "200",
                      Patterns::Integer(1),
                      "Iterations of the inner CG solve with the weighted "
                      "pressure mass matrix at most, >= 1.");
    prm.declare_entry("Reuse",
                      "true",
                      Patterns::Bool(),
                      "true: keep the velocity block's AMG hierarchy across "
                      "matrix assemblies (one per time step, as φ moves) "
                      "until one of the two "
                      "rebuild criteria below holds; the Krylov solver always "
                      "uses the current matrix, so the answer is the same to "
                      "the solver tolerance. false: build it for every new "
                      "matrix. See doc/numerics.md.");
    prm.declare_entry("Rebuild viscosity change",
                      "0.1",
                      Patterns::Double(0),
                      "With Reuse: rebuild the AMG when the volume mean of "
                      "|ln(η/η_built)| over the quadrature points, η_built the "
                      "viscosity the AMG was built with, exceeds this, >= 0 "
                      "(0: rebuild whenever the viscosity changed).");
    prm.declare_entry("Rebuild iteration growth",
                      "1.5",
                      Patterns::Double(1),
                      "With Reuse: rebuild the AMG at the next assembly when "
                      "the first solve with a new matrix took more than this "
                      "factor times the outer iterations of the first solve "
                      "after the last build, >= 1.");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  void
  StokesSolver::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stokes solver");
    const std::string name = prm.get("Method");
    method = (name == "direct" ? Method::direct :
              name == "thesis" ? Method::thesis :
                                 Method::block_preconditioned);
    tolerance      = prm.get_double("Tolerance");
    max_iterations = prm.get_integer("Maximum iterations");
    const std::string a = prm.get("Viscosity averaging");
    averaging = (a == "none"       ? Averaging::none :
                 a == "arithmetic" ? Averaging::arithmetic :
                 a == "harmonic"   ? Averaging::harmonic :
                                     Averaging::geometric);
    pressure_element = (prm.get("Pressure element") == "discontinuous" ?
                          PressureElement::discontinuous :
                          PressureElement::continuous);
    implicit_elastic_viscosity = prm.get_bool("Implicit elastic viscosity");
    prm.enter_subsection("Preconditioner");
    krylov_basis              = prm.get_integer("Krylov basis");
    cheap_iterations          = prm.get_integer("Cheap iterations");
    amg_w_cycle               = (prm.get("AMG cycle") == "W");
    amg_cycles                = prm.get_integer("AMG cycles");
    amg_smoother_sweeps       = prm.get_integer("AMG smoother sweeps");
    amg_aggregation_threshold = prm.get_double("AMG aggregation threshold");
    velocity_inner_tolerance  = prm.get_double("Velocity inner tolerance");
    velocity_inner_iterations = prm.get_integer("Velocity inner iterations");
    schur_inner_tolerance     = prm.get_double("Schur inner tolerance");
    schur_inner_iterations    = prm.get_integer("Schur inner iterations");
    reuse_preconditioner      = prm.get_bool("Reuse");
    rebuild_viscosity_change  = prm.get_double("Rebuild viscosity change");
    rebuild_iteration_growth  = prm.get_double("Rebuild iteration growth");
    prm.leave_subsection();
    prm.leave_subsection();
    check_input(tolerance > 0,
                "Stokes solver/Tolerance must be in (0, 1), got 0");
    check_input(velocity_inner_tolerance > 0,
                "Stokes solver/Preconditioner/Velocity inner tolerance must be "
                "in (0, 1), got 0");
    check_input(schur_inner_tolerance > 0,
                "Stokes solver/Preconditioner/Schur inner tolerance must be in "
                "(0, 1), got 0");
  }


  StokesSolver::StokesSolver(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const Parameters &                             parameters,
    const Model &                                  model,
    const BoundaryConditions &                     boundary_conditions,
    const unsigned int                             order)
    : triangulation(triangulation)
    , parameters(parameters)
    , model(model)
    , boundary_conditions(boundary_conditions)
    , mpi_communicator(triangulation.get_communicator())
    , fe(FE_Q<dim>(2), dim, *pressure_element(parameters.pressure_element), 1)
    , dofs(triangulation)
    , order(order)
    , flow_postprocessor(std::make_unique<FlowPostprocessor>())
  {}


  void
  StokesSolver::setup_dofs()
  {
    dofs.distribute_dofs(fe);
    // Block 0: the dim velocity components; block 1: the pressure.
    std::vector<unsigned int> block_component(dim + 1, 0);
    block_component[dim] = 1;
    DoFRenumbering::component_wise(dofs, block_component);
    const std::vector<types::global_dof_index> dofs_per_block =
      DoFTools::count_dofs_per_fe_block(dofs, block_component);
    const types::global_dof_index n_u = dofs_per_block[0],
                                  n_p = dofs_per_block[1];

    const IndexSet &owned = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    owned_partitioning    = {owned.get_view(0, n_u), owned.get_view(n_u, n_u + n_p)};
    relevant_partitioning = {locally_relevant_dofs.get_view(0, n_u),
                             locally_relevant_dofs.get_view(n_u, n_u + n_p)};

    // The constrained dofs do not change in time, only their values do.
    make_constraints(0.0);
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);

    // The AMG refers to the matrix it was built from: drop it first.
    velocity_amg.reset();
    mass_jacobi.reset();
    viscosity_at_build.clear();
    rebuild_requested = false;
    system_matrix.clear();
    preconditioner_matrix.clear();
    monolithic_matrix.clear();
    if (parameters.method != Method::block_preconditioned)
      {
        TrilinosWrappers::SparsityPattern sparsity(owned,
                                                   owned,
                                                   locally_relevant_dofs,
                                                   mpi_communicator);
        DoFTools::make_sparsity_pattern(dofs, sparsity, constraints, false, rank);
        sparsity.compress();
        monolithic_matrix.reinit(sparsity);
      }
    else
      {
        // Components 0 … dim − 1: u; dim: p.
        Table<2, DoFTools::Coupling> coupling(dim + 1, dim + 1);
        Table<2, DoFTools::Coupling> mass_coupling(dim + 1, dim + 1);
        for (unsigned int c = 0; c < dim + 1; ++c)
          for (unsigned int d = 0; d < dim + 1; ++d)
            {
              coupling[c][d] = (c == dim && d == dim) ? DoFTools::none :
                                                        DoFTools::always;
              mass_coupling[c][d] = (c == dim && d == dim) ? DoFTools::always :
                                                             DoFTools::none;
            }
        TrilinosWrappers::BlockSparsityPattern sparsity(owned_partitioning,
                                                        owned_partitioning,
                                                        relevant_partitioning,
                                                        mpi_communicator);
        DoFTools::make_sparsity_pattern(dofs, coupling, sparsity, constraints, false, rank);
        sparsity.compress();
        system_matrix.reinit(sparsity);

        TrilinosWrappers::BlockSparsityPattern mass_sparsity(owned_partitioning,
                                                             owned_partitioning,
                                                             relevant_partitioning,
                                                             mpi_communicator);
        DoFTools::make_sparsity_pattern(
          dofs, mass_coupling, mass_sparsity, constraints, false, rank);
        mass_sparsity.compress();
        preconditioner_matrix.reinit(mass_sparsity);
      }

    system_rhs.reinit(owned_partitioning, mpi_communicator);
    current_solution.reinit(owned_partitioning, relevant_partitioning, mpi_communicator);
    old_solution.reinit(owned_partitioning, relevant_partitioning, mpi_communicator);
    older_solution.reinit(owned_partitioning, relevant_partitioning, mpi_communicator);
    invalidate_matrix();
  }


  void
  StokesSolver::make_constraints(const double time)
  {
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    boundary_conditions.constrain_velocity(dofs, time, constraints);

    // A factorisation needs a nonsingular matrix: unless a boundary fixes the
    // pressure level, pin the first pressure dof (Q1: a coarse-mesh vertex,
    // never hanging; P1disc: the mean of rank 0's first cell); the pressure
    // is shifted to mean zero after the solve. Before the periodic
    // constraints, which respect it (as they do boundary values).
    if (parameters.method != Method::block_preconditioned &&
        !boundary_conditions.fixes_pressure_level())
      {
        const types::global_dof_index first_pressure_dof =
          owned_partitioning[0].size();
        if (locally_relevant_dofs.is_element(first_pressure_dof))
          {
            AssertThrow(!constraints.is_constrained(first_pressure_dof),
                        ExcInternalError());
            constraints.add_line(first_pressure_dof);
          }
      }
    boundary_conditions.constrain_periodic(dofs, constraints);
    constraints.close();
  }


  void
  StokesSolver::invalidate_matrix()
  {
    matrix_is_current = false;
  }


  void
  StokesSolver::assemble(const Coefficients &coefficients)
  {
    make_constraints(coefficients.time);

    const bool assemble_matrix = !matrix_is_current;
    const bool direct = (parameters.method != Method::block_preconditioned);
    if (assemble_matrix && direct)
      monolithic_matrix = 0;
    else if (assemble_matrix)
      {
        system_matrix         = 0;
        preconditioner_matrix = 0;
      }
    system_rhs = 0;

    const Quadrature<dim> quadrature = this->quadrature();
    FEValues<dim>     fe_values(fe,
                          quadrature,
                          update_values | update_gradients |
                            update_quadrature_points | update_JxW_values);
    FEValues<dim>     phi_fe_values(coefficients.volume_fraction_dof_handler->get_fe(),
                              quadrature,
                              update_values);
    // The prescribed normal traction −P n of pressure boundaries.
    const QGauss<dim - 1> face_quadrature(fe.degree + 1);
    FEFaceValues<dim>     fe_face_values(fe,
                                     face_quadrature,
                                     update_values | update_normal_vectors |
                                       update_quadrature_points | update_JxW_values);
    for (const auto &boundary : boundary_conditions.boundaries)
      boundary.pressure.function().set_time(coefficients.time);

    const unsigned int dofs_per_cell = fe.n_dofs_per_cell();
    const unsigned int n_q_points    = quadrature.size();
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(dim);

    FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
    FullMatrix<double> cell_mass(dofs_per_cell, dofs_per_cell);
    Vector<double>     cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);

    std::vector<double>                volume_fraction(n_q_points);
    std::vector<double>                viscosity(n_q_points);
    std::vector<Tensor<1, dim>>          old_velocity(n_q_points);
    std::vector<Tensor<1, dim>>        older_velocity(n_q_points); // zero unless BDF2
    std::vector<Vector<double>>        body_force(n_q_points, Vector<double>(dim));
    std::vector<SymmetricTensor<2, dim>> tau(n_q_points);
    std::vector<double>                elastic_viscosity(n_q_points, 0.0);
    std::vector<SymmetricTensor<2, dim>> iterate_strain_rate(n_q_points);
    const bool implicit_elastic =
      parameters.implicit_elastic_viscosity && model.viscoelastic;
    if (implicit_elastic && assemble_matrix)
      elastic_viscosity_cache.resize(triangulation.n_locally_owned_active_cells() *
                                     n_q_points);
    std::size_t cached = 0;
    // η at the quadrature points, for the AMG's rebuild criterion: the
    // integrals of |ln(η/η_built)| and of 1 (Preconditioner/Reuse).
    const bool track_viscosity =
      assemble_matrix && !direct && parameters.reuse_preconditioner;
    const bool compare_viscosity =
      track_viscosity && velocity_amg &&
      viscosity_at_build.size() ==
        triangulation.n_locally_owned_active_cells() * n_q_points;
    std::vector<double> viscosity_now;
    if (track_viscosity)
      viscosity_now.reserve(triangulation.n_locally_owned_active_cells() * n_q_points);
    double change_integrals[2] = {0, 0};
    const bool                         use_feet = !old_velocity_at_feet.empty();
    unsigned int                       foot     = 0;

    std::vector<Tensor<1, dim>>          phi_u(dofs_per_cell);
    std::vector<SymmetricTensor<2, dim>> symgrad_phi_u(dofs_per_cell);
    std::vector<double>                div_phi_u(dofs_per_cell);
    std::vector<double>                phi_p(dofs_per_cell);

    // Res ∂u/∂t (ρ ∂u/∂t in SI) by implicit Euler, (Res/k)(u − u^n, v), or
    // with u^{n-1} by BDF2 with variable steps, ω = k_n/k_{n-1}:
    // (Res/k)((1+2ω)/(1+ω) u − (1+ω) u^n + ω²/(1+ω) u^{n-1}, v).
    const bool   bdf2  = !previous_velocity_at_feet.empty();
    const double omega = bdf2 ? coefficients.time_step / previous_step : 0;
    const double mass_coefficient =
      model.density / coefficients.time_step * (bdf2 ? (1 + 2 * omega) / (1 + omega) : 1);
    const double old_coefficient =
      model.density / coefficients.time_step * (bdf2 ? 1 + omega : 1);
    const double older_coefficient =
      model.density / coefficients.time_step * omega * omega / (1 + omega);
    coefficients.body_force->set_time(coefficients.time);

    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          phi_fe_values.reinit(cell_of(*coefficients.volume_fraction_dof_handler, cell));
          phi_fe_values.get_function_values(*coefficients.volume_fraction,
                                            volume_fraction);
          for (unsigned int q = 0; q < n_q_points; ++q)
            viscosity[q] = model.viscosity(volume_fraction[q]);
          if (coefficients.elastic_stress)
            coefficients.elastic_stress(cell, volume_fraction, tau);
          average_viscosity(parameters.averaging, fe_values.get_JxW_values(), viscosity);
          if (implicit_elastic)
            {
              // From τ^n (the stress iterate when the matrix is built, at the
              // step's first Picard iteration), kept for the step: matrix and
              // right-hand side must use the same η_e for the two to cancel (added
              // after the averaging, which is a model of ηs only).
              fe_values[velocities].get_function_symmetric_gradients(current_solution,
                                                                     iterate_strain_rate);
              for (unsigned int q = 0; q < n_q_points; ++q, ++cached)
                {
                  if (assemble_matrix)
                    elastic_viscosity_cache[cached] =
                      model.elastic_viscosity(volume_fraction[q],
                                              coefficients.time_step,
                                              tau[q]);
                  elastic_viscosity[q] = elastic_viscosity_cache[cached];
                  viscosity[q] += elastic_viscosity[q];
                }
            }

          if (track_viscosity)
            for (unsigned int q = 0; q < n_q_points; ++q)
              {
                if (compare_viscosity)
                  {
                    change_integrals[0] +=
                      std::abs(std::log(viscosity[q] /
                                        viscosity_at_build[viscosity_now.size()])) *
                      fe_values.JxW(q);
                    change_integrals[1] += fe_values.JxW(q);
                  }
                viscosity_now.push_back(viscosity[q]);
              }

          if (use_feet)
            for (unsigned int q = 0; q < n_q_points; ++q, ++foot)
              {
                old_velocity[q] = old_velocity_at_feet[foot];
                if (bdf2)
                  older_velocity[q] = previous_velocity_at_feet[foot];
              }
          else
            fe_values[velocities].get_function_values(old_solution, old_velocity);
          coefficients.body_force->vector_value_list(
            fe_values.get_quadrature_points(), body_force);

          // With the matrix current, the cell matrix is needed only to move
          // the inhomogeneities of constrained dofs to the right-hand side:
          // boundary values, and hanging dofs constrained to boundary dofs,
          // which interior cells touching the wall at a vertex also hold.
          cell->get_dof_indices(local_dof_indices);
          const bool need_matrix =
            assemble_matrix ||
            std::any_of(local_dof_indices.begin(),
                        local_dof_indices.end(),
                        [this](const types::global_dof_index i) {
                          return constraints.is_inhomogeneously_constrained(i);
                        });
          cell_matrix = 0;
          cell_mass   = 0;
          cell_rhs    = 0;
          for (unsigned int q = 0; q < n_q_points; ++q)
            {
              for (unsigned int k = 0; k < dofs_per_cell; ++k)
                {
                  phi_u[k]         = fe_values[velocities].value(k, q);
                  symgrad_phi_u[k] = fe_values[velocities].symmetric_gradient(k, q);
                  div_phi_u[k]     = fe_values[velocities].divergence(k, q);
                  phi_p[k]         = fe_values[pressure].value(k, q);
                }
              const double       JxW = fe_values.JxW(q);
              Tensor<1, dim> force;
              for (unsigned int d = 0; d < dim; ++d)
                force[d] = body_force[q][d];
              const Tensor<1, dim> rhs_vector =
                old_coefficient * old_velocity[q] + force -
                older_coefficient * older_velocity[q];
              // s(φ) τ: φ τ in the thesis (eq. 2.34), τ for phases.
              // With the implicit elastic viscosity η_e in the matrix, its
              // explicit twin 2 η_e D(u^l) joins s τ on the right.
              const SymmetricTensor<2, dim> phi_tau =
                model.stress_coupling(volume_fraction[q]) * tau[q] -
                2 * elastic_viscosity[q] * iterate_strain_rate[q];

              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  for (unsigned int j = 0; j < dofs_per_cell && need_matrix; ++j)
                    {
                      cell_matrix(i, j) +=
                        (mass_coefficient * phi_u[i] * phi_u[j] +
                         2 * viscosity[q] * (symgrad_phi_u[i] * symgrad_phi_u[j]) -
                         div_phi_u[i] * phi_p[j] - phi_p[i] * div_phi_u[j]) *
                        JxW;
                      cell_mass(i, j) += phi_p[i] * phi_p[j] / viscosity[q] * JxW;
                    }
                  cell_rhs(i) += (rhs_vector * phi_u[i] -
                                  phi_tau * symgrad_phi_u[i]) *
                                 JxW;
                }
            }

          // −∫ P n·v ds (Type = pressure; outflow has P = 0).
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() &&
                boundary_conditions.boundary(face->boundary_id()).type ==
                  BoundaryConditions::Type::pressure)
              {
                const Function<dim> &pressure =
                  boundary_conditions.boundary(face->boundary_id()).pressure.function();
                fe_face_values.reinit(cell, face);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const double traction =
                      pressure.value(fe_face_values.quadrature_point(q)) *
                      fe_face_values.JxW(q);
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      cell_rhs(i) -= traction * (fe_face_values[velocities].value(i, q) *
                                                 fe_face_values.normal_vector(q));
                  }
              }

          if (assemble_matrix)
            {
              if (direct)
                constraints.distribute_local_to_global(cell_matrix,
                                                       local_dof_indices,
                                                       monolithic_matrix);
              else
                {
                  constraints.distribute_local_to_global(cell_matrix,
                                                         local_dof_indices,
                                                         system_matrix);
                  constraints.distribute_local_to_global(cell_mass,
                                                         local_dof_indices,
                                                         preconditioner_matrix);
                }
            }
          constraints.distribute_local_to_global(cell_rhs,
                                                 local_dof_indices,
                                                 system_rhs,
                                                 cell_matrix);
        }

    if (assemble_matrix)
      {
        if (direct)
          monolithic_matrix.compress(VectorOperation::add);
        else
          {
            system_matrix.compress(VectorOperation::add);
            preconditioner_matrix.compress(VectorOperation::add);
          }
        matrix_is_current              = true;
        mass_preconditioner_is_current = false;
        first_solve_with_matrix        = true;
        // Keep the AMG while it still fits the new matrix (Reuse).
        viscosity_change = 0;
        if (compare_viscosity)
          {
            Utilities::MPI::sum(change_integrals, mpi_communicator, change_integrals);
            viscosity_change = change_integrals[0] / change_integrals[1];
          }
        if (!compare_viscosity || rebuild_requested ||
            viscosity_change > parameters.rebuild_viscosity_change)
          {
            preconditioner_is_current = false;
            viscosity_at_build.swap(viscosity_now);
          }
      }
    system_rhs.compress(VectorOperation::add);
    // Constrained rows are decoupled (their values come from distribute()).
    // With zero right-hand side and first guess there they stay zero in the
    // Krylov space; otherwise their diagonal, of the size of η, meets the
    // preconditioner's pressure mass, of the size of h²/η, at hanging pressure
    // nodes and stalls FGMRES at large viscosity contrasts.
    constraints.set_zero(system_rhs);
  }


  Quadrature<dim>
  StokesSolver::quadrature() const
  {
    return QGauss<dim>(fe.degree + 1);
  }


  void
  StokesSolver::trace_back(DepartureFeet &feet, const double time_step)
  {
    step_length = time_step;
    old_velocity_at_feet.clear();
    previous_velocity_at_feet.clear();
    if (model.density == 0)
      return;
    FEValues<dim> fe_values(fe, quadrature(), update_quadrature_points);
    std::vector<Point<dim>>                               points;
    std::vector<Triangulation<dim>::active_cell_iterator> cells;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const Point<dim> &p : fe_values.get_quadrature_points())
            {
              points.push_back(p);
              cells.push_back(cell);
            }
        }
    // Order 1: feet by u^n. Order 2: u^n at the feet one step back and, for
    // BDF2, u^{n-1} at the feet two steps back, each traced with the velocity
    // at the middle of its interval, t_{n+1} − duration/2 (second order).
    const auto at_feet = [&](const double                              duration,
                             const TrilinosWrappers::MPI::BlockVector &values,
                             std::vector<Tensor<1, dim>> &               result) {
      feet.compute(points,
                   cells,
                   dofs,
                   order == 2 ? extrapolated_solution(time_step - 0.5 * duration) :
                                old_solution,
                   duration);
      for (const auto &value : evaluate_velocity(feet.at_feet(), dofs, values))
        {
          Tensor<1, dim> u;
          for (unsigned int d = 0; d < dim; ++d)
            u[d] = value[d];
          result.push_back(u);
        }
    };
    at_feet(time_step, old_solution, old_velocity_at_feet);
    if (order == 2 && previous_step > 0)
      at_feet(time_step + previous_step, older_solution, previous_velocity_at_feet);
  }


  TrilinosWrappers::MPI::BlockVector
  StokesSolver::extrapolated_solution(const double offset) const
  {
    TrilinosWrappers::MPI::BlockVector velocity = old_solution;
    if (previous_step > 0)
      {
        // u(t_n + offset) ≈ u^n + θ (u^n − u^{n-1}), θ = offset / k_{n-1}.
        const double theta = offset / previous_step;
        TrilinosWrappers::MPI::BlockVector distributed(owned_partitioning,
                                                       mpi_communicator);
        distributed = old_solution;
        distributed *= 1 + theta;
        TrilinosWrappers::MPI::BlockVector older(owned_partitioning, mpi_communicator);
        older = older_solution;
        distributed.add(-theta, older);
        velocity = distributed;
      }
    return velocity;
  }


  void
  StokesSolver::build_preconditioner()
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    const FEValuesExtractors::Vector                  velocities(0);
    DoFTools::extract_constant_modes(dofs,
                                     fe.component_mask(velocities),
                                     amg_data.constant_modes);
    amg_data.elliptic              = true;
    amg_data.higher_order_elements = true;
    amg_data.smoother_sweeps       = parameters.amg_smoother_sweeps;
    amg_data.aggregation_threshold = parameters.amg_aggregation_threshold;
    amg_data.w_cycle               = parameters.amg_w_cycle;
    amg_data.n_cycles              = parameters.amg_cycles;
    velocity_amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    velocity_amg->initialize(system_matrix.block(0, 0), amg_data);
    preconditioner_is_current = true;
    rebuild_requested         = false;
    ++n_builds;
  }


  unsigned int
  StokesSolver::solve()
  {
    TrilinosWrappers::MPI::BlockVector distributed(owned_partitioning,
                                                   mpi_communicator);
    const unsigned int iterations =
      (parameters.method == Method::block_preconditioned ?
         solve_block_preconditioned(distributed) :
         solve_monolithic(distributed));
    constraints.distribute(distributed);
    AssertThrow(std::isfinite(distributed.l2_norm()),
                ExcMessage("the Stokes solution is not finite (NaN or inf)"));
    normalize_pressure(distributed);
    current_solution = distributed;
    return iterations;
  }


  unsigned int
  StokesSolver::solve_block_preconditioned(
    TrilinosWrappers::MPI::BlockVector &distributed)
  {
    bool built = !preconditioner_is_current;
    if (built)
      build_preconditioner();
    if (!mass_preconditioner_is_current)
      {
        mass_jacobi = std::make_unique<TrilinosWrappers::PreconditionJacobi>();
        mass_jacobi->initialize(preconditioner_matrix.block(1, 1));
        mass_preconditioner_is_current = true;
      }

    // FGMRES from `distributed` with at most n_cheap cheap iterations, then
    // (if `go_on`) expensive ones; true if it converged.
    const double target = parameters.tolerance * system_rhs.l2_norm();
    unsigned int iterations = 0;
    const auto fgmres = [&](const unsigned int n_cheap, const bool go_on) {
      for (const bool expensive : {false, true})
        {
          SolverControl control(expensive ? parameters.max_iterations : n_cheap, target);
          SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(
            control,
            SolverFGMRES<TrilinosWrappers::MPI::BlockVector>::AdditionalData(
              parameters.krylov_basis));
          const BlockSchurPreconditioner preconditioner(
            system_matrix,
            preconditioner_matrix.block(1, 1),
            *velocity_amg,
            *mass_jacobi,
            parameters,
            expensive);
          try
            {
              solver.solve(system_matrix, distributed, system_rhs, preconditioner);
              iterations += control.last_step();
              return true;
            }
          catch (const SolverControl::NoConvergence &e)
            {
              iterations += e.last_step;
              if (expensive)
                throw ExcMessage(
                  "the Stokes solver (FGMRES) did not converge in " +
                  std::to_string(iterations) + " iterations: residual " +
                  Utilities::to_string(e.last_residual) + ", target " +
                  Utilities::to_string(control.tolerance()) +
                  " (Stokes solver/Maximum iterations = " +
                  std::to_string(parameters.max_iterations) + ")");
              if (!go_on)
                return false;
            }
        }
      return false;
    };

    if (target > 0)
      {
        distributed = current_solution; // the last solution as first guess
        constraints.set_zero(distributed);
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
                build_preconditioner();
                built = true;
              }
            // Cheap iterations first; if they stall, go on from where they
            // got with expensive ones (ASPECT's strategy).
            fgmres(n_cheap, true);
          }
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


  unsigned int
  StokesSolver::solve_monolithic(TrilinosWrappers::MPI::BlockVector &distributed)
  {
    const IndexSet &              owned = dofs.locally_owned_dofs();
    TrilinosWrappers::MPI::Vector rhs(owned, mpi_communicator);
    TrilinosWrappers::MPI::Vector solution(owned, mpi_communicator);
    for (const auto i : owned)
      {
        rhs(i)      = system_rhs(i);
        solution(i) = current_solution(i);
      }
    rhs.compress(VectorOperation::insert);
    solution.compress(VectorOperation::insert);

    unsigned int iterations = 0;
    if (parameters.method == Method::direct)
      {
        SolverControl                  control(1, 0);
        TrilinosWrappers::SolverDirect solver(control);
        solver.solve(monolithic_matrix, solution, rhs);
      }
    else
      {
        // ILU(0) of the saddle-point matrix; the zero pressure diagonal
        // needs the absolute diagonal shift ilu_atol to factorise.
        TrilinosWrappers::PreconditionILU ilu;
        ilu.initialize(monolithic_matrix,
                       TrilinosWrappers::PreconditionILU::AdditionalData(0, 1e-8));
        SolverControl control(parameters.max_iterations,
                              parameters.tolerance * rhs.l2_norm());
        TrilinosWrappers::SolverGMRES solver(
          control, TrilinosWrappers::SolverGMRES::AdditionalData(false, 100));
        try
          {
            solver.solve(monolithic_matrix, solution, rhs, ilu);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            throw ExcMessage("the Stokes solver (thesis: GMRES + ILU) did not "
                             "converge in " + std::to_string(e.last_step) +
                             " iterations: residual " +
                             Utilities::to_string(e.last_residual) +
                             " (Stokes solver/Maximum iterations = " +
                             std::to_string(parameters.max_iterations) + ")");
          }
        iterations = control.last_step();
      }

    for (const auto i : owned)
      distributed(i) = solution(i);
    distributed.compress(VectorOperation::insert);
    return iterations;
  }


  void
  StokesSolver::normalize_pressure(TrilinosWrappers::MPI::BlockVector &distributed)
  {
    if (boundary_conditions.fixes_pressure_level())
      return;
    current_solution = distributed;
    const double mean_pressure =
      VectorTools::compute_mean_value(dofs, QGauss<dim>(3), current_solution, dim);
    // The dofs whose shape functions sum to 1: all of Q1's, the cell mean
    // of P1disc's (its slopes must stay).
    std::vector<std::vector<bool>> constant_modes;
    DoFTools::extract_constant_modes(dofs,
                                     fe.component_mask(FEValuesExtractors::Scalar(dim)),
                                     constant_modes);
    const IndexSet &owned_pressure = owned_partitioning[1];
    for (unsigned int i = 0; i < owned_pressure.n_elements(); ++i)
      if (constant_modes[0][i])
        distributed.block(1)(owned_pressure.nth_index_in_set(i)) -= mean_pressure;
    distributed.compress(VectorOperation::add);
  }


  void
  StokesSolver::prepare_for_refinement()
  {
    carrier.prepare(dofs, current_solution);
    if (order == 2)
      previous_carrier.prepare(dofs, older_solution);
  }


  void
  StokesSolver::finish_refinement()
  {
    setup_dofs();
    TrilinosWrappers::MPI::BlockVector distributed(owned_partitioning,
                                                   mpi_communicator);
    carrier.finish(dofs, distributed);
    current_solution = distributed;
    old_solution     = distributed;
    if (order == 2)
      {
        previous_carrier.finish(dofs, distributed);
        older_solution = distributed;
      }
  }


  void
  StokesSolver::prepare_for_checkpoint()
  {
    carrier.prepare_checkpoint(dofs, current_solution);
    if (order == 2)
      previous_carrier.prepare_checkpoint(dofs, older_solution);
  }


  void
  StokesSolver::checkpoint_written()
  {
    carrier.release();
    previous_carrier.release();
  }


  void
  StokesSolver::advance_time()
  {
    if (order == 2)
      {
        older_solution = old_solution;
        previous_step  = step_length;
      }
    old_solution = current_solution;
  }


  const TrilinosWrappers::MPI::BlockVector &
  StokesSolver::previous_solution() const
  {
    return older_solution;
  }


  double
  StokesSolver::previous_time_step() const
  {
    return previous_step;
  }


  const TrilinosWrappers::MPI::BlockVector &
  StokesSolver::start_of_step_solution() const
  {
    return old_solution;
  }


  void
  StokesSolver::set_previous_time_step(const double time_step)
  {
    previous_step = time_step;
  }


  void
  StokesSolver::restore_old()
  {
    current_solution = old_solution;
  }


  const DoFHandler<dim> &
  StokesSolver::dof_handler() const
  {
    return dofs;
  }


  const TrilinosWrappers::MPI::BlockVector &
  StokesSolver::solution() const
  {
    return current_solution;
  }


  types::global_dof_index
  StokesSolver::n_dofs() const
  {
    return dofs.n_dofs();
  }


  void
  StokesSolver::add_output(DataOut<dim> &data_out) const
  {
    std::vector<std::string> names(dim, "velocity");
    names.push_back("pressure");
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim, DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);
    data_out.add_data_vector(dofs, current_solution, names, interpretation);
    data_out.add_data_vector(dofs, current_solution, *flow_postprocessor);
  }


  double
  StokesSolver::max_velocity() const
  {
    const Quadrature<dim> nodes(fe.base_element(0).get_unit_support_points());
    FEValues<dim>         fe_values(fe, nodes, update_values);
    std::vector<Tensor<1, dim>> velocity(nodes.size());
    const FEValuesExtractors::Vector velocities(0);
    double                    max_speed = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current_solution, velocity);
          for (const Tensor<1, dim> &u : velocity)
            max_speed = std::max(max_speed, u.norm());
        }
    return Utilities::MPI::max(max_speed, mpi_communicator);
  }


  double
  StokesSolver::max_cell_divergence() const
  {
    const QGauss<dim>                  quadrature(fe.degree + 1);
    FEValues<dim>                      fe_values(fe, quadrature, update_gradients | update_JxW_values);
    std::vector<double>              divergence(quadrature.size());
    const FEValuesExtractors::Vector velocities(0);
    double                           max_divergence = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_divergences(current_solution, divergence);
          double integral = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            integral += divergence[q] * fe_values.JxW(q);
          max_divergence = std::max(max_divergence, std::abs(integral) / cell->measure());
        }
    return Utilities::MPI::max(max_divergence, mpi_communicator);
  }


  Vector<float>
  StokesSolver::velocity_error_indicator() const
  {
    Vector<float> indicator(triangulation.n_active_cells());
    KellyErrorEstimator<dim>::estimate(dofs,
                                     QGauss<dim - 1>(fe.degree + 1),
                                     {},
                                     current_solution,
                                     indicator,
                                     fe.component_mask(FEValuesExtractors::Vector(0)));
    return indicator;
  }


  double
  StokesSolver::velocity_relative_change(
    const TrilinosWrappers::MPI::BlockVector &previous) const
  {
    // ‖u − u_prev‖_L2 / ‖u‖_L2: the velocity alone, as the pressure's size
    // (which grows with the viscosity) says nothing about the flow's change.
    FEValues<dim> fe_values(fe, quadrature(), update_values | update_JxW_values);
    const FEValuesExtractors::Vector velocities(0);
    std::vector<Tensor<1, dim>>        now(fe_values.n_quadrature_points);
    std::vector<Tensor<1, dim>>        before(fe_values.n_quadrature_points);
    double                           squares[2] = {0, 0}; // change, size
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current_solution, now);
          fe_values[velocities].get_function_values(previous, before);
          for (unsigned int q = 0; q < now.size(); ++q)
            {
              squares[0] += (now[q] - before[q]).norm_square() * fe_values.JxW(q);
              squares[1] += now[q].norm_square() * fe_values.JxW(q);
            }
        }
    Utilities::MPI::sum(squares, mpi_communicator, squares);
    return squares[1] > 0 ? std::sqrt(squares[0] / squares[1]) : std::sqrt(squares[0]);
  }


  unsigned int
  StokesSolver::n_preconditioner_builds() const
  {
    return n_builds;
  }


  double
  StokesSolver::viscosity_change_since_build() const
  {
    return viscosity_change;
  }
} // namespace viscofilm
