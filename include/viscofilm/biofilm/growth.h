// Biomass growth (doc/model.md, "Growth"): the biofilm φ gains what the
// substrate's Monod consumption makes of it, Y/ρX per unit of S consumed,
// and loses b φ by decay:
//   ∂φ/∂t + ∇·(u φ) = P,   P = μmax φ S/(K_S + S) − b φ,
// φ in [0, φmax]. The new biomass makes room by expanding the mixture,
// ∇·u = P/φmax (Klapper, Cogan & Keener's mixture models), so that the
// flow pushes the biofilm's surface out and φ itself stays below φmax;
// or, with Expansion = none, φ rises to φmax and the excess goes to the
// biofilm's fronts.
#ifndef viscofilm_growth_h
#define viscofilm_growth_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <array>

#include <viscofilm/biofilm/biofilm.h>
#include <viscofilm/core/reporter.h>
#include <viscofilm/geometry/boundary_conditions.h>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class Substrate;
  template <int dim>
  class VolumeFraction;

  template <int dim>
  class Growth : public Reporter<dim>
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      /// Needs the substrate (its kinetics) and, with Expansion = flow, a
      /// boundary the added volume can leave through.
      void
      parse_parameters(ParameterHandler &              prm,
                       const bool                      substrate_enabled,
                       const BoundaryConditions<dim> &boundary_conditions);

      bool   enabled = false;
      double decay_rate;              // b
      double maximum_volume_fraction; // φmax
      /// ∇·u = P/φmax in the Stokes problem.
      bool expansion = true;
    };

    /// The thickness is taken on @p biofilm's walls.
    Growth(const Parameters &    parameters,
           const Biofilm<dim> &  biofilm,
           const Substrate<dim> &substrate,
           VolumeFraction<dim> & volume_fraction);

    /// At the start of a step, from φ^n and S^n: the expansion rate P/φmax
    /// at φ's nodes for the step's Stokes problem and φ's transport
    /// (nothing with Expansion = none).
    void
    start_step();

    /// ∇·u at φ's nodes (ghosted), or nullptr with Expansion = none.
    const TrilinosWrappers::MPI::Vector *
    expansion() const;

    /// After an accepted step, whose substrate consumed with the
    /// transported φ: φ += k P (1 − φ/φmax) at φ's nodes (k P without
    /// expansion), P's growth scaled to the step's consumption, then φ
    /// clipped to [0, φmax] and ∫φ put to its balance at the biofilm's
    /// fronts: what the transport kept, less its k ∫φ^n ∇·u, + k Y/ρX × the
    /// substrate's consumption rate − k b ∫φ. Returns what could
    /// not be placed within [0, φmax] beyond round-off (a step too long for
    /// the fronts' room).
    double
    grow(const double time_step);

    /// statistics.csv: biomass_produced, biomass_decayed (∫ of the volume
    /// fraction since t = 0), biomass_relocated (what the last step put at
    /// the fronts, not where it grew), biomass_unplaced (what it could not
    /// put within [0, φmax]: a time step too long for the fronts' room); biofilm_thickness_mean, _max, _roughness
    /// (thickness()).
    void
    add_statistics(CsvFile &statistics, const double time) const override;
    void
    save_state(CheckpointValues &values) const override;
    void
    load_state(const CheckpointValues &values) override;

    /// The biofilm's thickness on the walls: each cell's ∫φ/φmax goes to
    /// the wall face nearest its centre, and L_f is face f's share per unit
    /// of its area (a column's height at φmax: the continuum's COMSTAT
    /// thickness). Returns the area-weighted mean of L_f, its largest, and
    /// the roughness Σ_f a_f |L_f − mean| / (mean Σ_f a_f) (0 without
    /// biofilm or walls).
    std::array<double, 3>
    thickness() const;

  private:
    /// μmax φ S/(K_S + S) at φ's nodes (owned values), φ clipped to [0,
    /// φmax], S interpolated from its Q1 nodes.
    TrilinosWrappers::MPI::Vector
    monod_growth() const;

    /// @p owned (φ's dofs) with ghosts.
    TrilinosWrappers::MPI::Vector
    ghosted(const TrilinosWrappers::MPI::Vector &owned) const;

    /// @p q1 (S's FE_Q(1) dofs, ghosted) interpolated onto φ's FE_Q(2)
    /// nodes (exact: Q1 ⊂ Q2), each value passed with φ there through @p f.
    template <typename Function>
    TrilinosWrappers::MPI::Vector
    on_phi_nodes(const TrilinosWrappers::MPI::Vector &q1, const Function &f) const;

    const Parameters &     parameters;
    const Biofilm<dim> &   biofilm;
    const Substrate<dim> & substrate;
    VolumeFraction<dim> &  volume_fraction;

    /// P/φmax at φ's nodes, ghosted (Expansion = flow).
    TrilinosWrappers::MPI::Vector expansion_rate;

    double produced = 0, decayed = 0; // since t = 0
    double relocated = 0; // put at the fronts by the last step
    double unplaced  = 0; // by the last step
  };
} // namespace viscofilm

#endif
