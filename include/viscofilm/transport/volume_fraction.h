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

      /// semi-Lagrangian or FCT: bounded (doc/numerics.md). thesis: GLS,
      /// and softening by the same Galerkin diffusion.
      bool bounded = true;
      /// FCT: Eulerian, algebraic flux correction with SSP-RK3 (bounded too).
      bool flux_corrected = false;
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
    /// and the φ-scaled diffusion D φ^n ∇φ; φ takes each boundary's Volume
    /// fraction where the flow enters. Bounded: semi-Lagrangian along the
    /// feet of φ's nodes (traced by @p feet with u^{n+1}; @p order 2: with
    /// (u^n + u^{n+1})/2, the midpoint rule), clipped, then the bounded
    /// diffusion step and the mass fixer. FCT: SSP-RK3 stages from u^n to
    /// u^{n+1} (either order; @p feet unused), then the bounded diffusion
    /// step. Thesis: GLS-stabilised Galerkin.
    /// @p estimate_error (order 2, bounded): also the first-order feet (FCT:
    /// the stages with u^{n+1}), for error_estimate(). Returns the linear
    /// solver's iteration count.
    unsigned int
    advance(const StokesFlow<dim> &stokes,
            DepartureFeet<dim> & feet,
            const double        diffusion,
            const double        time_step,
            const unsigned int  order          = 1,
            const bool          estimate_error = false);

    /// After advance() with estimate_error: max over the nodes of |φ₂ − φ₁|,
    /// the advected φ of the second-order feet against that of the
    /// first-order ones (FCT: of the stages with u interpolated against
    /// those with u^{n+1}; φ is a fraction: the absolute difference is
    /// dimensionless), the local error of a first-order step. 0 otherwise.
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
    /// boundary exchange since t = 0, below), _min, _max and, with FCT,
    /// _substeps.
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

    /// Smallest and largest nodal value (@p free_nodes: of the nodes no
    /// constraint sets, which a hanging node's interpolant can overshoot).
    std::pair<double, double>
    range(const bool free_nodes = false) const;

    /// FCT: the sub-steps the last advance() took (its step cut to the
    /// explicit scheme's positivity limit); 1 otherwise.
    unsigned int
    substeps() const;

  private:
    using FieldType = Field<dim, TrilinosWrappers::MPI::Vector>;
    using FieldType::constraints;
    using FieldType::current_solution;
    using FieldType::dofs;
    using FieldType::locally_relevant_dofs;
    using FieldType::old_solution;

    /// Q2 interpolation onto children overshoots at fronts: clip to the
    /// range before the mesh change, and restore the mass within it.
    void
    transferred(TrilinosWrappers::MPI::Vector &distributed) override;

    /// The thesis' step, implicit; without @p stokes: pure φ-scaled diffusion.
    unsigned int
    gls_step(const StokesFlow<dim> *stokes, const double diffusion, const double time_step);

    /// system_matrix φ = system_rhs by GMRES, then the constraints.
    unsigned int
    solve();

    /// The bounded scheme's advection: @p advected := φ^n at the feet of the
    /// nodes along @p velocity (on @p stokes_dofs), clipped to the nodal
    /// range of the cell holding the foot, which goes to @p lower and
    /// @p upper; owned values, constraints distributed.
    void
    semi_lagrangian_step(const DoFHandler<dim> &                     stokes_dofs,
                         const TrilinosWrappers::MPI::BlockVector &velocity,
                         DepartureFeet<dim> &                      feet,
                         const double                              time_step,
                         TrilinosWrappers::MPI::Vector &           advected,
                         TrilinosWrappers::MPI::Vector &           lower,
                         TrilinosWrappers::MPI::Vector &           upper) const;

    /// One implicit Euler step of ∂φ/∂t = ∇·(D φ^n ∇φ) with lumped mass and
    /// the stiffness of the Q1 sub-cells of the Q2 nodes, discretely
    /// upwinded: an M-matrix on a conforming mesh, so φ stays in the range
    /// of φ^n and the constraints' values. (Condensing hanging nodes, weights
    /// 3/8, 3/4, −1/8, can add positive couplings between their masters; the
    /// adapted tests stay in range to 3e-8.) Returns the iteration count.
    unsigned int
    bounded_diffusion_step(const double diffusion, const double time_step);

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

    /// Add λ c_i, c_i = (φ_i − l_i)(u_i − φ_i)/(u_i − l_i), to the free
    /// nodes so that ∫φ = @p mass; |λ| <= 1 keeps φ_i in [l_i, u_i] (l =
    /// @p lower, u = @p upper), so mass goes only where φ is between its
    /// bounds: at fronts. (With |λ| = 1 some mass may still be missing.)
    void
    restore_mass(const double                         mass,
                 const TrilinosWrappers::MPI::Vector &lower,
                 const TrilinosWrappers::MPI::Vector &upper);

    /// restore_mass() with the same bounds [@p low, @p high] at every node.
    void
    restore_mass(const double mass, const double low, const double high);

    /// max over all nodes of |@p a_i − @p b_i| (owned values, all ranks).
    double
    max_difference(const TrilinosWrappers::MPI::Vector &a,
                   const TrilinosWrappers::MPI::Vector &b) const;

    /// ∫_∂Ω φ u·n ds with the velocity @p velocity on @p stokes_dofs, and
    /// its outflow and inflow parts.
    Exchange
    boundary_flux(const DoFHandler<dim> &                     stokes_dofs,
                  const TrilinosWrappers::MPI::BlockVector &velocity) const;

    /// The flux-corrected transport's operator at one velocity: the Galerkin
    /// convection k_ij = −∫ψ_i u·∇ψ_j of the owned free nodes' rows (and
    /// k_ji), the lumped mass, and the boundary's lumped inflow and outflow.
    struct TransportOperator;

    /// FCT: φ^{n+1} from φ^n by SSP-RK3 with the velocity interpolated
    /// linearly between u^n and u^{n+1} at each stage, every stage limited.
    /// @p estimate_error: also the step with u^{n+1} in every stage (first
    /// order), for error_estimate(). Returns the step's outflow − inflow of
    /// ∫φ.
    double
    flux_corrected_step(const StokesFlow<dim> &stokes,
                        const double             time_step,
                        const bool               estimate_error);

    /// One limited forward Euler stage: @p result := φ + k M_L^{-1}(low-order
    /// rate + limited antidiffusion) from the ghosted @p phi with the operator
    /// @p theta of the way from u^n to u^{n+1}; @p flux gets its boundary
    /// rates (outflow, inflow) × @p weight.
    void
    flux_corrected_stage(const TransportOperator &      op,
                         const double                   theta,
                         const double                   time_step,
                         const TrilinosWrappers::MPI::Vector &phi,
                         TrilinosWrappers::MPI::Vector &result,
                         const double                   weight,
                         Exchange &                     flux) const;

    /// The value φ takes where the flow enters through boundary @p id.
    double
    inflow_value(const types::boundary_id id) const;

    /// Hanging nodes, and φ = boundary value on faces where the flow enters
    /// (their mean u·n below −1e-8 max|u|, so that round-off on a wall is
    /// no inflow).
    void
    make_constraints(const StokesFlow<dim> *stokes);

    const Parameters &        parameters;
    const BoundaryConditions<dim> &boundary_conditions;
    const MPI_Comm            mpi_communicator;
    const std::string         name;
    const bool                inflow_from_boundaries;
    const FE_Q<dim>             fe;

    /// Range and mass before a mesh change (bounded scheme), restored after.
    std::optional<std::array<double, 3>> before_transfer;

    TrilinosWrappers::SparseMatrix system_matrix;
    /// The locally relevant dofs and every column of system_matrix's owned
    /// rows, where FCT reads φ: on an adapted mesh a master of a hanging
    /// node couples to the hanging node's cell, which need not be a ghost of
    /// the master's owner.
    IndexSet matrix_columns;
    TrilinosWrappers::MPI::Vector  system_rhs;
    double                        last_error_estimate = 0;
    unsigned int                  last_substeps       = 1;
    Exchange exchange, old_exchange; // since t = 0; at t_n, for restore_old()
  };
} // namespace viscofilm

#endif
