// The Stokes solver's parameters, dofs, constraints and the life cycle of
// its solutions; the assembly is in stokes_assembly.cc, the linear-solver
// strategies in stokes_linear_solver.h, the diagnostics in
// stokes_diagnostics.cc.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/affine_constraints.templates.h>

#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgp.h>
#include <deal.II/fe/fe_q.h>

#include <deal.II/numerics/vector_tools.h>

#include <Amesos.h>

#include <viscofilm/core/input.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/flow/stokes_linear_solver.h>

#include <cmath>

namespace viscofilm
{
  namespace
  {
    template <int dim>
    std::unique_ptr<FiniteElement<dim>>
    pressure_element(const typename StokesFlow<dim>::PressureElement element)
    {
      if (element == StokesFlow<dim>::PressureElement::discontinuous)
        return std::make_unique<FE_DGP<dim>>(1);
      return std::make_unique<FE_Q<dim>>(1);
    }
  } // namespace


  template <int dim>
  void
  StokesFlow<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stokes solver");
    prm.declare_entry("Method",
                      "auto",
                      Patterns::Selection("auto|block preconditioned|direct|thesis"),
                      "auto: direct where the viscosity ratio max/min of "
                      "Model's η(φ) is 1e4 or more (there the block "
                      "preconditioner's iterations grow past 100) and the "
                      "mesh is one the factorisation fits (Stokes dofs up "
                      "to 6e5 in 2D and 3e4 in 3D with MUMPS, 4e4 and 1e4 "
                      "with KLU; decided at every mesh change), else block "
                      "preconditioned; the run prints the choice. "
                      "block preconditioned: FGMRES with AMG or GMG on the "
                      "velocity block (Preconditioner/Velocity preconditioner) "
                      "and, for the Schur complement, the 1/η-weighted "
                      "pressure mass matrix plus, with a mass term, ρ/k times "
                      "the inverse pressure Laplacian (Cahouet-Chabard; scales "
                      "to large meshes). direct: "
                      "a sparse LU factorisation of the whole system (Direct "
                      "solver), once per assembled matrix: robust at any "
                      "viscosity contrast and Reynolds number, in 2D up to "
                      "about 1e6 unknowns (2 GB a rank at 6e5). thesis: the thesis' solver, GMRES "
                      "(AztecOO) with an incomplete LU factorisation of the "
                      "whole system, as a baseline for benchmarks.");
    prm.declare_entry("Momentum convection",
                      "semi-Lagrangian",
                      Patterns::Selection("semi-Lagrangian|Eulerian"),
                      "The inertia ρ Du/Dt (Model/Density or Reynolds number "
                      "> 0). semi-Lagrangian: differences of u along the "
                      "departure feet (implicit Euler, or BDF2 at Order 2), "
                      "symmetric matrix; a steady state depends on k (DFG "
                      "2D-1's drag is 6.6 % high at Ū k = D/5). "
                      "Eulerian: ρ(∂u/∂t + (u*·∇)u) with the same differences "
                      "in time at the point and the convection implicit in u, "
                      "linearised about u* = u^n (Order 1) or its extrapolation "
                      "2u^n − u^{n-1} (Order 2): a steady state independent of "
                      "k, for steady flows at Re > 1 (in the periodic DFG "
                      "2D-2 it damps the vortex street more than the "
                      "semi-Lagrangian step). Its matrix is not "
                      "symmetric; the block preconditioner approximates its "
                      "symmetric part, so at cell Reynolds numbers ρ|u|Δx/η "
                      "above about 10 use Method = direct.");
    prm.declare_entry("Direct solver",
                      "MUMPS",
                      Patterns::Selection("MUMPS|KLU"),
                      "The factorisation of Method = direct (Trilinos Amesos). "
                      "MUMPS: multifrontal, distributed over the MPI ranks, "
                      "with a nested-dissection ordering; 5 times faster "
                      "than KLU on 1.5e5 unknowns (doc/performance.md). KLU: "
                      "serial (on one rank), for small systems.");
    prm.declare_entry("Tolerance",
                      "1e-8",
                      Patterns::Double(0, 1),
                      "Relative residual reduction of the Krylov solve, in (0, 1).");
    prm.declare_entry("Predictor tolerance",
                      "0",
                      Patterns::Double(0, 1),
                      "The relative residual reduction of the first Picard "
                      "iteration's solve in each step, when it is larger "
                      "than Tolerance (the loop always iterates at least "
                      "twice, so that solve is never its last); 0: "
                      "Tolerance for every solve. With Maximum Picard "
                      "iterations = 2 at Order 2 the first solve is a "
                      "predictor whose u reaches the answer only through "
                      "the φ and τ of the second: 1e-4 there saves a third "
                      "of the FGMRES iterations at the same accuracy "
                      "(doc/performance.md, prm/default.prm).");
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
                      "V",
                      Patterns::Selection("V|W"),
                      "Multigrid cycle of the velocity block's AMG (Trilinos ML).");
    prm.declare_entry("AMG cycles",
                      "1",
                      Patterns::Integer(1),
                      "AMG cycles per application, >= 1. With AMG matrix = Q2, "
                      "two W-cycles keep FGMRES below 40 iterations up to "
                      "Δx = 1/256 at viscosity ratio 1e4; one V-cycle of the "
                      "sub-cell matrix needs more iterations but less time "
                      "(doc/performance.md).");
    prm.declare_entry("AMG smoother sweeps",
                      "2",
                      Patterns::Integer(1),
                      "Smoother sweeps on each AMG level, >= 1.");
    prm.declare_entry("AMG aggregation threshold",
                      "0.02",
                      Patterns::Double(0, 1),
                      "Couplings weaker than this (relative) are dropped when "
                      "ML builds the coarse levels, in [0, 1].");
    prm.declare_entry("AMG smoother",
                      "Chebyshev",
                      Patterns::Selection("Chebyshev|symmetric Gauss-Seidel"),
                      "ML's smoother on each level of the velocity block's AMG.");
    // The fastest measured (doc/performance.md, "The velocity AMG's matrix
    // and cycle"): with the couplings between components in 2D, without in 3D.
    prm.declare_entry("AMG matrix",
                      dim == 2 ? "Q1 sub-cells" : "Q1 sub-cells by component",
                      Patterns::Selection("Q2|Q1 sub-cells|Q1 sub-cells by component"),
                      "The matrix ML builds its hierarchy from. Q2: the velocity "
                      "block of the system. Q1 sub-cells: the same operator "
                      "assembled with piecewise-linear functions on the 2^dim "
                      "sub-cells of each cell (FE_Q_iso_Q1(2), the Q2 element's "
                      "nodes and numbering): spectrally equivalent to the Q2 "
                      "block with a 3^dim- instead of a 5^dim-point stencil, "
                      "so the setup and each cycle are cheaper; FGMRES still "
                      "applies the Q2 matrix. Q1 sub-cells by component: "
                      "the same without the couplings between velocity "
                      "components, dim Laplace-like blocks, by Korn's "
                      "inequality still equivalent (ASPECT's choice). "
                      "Default: Q1 sub-cells in 2D, Q1 sub-cells by component "
                      "in 3D, the faster in each (doc/performance.md).");
    prm.declare_entry("Velocity preconditioner",
                      "auto",
                      Patterns::Selection("AMG|GMG|auto"),
                      "The velocity block's approximate inverse: AMG, GMG or "
                      "auto. AMG: Trilinos "
                      "ML on the AMG matrix (the AMG settings above). GMG: one "
                      "V-cycle of geometric multigrid on the globally coarsened "
                      "meshes, matrix-free Q2 operators with the system's "
                      "viscosity on the active mesh and cell means of it on "
                      "coarser ones, Chebyshev smoothing, CG with AMG on the "
                      "coarse mesh (doc/numerics.md); not with periodic "
                      "boundaries. Half the FGMRES iterations of AMG or fewer, "
                      "independent of the mesh; faster on large meshes (in "
                      "the transient default case 0.85 x the AMG's time at "
                      "3.8e4 Stokes dofs and 0.78 x at 1.5e5 in 2D, 0.55 x on "
                      "the adapted 3D mushroom), slower on small ones "
                      "(1.06 x at 9.5e3 in 2D; doc/performance.md). auto: "
                      "GMG from 2e4 Stokes dofs in 2D and 1e4 in 3D without "
                      "periodic boundaries, else AMG, chosen anew at each "
                      "mesh change (the log names it on the Mesh line and "
                      "when an adapted mesh changes it).");
    prm.declare_entry("GMG smoother degree",
                      "4",
                      Patterns::Integer(1),
                      "Velocity preconditioner = GMG: the degree of the "
                      "Chebyshev smoother (matrix-vector products per "
                      "smoothing) on each level, >= 1.");
    prm.declare_entry("Interface solve viscosity ratio",
                      "1000",
                      Patterns::Double(0),
                      "Where the viscosity jumps (a biofilm in water), the "
                      "velocity preconditioner adds an exact solve (a sparse LU "
                      "with the Direct solver) on the dofs along the edge of the "
                      "cells whose viscosity exceeds this multiple of the "
                      "water's (φ = 0), before and after each multigrid cycle: "
                      "multigrid alone loses its robustness at such jumps. It "
                      "makes 2D solves at ratios up to 1e6 converge, not yet 3D "
                      "ones (doc/numerics-stokes.md, \"Sharp viscosity "
                      "contrasts\"). 0: off.");
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
                      "Relative tolerance of the inner CG solves with the "
                      "1/η-weighted pressure mass matrix and the pressure "
                      "Laplacian (the Schur complement's stand-in), in (0, 1).");
    prm.declare_entry("Schur inner iterations",
                      "200",
                      Patterns::Integer(1),
                      "Iterations of each inner CG solve with the weighted "
                      "pressure mass matrix or the pressure Laplacian at most, "
                      ">= 1.");
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


  template <int dim>
  void
  StokesFlow<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stokes solver");
    const std::string name = prm.get("Method");
    method = (name == "auto"   ? Method::automatic :
              name == "direct" ? Method::direct :
              name == "thesis" ? Method::thesis :
                                 Method::block_preconditioned);
    convection = (prm.get("Momentum convection") == "Eulerian" ? Convection::eulerian :
                                                                  Convection::semi_lagrangian);
    direct_solver = "Amesos_" + std::string(prm.get("Direct solver") == "KLU" ? "Klu" : "Mumps");
    direct_available = Amesos().Query(direct_solver);
    check_input(method != Method::direct || direct_available,
                "Stokes solver/Direct solver = " + prm.get("Direct solver") +
                  ": this build's Trilinos has no " + direct_solver +
                  "; choose KLU (always built) or Method = block preconditioned");
    tolerance      = prm.get_double("Tolerance");
    predictor_tolerance = prm.get_double("Predictor tolerance");
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
    amg_smoother              = prm.get("AMG smoother");
    const std::string m = prm.get("AMG matrix");
    amg_matrix = (m == "Q2"           ? AMGMatrix::q2 :
                  m == "Q1 sub-cells" ? AMGMatrix::q1_subcells :
                                        AMGMatrix::q1_subcells_by_component);
    const std::string v = prm.get("Velocity preconditioner");
    velocity_preconditioner = (v == "GMG" ? VelocityPreconditioner::gmg :
                               v == "AMG" ? VelocityPreconditioner::amg :
                                            VelocityPreconditioner::automatic);
    gmg_smoother_degree       = prm.get_integer("GMG smoother degree");
    velocity_inner_tolerance  = prm.get_double("Velocity inner tolerance");
    interface_solve_ratio     = prm.get_double("Interface solve viscosity ratio");
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


  template <int dim>
  StokesFlow<dim>::StokesFlow(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const Mapping<dim> &                           mapping,
    const Parameters &                             parameters,
    const Model &                                  model,
    const BoundaryConditions<dim> &                boundary_conditions,
    const unsigned int                             order)
    : FieldType(triangulation, mapping)
    , triangulation(triangulation)
    , parameters(parameters)
    , model(model)
    , boundary_conditions(boundary_conditions)
    , mpi_communicator(triangulation.get_communicator())
    , fe(FE_Q<dim>(2), dim, *pressure_element<dim>(parameters.pressure_element), 1)
    , order(order)
  {
    if (order == 2)
      this->carry(older_solution);
  }


  template <int dim>
  StokesFlow<dim>::~StokesFlow() = default;


  template <int dim>
  void
  StokesFlow<dim>::setup_dofs()
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
    this->setup_vectors({owned.get_view(0, n_u), owned.get_view(n_u, n_u + n_p)},
                        {locally_relevant_dofs.get_view(0, n_u),
                         locally_relevant_dofs.get_view(n_u, n_u + n_p)});

    if (const Method method = choose_method(); !linear_solver || method != method_in_use)
      {
        if (linear_solver)
          earlier_preconditioner_builds += linear_solver->n_preconditioner_builds();
        linear_solver = StokesLinearSolver<dim>::create(method,
                                                        parameters,
                                                        model.viscosity(0.0),
                                                        boundary_conditions);
        method_in_use = method;
      }
    // The constrained dofs do not change in time, only their values do.
    make_constraints(0.0);
    linear_solver->reinit(dofs, constraints, owned_partitioning, relevant_partitioning);

    system_rhs.reinit(owned_partitioning, mpi_communicator);
    older_solution.reinit(owned_partitioning, relevant_partitioning, mpi_communicator);
    invalidate_matrix();
  }


  template <int dim>
  typename StokesFlow<dim>::Method
  StokesFlow<dim>::choose_method() const
  {
    if (parameters.method != Method::automatic)
      return parameters.method;
    // Measured (doc/performance.md, "Real scales"): at a ratio of 1e4 the
    // block preconditioner takes 109-158 iterations, at 1e6 it fails; MUMPS
    // takes 2.2 GB a rank at 6e5 dofs in 2D, 2 GB at 1.1e5 in 3D (233 s);
    // KLU, on one rank, 1.1 s a step at 3.8e4 in 2D, 19.5 s at 1.5e5.
    const bool                    mumps   = (parameters.direct_solver == "Amesos_Mumps");
    const types::global_dof_index largest = (dim == 2 ? (mumps ? 600000 : 40000) :
                                                        (mumps ? 30000 : 10000));
    return (parameters.direct_available && model.viscosity_ratio() >= 1e4 &&
            dofs.n_dofs() <= largest) ?
             Method::direct :
             Method::block_preconditioned;
  }


  template <int dim>
  std::string
  StokesFlow<dim>::solver_description() const
  {
    switch (method_in_use)
      {
        case Method::direct:
          return std::string("direct (") +
                 (parameters.direct_solver == "Amesos_Klu" ? "KLU" : "MUMPS") + ")";
        case Method::thesis:
          return "thesis (GMRES + ILU)";
        default:
          return "block preconditioned, velocity preconditioner " +
                 linear_solver->velocity_preconditioner();
      }
  }


  template <int dim>
  void
  StokesFlow<dim>::make_constraints(const double time)
  {
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    boundary_conditions.constrain_velocity(this->mapping(), dofs, time, constraints);

    // A factorisation needs a nonsingular matrix: unless a boundary fixes the
    // pressure level, pin the first pressure dof (Q1: a coarse-mesh vertex,
    // never hanging; P1disc: the mean of rank 0's first cell); the pressure
    // is shifted to mean zero after the solve. Before the periodic
    // constraints, which respect it (as they do boundary values).
    if (linear_solver->pins_pressure() && !boundary_conditions.fixes_pressure_level())
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


  template <int dim>
  void
  StokesFlow<dim>::invalidate_matrix()
  {
    matrix_is_current = false;
  }


  template <int dim>
  TrilinosWrappers::MPI::BlockVector
  StokesFlow<dim>::extrapolated_solution(const double offset) const
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


  template <int dim>
  unsigned int
  StokesFlow<dim>::solve(const bool predictor)
  {
    TrilinosWrappers::MPI::BlockVector distributed(owned_partitioning,
                                                   mpi_communicator);
    const double tolerance = (predictor && parameters.predictor_tolerance > 0 ?
                                std::max(parameters.tolerance, parameters.predictor_tolerance) :
                                parameters.tolerance);
    const unsigned int iterations =
      linear_solver->solve(system_rhs, current_solution, constraints, distributed, tolerance);
    constraints.distribute(distributed);
    AssertThrow(std::isfinite(distributed.l2_norm()),
                ExcMessage("the Stokes solution is not finite (NaN or inf)"));
    normalize_pressure(distributed);
    current_solution = distributed;
    return iterations;
  }


  template <int dim>
  void
  StokesFlow<dim>::normalize_pressure(TrilinosWrappers::MPI::BlockVector &distributed)
  {
    if (boundary_conditions.fixes_pressure_level())
      return;
    current_solution = distributed;
    const double mean_pressure =
      VectorTools::compute_mean_value(this->mapping(), dofs, QGauss<dim>(3), current_solution, dim);
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


  template <int dim>
  void
  StokesFlow<dim>::advance_time()
  {
    if (order == 2)
      {
        older_solution = old_solution;
        previous_step  = step_length;
      }
    FieldType::advance_time();
  }


  template <int dim>
  const TrilinosWrappers::MPI::BlockVector &
  StokesFlow<dim>::start_of_step_solution() const
  {
    return old_solution;
  }


  template <int dim>
  bool
  StokesFlow<dim>::check_initial_velocity()
  {
    unsigned int misses = 0;
    for (const types::global_dof_index i : dofs.locally_owned_dofs())
      if (constraints.is_inhomogeneously_constrained(i))
        misses = 1;
    impulsive_start = Utilities::MPI::max(misses, mpi_communicator) > 0;
    return impulsive_start;
  }


  template <int dim>
  bool
  StokesFlow<dim>::old_velocity_is_impulsive_start() const
  {
    return order == 2 && impulsive_start && previous_step == 0;
  }


  template <int dim>
  void
  StokesFlow<dim>::set_previous_time_step(const double time_step)
  {
    previous_step = time_step;
  }


  template <int dim>
  void
  StokesFlow<dim>::save_state(CheckpointValues &values) const
  {
    values["previous_time_step"] = previous_step;
  }


  template <int dim>
  void
  StokesFlow<dim>::load_state(const CheckpointValues &values)
  {
    previous_step = checkpoint_value(values, "previous_time_step");
  }


  template <int dim>
  types::global_dof_index
  StokesFlow<dim>::n_dofs() const
  {
    return dofs.n_dofs();
  }


  template <int dim>
  unsigned int
  StokesFlow<dim>::n_preconditioner_builds() const
  {
    return earlier_preconditioner_builds + linear_solver->n_preconditioner_builds();
  }


  template <int dim>
  double
  StokesFlow<dim>::viscosity_change_since_build() const
  {
    return linear_solver->viscosity_change_since_build();
  }


  VISCOFILM_INSTANTIATE(StokesFlow)
} // namespace viscofilm
