// The biofilm volume fraction φ on its own FE_Q(2) DoFHandler (MODEL.md §2).
#ifndef viscofilm_volume_fraction_h
#define viscofilm_volume_fraction_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/data_out.h>

#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/core/dimension.h>
#include <viscofilm/core/field.h>

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class DepartureFeet;
  template <int dim>
  class TransportScheme;

  template <int dim>
  class VolumeFraction : public Field<dim, TrilinosWrappers::MPI::Vector>
  {
  public:
    /// The transport scheme and the GLS stabilisation of the thesis' one
    /// (thesis eq. 3.47-3.50).
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// One TransportScheme each (transport_scheme.h, doc/numerics-transport.md).
      enum class Scheme
      {
        semi_lagrangian,
        flux_corrected,
        thesis
      };
      Scheme scheme = Scheme::semi_lagrangian;
      /// constant: τ = GLS parameter (the thesis: 1). standard: τ = GLS
      /// parameter × (4/k² + (2|u|/h)²)^(-1/2).
      bool   standard_tau  = false;
      double gls_parameter = 1.0;
    };

    /// What the boundary carries: of a step, ∫_∂Ω φ u·n ds (net) and its
    /// parts through faces where the flow leaves (outflow, u·n > 0) and
    /// enters (inflow, as a positive number), periodic faces in neither;
    /// summed over the accepted steps (× k), outflow and inflow since t = 0.
    struct Exchange
    {
      double net     = 0;
      double outflow = 0;
      double inflow  = 0;
    };

    /// @p name: the field's name in the snapshots. @p inflow_from_boundaries:
    /// φ takes each boundary's Volume fraction where the flow enters; false:
    /// 0 there (a second transported fraction, the detached biofilm, which
    /// no boundary brings in).
    VolumeFraction(const parallel::distributed::Triangulation<dim> &triangulation,
                   const Mapping<dim> &                           mapping,
                   const Parameters &                             parameters,
                   const BoundaryConditions<dim> &                boundary_conditions,
                   const std::string &name                   = "volume_fraction",
                   const bool         inflow_from_boundaries = true);
    ~VolumeFraction() override;

    void
    setup_dofs() override;

    /// φ := the interpolant of @p initial at the Q2 nodes.
    void
    interpolate(const Function<dim> &initial);

    /// φ := @p distributed (owned values, no ghosts), with the constraints
    /// distributed (and, bounded, the hanging nodes kept in range): a change
    /// made outside the transport (the detachment's release).
    void
    set(TrilinosWrappers::MPI::Vector &distributed);

    /// MODEL.md §3 step 3: φ^{n+1} from φ^n with the velocity of @p stokes
    /// and the φ-scaled diffusion D φ^n ∇φ, by the scheme's
    /// TransportScheme::advance(). Returns the linear solver's iteration
    /// count.
    unsigned int
    advance(const StokesFlow<dim> &stokes,
            DepartureFeet<dim> &   feet,
            const double           diffusion,
            const double           time_step,
            const unsigned int     order          = 1,
            const bool             estimate_error = false);

    /// After advance() with estimate_error: the scheme's local error
    /// estimate of a first-order step (TransportScheme::error_estimate()).
    double
    error_estimate() const;

    /// φ := φ^n and the boundary's totals with it: a rejected step, or the
    /// next iterate of Order 2's Picard loop.
    void
    restore_old() override;

    /// φ^n := φ and the boundary's totals with it.
    void
    advance_time() override;

    /// Eq. 2.50: @p n_steps implicit Euler steps of ∂φ/∂t = ∇·(D φ ∇φ).
    void
    soften(const double diffusion, const unsigned int n_steps, const double time_step);

    /// Add the field (named as constructed) to @p data_out.
    void
    add_output(DataOut<dim> &data_out) override;

    /// statistics.csv: volume_fraction_integral, _outflow, _inflow (the
    /// boundary exchange since t = 0, below), _min, _max and the scheme's
    /// own columns.
    void
    add_statistics(CsvFile &statistics, const double time) const override;

    /// The boundary exchange's totals.
    void
    save_state(CheckpointValues &values) const override;
    void
    load_state(const CheckpointValues &values) override;

    /// Bounded: φ's range and mass before a mesh change, restored after it.
    void
    prepare_for_refinement() override;

    /// ∫_Ω φ dx.
    double
    integral() const;

    /// ∫_Ω of @p values (ghosted, on these dofs), times @p weight (the
    /// same) if given.
    double
    integral_of(const TrilinosWrappers::MPI::Vector &values,
                const TrilinosWrappers::MPI::Vector *weight = nullptr) const;

    /// What the last transport step's mass fixer could not put back (the
    /// bounded schemes' ∫φ balance misses it): 0 to round-off unless the
    /// step is too long for the room at the fronts.
    double
    last_mass_defect() const;

    /// Smallest and largest nodal value (@p free_nodes: of the nodes no
    /// constraint sets, which a hanging node's interpolant can overshoot).
    std::pair<double, double>
    range(const bool free_nodes = false) const;

    /// The flow's divergence ∇·u = @p rate (ghosted, on these dofs; nullptr:
    /// none) for the coming step, from the biomass' growth: the advective
    /// transport gains ∫φ ∇·u, which the bounded schemes' mass balance
    /// adds. Stored with ∫φ^n rate, taken now.
    void
    set_expansion(const TrilinosWrappers::MPI::Vector *rate);

    /// ∫φ^n ∇·u of set_expansion() (0 without).
    double
    expansion_integral() const;

    /** @name The schemes' toolbox (transport_scheme.h) */
    /// @{

    /// Hanging nodes, periodicity and, with @p stokes, φ = boundary value on
    /// faces where the flow enters (their mean u·n below −1e-8 max|u|, so
    /// that round-off on a wall is no inflow).
    void
    make_constraints(const StokesFlow<dim> *stokes);

    /// The value φ takes where the flow enters through boundary @p id.
    double
    inflow_value(const types::boundary_id id) const;

    /// ∫_∂Ω φ u·n ds with the velocity @p velocity on @p stokes_dofs, and
    /// its outflow and inflow parts.
    Exchange
    boundary_flux(const DoFHandler<dim> &                    stokes_dofs,
                  const TrilinosWrappers::MPI::BlockVector &velocity) const;

    /// Add a step's exchange (rates × @p time_step) to the totals since t = 0.
    void
    add_exchange(const Exchange &rates, const double time_step);

    /// One implicit Euler step of ∂φ/∂t = ∇·(D φ^n ∇φ) with lumped mass and
    /// the stiffness of the Q1 sub-cells of the Q2 nodes, discretely
    /// upwinded: an M-matrix on a conforming mesh, so φ stays in the range
    /// of φ^n and the constraints' values. (Condensing hanging nodes, weights
    /// 3/8, 3/4, −1/8, can add positive couplings between their masters; the
    /// adapted tests stay in range to 3e-8.) Returns the iteration count.
    unsigned int
    bounded_diffusion_step(const double diffusion, const double time_step);

    /// Add λ c_i, c_i = (φ_i − l_i)(u_i − φ_i)/(u_i − l_i), to the free
    /// nodes so that ∫φ = @p mass; |λ| <= 1 keeps φ_i in [l_i, u_i] (l =
    /// @p lower, u = @p upper), so mass goes only where φ is between its
    /// bounds: at fronts. (With |λ| = 1 some mass may still be missing.)
    /// Returns what is still missing (mass − ∫φ after).
    double
    restore_mass(const double                         mass,
                 const TrilinosWrappers::MPI::Vector &lower,
                 const TrilinosWrappers::MPI::Vector &upper);

    /// restore_mass() with the same bounds [@p low, @p high] at every node.
    double
    restore_mass(const double mass, const double low, const double high);

    /// system_matrix φ = system_rhs by GMRES (ILU; AMG once ILU has
    /// stalled), then the constraints.
    unsigned int
    solve();

    /// max over all nodes of |@p a_i − @p b_i| (owned values, all ranks).
    double
    max_difference(const TrilinosWrappers::MPI::Vector &a,
                   const TrilinosWrappers::MPI::Vector &b) const;

    /// @}

  private:
    using FieldType = Field<dim, TrilinosWrappers::MPI::Vector>;
    using FieldType::constraints;
    using FieldType::current_solution;
    using FieldType::dofs;
    using FieldType::locally_relevant_dofs;
    using FieldType::old_solution;
    /// The schemes read and write φ's vectors, constraints and matrix.
    friend class TransportScheme<dim>;

    /// Q2 interpolation onto children overshoots at fronts: clip to the
    /// range before the mesh change, and restore the mass within it.
    void
    transferred(TrilinosWrappers::MPI::Vector &distributed) override;

    /// Hanging nodes take the coarse edge's Q2 interpolant, whose weights
    /// (3/8, 3/4, −1/8) leave the data's range at a front: shift each such
    /// node's heaviest master (the coarse edge's midpoint) just enough to
    /// bring it back, within the range. The range is [min @p lower, max
    /// @p upper] over the free nodes. @p distributed: owned values with the
    /// constraints distributed; they are distributed again.
    void
    bound_hanging_nodes(TrilinosWrappers::MPI::Vector &      distributed,
                        const TrilinosWrappers::MPI::Vector &lower,
                        const TrilinosWrappers::MPI::Vector &upper) const;

    const BoundaryConditions<dim> &boundary_conditions;
    const MPI_Comm                 mpi_communicator;
    const std::string              name;
    const bool                     inflow_from_boundaries;
    const FE_Q<dim>                fe;
    /// After fe: the scheme reads it.
    const std::unique_ptr<TransportScheme<dim>> scheme;

    /// Range and mass before a mesh change (bounded scheme), restored after.
    std::optional<std::array<double, 3>> before_transfer;

    TrilinosWrappers::SparseMatrix system_matrix;
    /// The locally relevant dofs and every column of system_matrix's owned
    /// rows, where FCT reads φ: on an adapted mesh a master of a hanging
    /// node couples to the hanging node's cell, which need not be a ghost of
    /// the master's owner.
    IndexSet                      matrix_columns;
    TrilinosWrappers::MPI::Vector system_rhs;
    /// Whether ILU stalled in a solve: AMG from then on.
    bool     diffusion_dominated = false;

    double expansion = 0; // ∫φ^n ∇·u
    /// What the last transport step's mass fixer could not restore (a step
    /// too long for the room at the fronts).
    double mass_defect = 0;
    Exchange exchange, old_exchange; // since t = 0; at t_n, for restore_old()
  };
} // namespace viscofilm

#endif
