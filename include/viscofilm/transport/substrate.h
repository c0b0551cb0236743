// A dissolved substrate S (a carbon source) carried by the flow, diffusing
// faster in water than in the biofilm, and consumed by the biomass with
// Monod kinetics (doc/model.md, "Substrate"):
//   ∂S/∂t + ∇·(u S) = ∇·(D(φ) ∇S) − (μmax/Y) ρX φ S/(K_S + S),
//   D(φ) = D_w (1 − φ) + D_b φ, D_b = ratio × D_w.
// S stays within the range of its data (>= 0), and its balance (amount,
// inflow, outflow, consumption) holds to the linear solver's tolerance.
#ifndef viscofilm_substrate_h
#define viscofilm_substrate_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <viscofilm/core/field.h>
#include <viscofilm/geometry/boundary_conditions.h>

#include <map>
#include <optional>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class VolumeFraction;

  template <int dim>
  class Substrate : public Field<dim, TrilinosWrappers::MPI::Vector>
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm, const BoundaryConditions<dim> &boundary_conditions);

      bool   enabled = false;
      double diffusivity;               // D_w
      double biofilm_diffusivity_ratio; // D_b / D_w
      double maximum_growth_rate;       // μmax
      double half_saturation;           // K_S
      double yield;                     // Y
      double biomass_density;           // ρX
      double initial_value;
      /// Without ∂S/∂t: S in balance with the current flow and biomass.
      bool quasi_steady = false;
      /// S on these boundaries; no diffusive flux through the others.
      std::map<types::boundary_id, double> fixed_values;

      /// D(φ), φ clipped to [0, 1].
      double
      diffusivity_at(const double phi) const;
      /// (μmax/Y) ρX: the consumption of pure biomass per unit S/(K_S + S).
      double
      uptake_rate() const;
    };

    Substrate(const parallel::distributed::Triangulation<dim> &triangulation,
              const Mapping<dim> &                             mapping,
              const Parameters &                               parameters,
              const BoundaryConditions<dim> &                  boundary_conditions,
              const VolumeFraction<dim> &                      volume_fraction);

    void
    setup_dofs() override;

    /// S := Initial value, and the fixed values on their boundaries.
    void
    set_initial_values();

    /// S^{n+1} with u^{n+1} and φ^{n+1} by implicit Euler (or its steady
    /// state, Quasi-steady), the Monod term by Newton's method until S
    /// settles. Returns the Newton iterations.
    unsigned int
    advance(const StokesFlow<dim> &stokes, const double time_step);

    void
    restore_old() override;
    void
    advance_time() override;

    /// The kinetics (μmax, K_S, Y, ρX).
    const Parameters &
    kinetics() const;

    /// The last step's consumption rate, Σ_i c_i (c_i the Monod term of
    /// node i with its biomass ∫ψ_i φ).
    double
    consumption_rate() const;

    /// The dataset "substrate".
    void
    add_output(DataOut<dim> &data_out) override;
    /// statistics.csv: substrate_amount (Σ_i m_i S_i, m_i the lumped mass),
    /// _inflow, _outflow, _consumed, _remeshed (Totals), _inflow_rate (the last
    /// step's inflow rate through the fixed-value boundaries), _min, _max,
    /// _iterations.
    void
    add_statistics(CsvFile &statistics, const double time) const override;
    void
    save_state(CheckpointValues &values) const override;
    void
    load_state(const CheckpointValues &values) override;

    /// The amount before a mesh change, restored after it.
    void
    prepare_for_refinement() override;

  private:
    using FieldType = Field<dim, TrilinosWrappers::MPI::Vector>;
    using FieldType::constraints;
    using FieldType::current_solution;
    using FieldType::dofs;
    using FieldType::locally_relevant_dofs;
    using FieldType::old_solution;

    /// Rates of the last step: through the fixed-value boundaries (in),
    /// through the other boundaries (out), consumed by the biomass.
    struct Rates
    {
      double inflow   = 0;
      double outflow  = 0;
      double consumed = 0;
    };
    /// Rates × k summed since t = 0, and what mesh changes added (the
    /// amount on the new mesh less that on the old): amount(t) − amount(0)
    /// = inflow − outflow − consumed + remeshed (implicit Euler; with
    /// Quasi-steady each step's inflow = outflow + consumption instead).
    struct Totals : Rates
    {
      double remeshed = 0;
    };

    /// Assemble with the Monod term linearised about @p iterate (ghosted);
    /// with @p rates, instead, evaluate the step's balance at the current
    /// solution.
    void
    assemble(const StokesFlow<dim> &              stokes,
             const double                         time_step,
             const TrilinosWrappers::MPI::Vector &iterate,
             Rates *                              rates);

    /// Interpolation onto a new mesh keeps S >= 0 but not the lumped amount
    /// (coarsening drops nodes; the fixed values' share changes with the
    /// boundary's cells): the change goes to Totals::remeshed. Nothing on a
    /// loaded checkpoint's mesh, which is the mesh the values were on.
    void
    transferred(TrilinosWrappers::MPI::Vector &distributed) override;

    /// The lumped mass m_j of each dof, hanging nodes' shares condensed
    /// onto their masters (Σ_i m_i S_i = lumped_mass · S): of the mesh only,
    /// made by setup_dofs().
    void
    compute_lumped_mass();

    /// Σ_i m_i S_i.
    double
    amount() const;

    const Parameters &             parameters;
    const BoundaryConditions<dim> &boundary_conditions;
    const VolumeFraction<dim> &    volume_fraction;
    const MPI_Comm                 mpi_communicator;
    /// Q1: Taylor–Hood's u is divergence-free against exactly these
    /// functions (the pressure's), so the convection's rows sum to zero and
    /// S keeps the maximum principle besides its balance (Q1 on the Q2
    /// nodes' sub-cells rose 4 % above its data next to a biofilm); its
    /// hanging nodes take means (weights >= 0), which keep S >= 0.
    const FE_Q<dim>                fe;
    /// Hanging nodes and periodicity only: the balance's residual keeps the
    /// fixed values' rows.
    AffineConstraints<double>      hanging_node_constraints;

    TrilinosWrappers::MPI::Vector  lumped_mass;
    TrilinosWrappers::SparseMatrix system_matrix;
    TrilinosWrappers::MPI::Vector  system_rhs;

    /// The amount before a mesh change (none when a checkpoint is loaded).
    std::optional<double> amount_before_transfer;

    Rates        last_rates;
    Totals       totals, old_totals; // since t = 0; at t_n
    unsigned int last_iterations = 0;
  };
} // namespace viscofilm

#endif
