// Variable-viscosity Stokes with Taylor–Hood elements and a block-
// preconditioned Krylov solver (MODEL.md §3 step 2a).
#ifndef viscofilm_stokes_h
#define viscofilm_stokes_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/core/field.h>
#include <viscofilm/material/model.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesLinearSolver;
  template <int dim>
  class StokesViscosity;
  template <int dim>
  class ElasticStress;

  /// The Stokes solve of a time step: its dofs and solutions, the assembly
  /// (stokes_assembly.cc), a linear-solver strategy per Method
  /// (stokes_linear_solver.h) and diagnostics (stokes_diagnostics.cc).
  template <int dim>
  class StokesFlow : public Field<dim, TrilinosWrappers::MPI::BlockVector>
  {
  public:
    enum class Method
    {
      automatic,            // direct where it is needed and affordable, else block
      block_preconditioned, // FGMRES + block triangular preconditioner
      direct,               // a sparse LU of the whole system (Direct solver)
      thesis                // the thesis' way: GMRES + ILU on the whole system
    };

    /// How η(φ) enters each cell.
    enum class Averaging
    {
      none,       // η at every quadrature point
      arithmetic, // cell mean of η
      harmonic,   // cell harmonic mean of η
      geometric   // cell geometric mean of η
    };

    /// The matrix of the velocity block's AMG: the block itself, or the same
    /// operator with Q1 on the 2^dim sub-cells of each cell (FE_Q_iso_Q1(2),
    /// the same dofs): sparser and spectrally equivalent; by component:
    /// without the couplings between velocity components (Korn).
    enum class AMGMatrix
    {
      q2,
      q1_subcells,
      q1_subcells_by_component
    };

    /// The velocity block's approximate inverse in the block preconditioner.
    enum class VelocityPreconditioner
    {
      amg,      // Trilinos ML on the AMG matrix
      gmg,      // geometric multigrid, matrix-free (stokes_velocity_multigrid.h)
      automatic // GMG on large meshes without periodic boundaries, else AMG
    };

    /// The pressure space of the Taylor–Hood pair.
    enum class PressureElement
    {
      continuous,   // Q2 × Q1
      discontinuous // Q2 × P1disc: each cell conserves mass
    };

    /// The discretisation of ρ Du/Dt (Momentum convection).
    enum class Convection
    {
      semi_lagrangian, // differences along the departure feet
      eulerian         // ∂u/∂t by differences at the point, (u*·∇)u implicit
    };

    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      Method          method         = Method::automatic;
      Convection      convection     = Convection::semi_lagrangian;
      /// The Amesos package of Method = direct.
      std::string     direct_solver  = "Amesos_Mumps";
      bool            direct_available = true; // this Trilinos has direct_solver
      double          tolerance      = 1e-8;
      double          predictor_tolerance = 0; // 0: tolerance
      unsigned int    max_iterations = 1000;
      Averaging       averaging      = Averaging::none;
      PressureElement pressure_element = PressureElement::continuous;
      /// Put the update's elastic viscosity (Model::elastic_viscosity) into
      /// the matrix and its explicit twin into the right-hand side, so that
      /// the Picard loop contracts where ηp k/(λ + k) exceeds ηs.
      bool implicit_elastic_viscosity = false;

      /// The block preconditioner's parts (Method = block preconditioned).
      unsigned int krylov_basis        = 100;  // FGMRES restart length
      unsigned int cheap_iterations    = 100;  // with one AMG application
      bool         amg_w_cycle         = false;
      unsigned int amg_cycles          = 1;
      unsigned int amg_smoother_sweeps = 2;
      double       amg_aggregation_threshold = 0.02;
      /// ML's smoother: "Chebyshev" or "symmetric Gauss-Seidel".
      std::string  amg_smoother = "Chebyshev";
      /// The matrix ML builds the velocity block's hierarchy from.
      AMGMatrix    amg_matrix = dim == 2 ? AMGMatrix::q1_subcells :
                                             AMGMatrix::q1_subcells_by_component;
      VelocityPreconditioner velocity_preconditioner = VelocityPreconditioner::automatic;
      unsigned int gmg_smoother_degree = 4; // Chebyshev degree on each level
      double       velocity_inner_tolerance  = 1e-2; // expensive iterations
      /// The interface solve on the edge of the cells with η above this
      /// multiple of the water's; 0: off.
      double       interface_solve_ratio     = 1000;
      unsigned int velocity_inner_iterations = 1000;
      double       schur_inner_tolerance     = 1e-3;
      unsigned int schur_inner_iterations    = 200;
      /// Keep the velocity block's AMG across matrix assemblies (one per
      /// time step) until the viscosity has moved by more than
      /// rebuild_viscosity_change (volume mean of |ln(η/η_built)|) or the
      /// first solve with a new matrix needs more than
      /// rebuild_iteration_growth times the outer iterations of the first
      /// solve after the last build.
      bool   reuse_preconditioner     = true;
      double rebuild_viscosity_change = 0.1;
      double rebuild_iteration_growth = 1.5;
    };

    /// What the momentum equation needs besides the unknowns.
    struct Coefficients
    {
      double                          time;
      double                          time_step;
      const DoFHandler<dim> *           volume_fraction_dof_handler;
      const TrilinosWrappers::MPI::Vector *volume_fraction;
      const ParsedExpression<dim> *     body_force; // at time
      /// τ for the term −(s(φ) τ, ∇v) on the right-hand side.
      const ElasticStress<dim> *elastic_stress;
      /// ∇·u on φ's dofs where growth expands the mixture (Growth); nullptr:
      /// ∇·u = 0.
      const TrilinosWrappers::MPI::Vector *expansion;
    };

    /// @p order: Time stepping/Order (2: BDF2 for Res ∂u/∂t, and u^{n-1}
    /// is kept for it and for the extrapolated velocity of the feet).
    StokesFlow(const parallel::distributed::Triangulation<dim> &triangulation,
                 const Mapping<dim> &                           mapping,
                 const Parameters &                             parameters,
                 const Model &                                  model,
                 const BoundaryConditions<dim> &                boundary_conditions,
                 const unsigned int                             order);
    ~StokesFlow();

    /// Distribute dofs, build sparsity patterns, zero the solution.
    void
    setup_dofs() override;

    /// The viscosity or time step changed: the matrix and the preconditioner
    /// are rebuilt at the next assemble()/solve().
    void
    invalidate_matrix();

    /// The quadrature of the assembly (τ is asked for at its points).
    Quadrature<dim>
    quadrature() const;

    /// u^n at the departure feet of the quadrature points, for the term
    /// (Res/k)(u^n(y), v) of MODEL.md §3 step 2a, and with Order = 2 u^{n-1}
    /// at the feet over two steps (BDF2). Skipped when Res = 0. Records
    /// @p time_step as the length k_n of the step.
    void
    trace_back(DepartureFeet<dim> &feet, const double time_step);

    /// Res Du/Dt of the last step's momentum equation at the points of
    /// @p fe_values (this field's, with quadrature(), on the
    /// @p owned_index-th owned cell in the order of the active cells), after
    /// the step's solve and before advance_time(): the inertia of the
    /// consistent forces' residual. Zero when Res = 0.
    void
    inertia(const FEValues<dim> &         fe_values,
            const std::size_t             owned_index,
            std::vector<Tensor<1, dim>> &result) const;

    /// The solution at t_n + @p offset extrapolated linearly from u^{n-1} and
    /// u^n, u^n while there is no u^{n-1} (Order = 1, the first step); the
    /// velocity of second-order feet at the middle of their interval.
    /// Ghosted.
    TrilinosWrappers::MPI::BlockVector
    extrapolated_solution(const double offset) const;

    /// Assemble the right-hand side (and the matrix if invalidated): a
    /// WorkStream over the owned cells, on MultithreadInfo::n_threads()
    /// threads (viscofilm --threads); the same sums in the same order on any
    /// number of threads.
    void
    assemble(const Coefficients &coefficients);

    /// Solve (a @p predictor: to Predictor tolerance); returns the number
    /// of outer Krylov iterations (0 if direct). Throws with the residual if
    /// the solver does not converge.
    unsigned int
    solve(bool predictor = false);

    /// u^n := current solution (Order = 2: u^{n-1} := u^n before), before
    /// the next time step.
    void
    advance_time() override;

    /// Res > 0, before the first step (after setup_dofs(), which leaves the
    /// constraints at t = 0): whether the initial condition u = 0 misses the
    /// velocity boundary data at t = 0, an impulsive start.
    bool
    check_initial_velocity();

    /// Order 2: whether u^n is the u = 0 of an impulsive start (the first
    /// step's), which the flow leaves within a time of order Res.
    bool
    old_velocity_is_impulsive_start() const;

    /// Set k_{n-1} = t_n − t_{n-1} (0: there is no u^{n-1}).
    void
    set_previous_time_step(const double time_step);

    types::global_dof_index
    n_dofs() const;

    /// max |u| over the Q2 nodes.
    double
    max_velocity() const;

    /// max over the cells K of |∫_K ∇·u| / |K|: zero up to the solver
    /// tolerance with the discontinuous pressure, which conserves mass in
    /// each cell; not so with the continuous one.
    double
    max_cell_divergence() const;

    /// Kelly's indicator of the velocity per active cell (zero on cells not
    /// owned here): (h/24 Σ_faces ∫ |[∂u/∂n]|²)^½, the jump of the velocity
    /// gradient across the faces, of the size of the velocity error there.
    Vector<float>
    velocity_error_indicator() const;

    /// Add velocity, pressure and the derived divergence (∇·u), vorticity
    /// (∂v/∂x − ∂u/∂y) and inertia (|u·∇u|) to @p data_out.
    void
    add_output(DataOut<dim> &data_out) override;

    /// statistics.csv: stokes_preconditioner_builds,
    /// stokes_viscosity_change, max_velocity, max_cell_divergence.
    void
    add_statistics(CsvFile &statistics, const double time) const override;

    /// k_{n-1} (previous_time_step).
    void
    save_state(CheckpointValues &values) const override;
    void
    load_state(const CheckpointValues &values) override;

    /// ‖u − u_prev‖_L2 / ‖u‖_L2 from the velocity of @p previous (ghosted)
    /// to the current one: the Picard criterion on u.
    double
    velocity_relative_change(const TrilinosWrappers::MPI::BlockVector &previous) const;

    /// (u^n, p^n) with ghost values: the solution at the start of the step
    /// (before advance_time(), solution() is the step's end).
    const TrilinosWrappers::MPI::BlockVector &
    start_of_step_solution() const;

    /// How often the velocity AMG was built so far (Preconditioner/Reuse).
    unsigned int
    n_preconditioner_builds() const;

    /// The linear solver on this mesh, for the run's log: "direct (MUMPS)",
    /// "block preconditioned, velocity preconditioner AMG", ...
    std::string
    solver_description() const;

    /// The rebuild criterion's measure at the last matrix assembly: the
    /// volume mean of |ln(η/η_built)| against the AMG in use until then (0
    /// if there was none, or without Reuse).
    double
    viscosity_change_since_build() const;

    /// The cell's viscosities replaced by one average (Viscosity
    /// averaging; none leaves them as they are).
    static void
    average_viscosity(const Averaging            averaging,
                      const std::vector<double> &JxW,
                      std::vector<double> &      viscosity);

  private:
    using FieldType = Field<dim, TrilinosWrappers::MPI::BlockVector>;
    using FieldType::constraints;
    using FieldType::current_solution;
    using FieldType::dofs;
    using FieldType::locally_relevant_dofs;
    using FieldType::old_solution;
    using FieldType::owned_partitioning;
    using FieldType::relevant_partitioning;

    void
    make_constraints(const double time);
    /// Stokes solver/Method, or for auto what it picks on this mesh.
    Method
    choose_method() const;
    /// Whether Res Du/Dt is BDF2 in the current step (u^{n-1} at hand).
    bool
    inertia_bdf2() const;
    /// The weights (a, b, c) of Res (a u − b u^n + c u^{n-1})/… for a step
    /// of length @p k: (Res/k)(1, 1, 0), or BDF2's with ω = k/k_{n-1}.
    std::array<double, 3>
    inertia_weights(const double k) const;
    /// The convecting velocity of the Eulerian step at t_{n+1} from u^n and
    /// u^{n-1} at a point: u* = (1 + θ) u^n − θ u^{n-1}, θ = k/k_{n-1} with
    /// BDF2, else 0 (u^n).
    Tensor<1, dim>
    convecting_velocity(const Tensor<1, dim> &old_velocity,
                        const Tensor<1, dim> &older_velocity) const;
    /// Shift the pressure to mean zero unless an outflow boundary fixes it.
    void
    normalize_pressure(TrilinosWrappers::MPI::BlockVector &distributed);

    const parallel::distributed::Triangulation<dim> &triangulation;
    const Parameters &                             parameters;
    const Model &                                  model;
    const BoundaryConditions<dim> &                boundary_conditions;
    const MPI_Comm                                 mpi_communicator;

    const FESystem<dim> fe;

    TrilinosWrappers::MPI::BlockVector system_rhs;
    TrilinosWrappers::MPI::BlockVector older_solution;   // ghosted, u^{n-1} (Order = 2)
    const unsigned int                 order;
    double                             step_length   = 0; // k_n, from trace_back()
    double                             previous_step = 0; // k_{n-1}; 0: no u^{n-1}
    bool                               impulsive_start = false; // check_initial_velocity()
    /// Model::elastic_viscosity at each owned cell's quadrature points, from
    /// the assembly that built the matrix (Implicit elastic viscosity).
    std::vector<double> elastic_viscosity_cache;
    std::vector<Tensor<1, dim>>          old_velocity_at_feet; // per owned cell and q
    std::vector<Tensor<1, dim>>        previous_velocity_at_feet; // u^{n-1}, BDF2

    bool matrix_is_current = false;

    /// The matrices, preconditioners and solver (Method).
    std::unique_ptr<StokesLinearSolver<dim>> linear_solver; // from setup_dofs()
    Method                                   method_in_use = Method::automatic;
    /// The velocity AMG builds of the linear solvers Method = auto replaced.
    unsigned int earlier_preconditioner_builds = 0;
    /// η at the strategy's own points (StokesViscosity), from the model, the
    /// φ and the averaging of the last matrix assembly.
    std::unique_ptr<StokesViscosity<dim>> assembled_viscosity;
  };
} // namespace viscofilm

#endif
