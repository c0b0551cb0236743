// Material model: the rheology's formulas in one place (MODEL.md §2). Every
// component asks Model for the clipped φ, the solvent viscosity, the
// conformation ↔ stress map, the relaxation coefficients of the update and
// the prefactor of τ in the momentum equation; nobody else writes them.
//
// General form (doc/numerics.md, "Rheology"): along particle paths
//   w(φ) L_Φ(c) + α(φ) c = β(φ) I,   τ = G(φ) (c − c_rest I),
// and the flow sees ∇·(s(φ) τ). The thesis mixture and the per-phase
// Oldroyd-B/Johnson–Segalman fluids are two choices of w, α, β, G, c_rest, s.
#ifndef viscofilm_model_h
#define viscofilm_model_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <viscofilm/core/dimension.h>

#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  class Model
  {
  public:
    enum class Units
    {
      dimensionless,
      SI
    };
    enum class Rheology
    {
      thesis_mixture,
      phases
    };
    /// How `phases` mixes the two phases' elasticity in φ: ηp and λ linear
    /// (G = ηp/λ the biofilm's at any φ > 0 next to a Newtonian water), G
    /// and λ linear (G → 0 with φ there), or G linear and λ geometric (a
    /// dilute fringe also relaxes as fast as the water's λ).
    enum class Mixture
    {
      viscosity,
      modulus,
      geometric
    };

    /// One phase (water or biofilm): solvent viscosity ηs, polymer
    /// viscosity ηp (0: Newtonian) and relaxation time λ, in the input's
    /// units.
    struct Phase
    {
      double solvent_viscosity = 1;
      double polymer_viscosity = 0;
      double relaxation_time   = 0;
    };

    /// The coefficients of the update c^{n+1} = (w E c(foot) Eᵀ + kβ I) /
    /// (w + kα) (eq. 3.44 in the thesis' case).
    struct Relaxation
    {
      double weight;
      double alpha;
      double beta;
    };

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// φ clipped to [0, 1]: a Q2 interpolant of a step overshoots.
    static double
    clipped(const double volume_fraction);

    /// The solvent viscosity ηs(φ) of the mixture. Thesis mixture: η(φ) =
    /// ηs + (ηp − ηs) φ (thesis eq. 2.8, = 1 + (ηp/ηs − 1) φ dimensionless);
    /// phases: ηs,water + (ηs,biofilm − ηs,water) φ.
    double
    viscosity(const double volume_fraction) const;

    /// The largest over the smallest of viscosity(φ), φ in [0, 1] (it is
    /// monotone in φ); infinite if one is 0.
    double
    viscosity_ratio() const;

    /// c of the relaxed state (τ = 0), the same everywhere: ηp/(a λ) for the
    /// thesis mixture (eq. 2.39), 1 for phases.
    double
    relaxed_conformation() const;

    /// τ = G(φ) (c − c_rest I) (thesis eq. 2.39 with G = 1; phases: G(φ) of
    /// stress_modulus(), 0 in a Newtonian phase).
    template <int dim>
    SymmetricTensor<2, dim>
    stress(const SymmetricTensor<2, dim> &conformation,
           const double                   volume_fraction) const;

    /// G(φ) in τ = G (c − c_rest I). Phases: ηp(φ)/(a λ(φ)) with ηp
    /// linear in φ (Mixture = viscosity), or G linear in φ between the
    /// phases' ηp/(a λ) (Mixture = modulus, geometric; then ηp(φ) = a G(φ)
    /// λ(φ)).
    double
    stress_modulus(const double volume_fraction) const;

    /// Phases: λ(φ), linear in φ, or the geometric mean λw^(1−φ) λb^φ
    /// (Mixture = geometric).
    double
    relaxation_time(const double volume_fraction) const;

    /// The inverse of stress(): c of a given τ (c_rest I where G = 0).
    template <int dim>
    SymmetricTensor<2, dim>
    conformation(const SymmetricTensor<2, dim> &stress,
                 const double                   volume_fraction) const;

    /// s(φ): the flow sees ∇·(s τ). φ for the thesis mixture (eq. 2.34),
    /// 1 for phases.
    double
    stress_coupling(const double volume_fraction) const;

    /// w, α, β of the update at φ: thesis w = φ, α = 1/λ, β = ηp/(a λ²)
    /// (eq. 2.40); phases w = λ(φ), α = β = 1.
    Relaxation
    relaxation(const double volume_fraction) const;

    /// The viscosity with which the update of one step of length @p k
    /// answers a velocity gradient, s G w k a c_max / (w + k α) with c_max
    /// the largest eigenvalue of the conformation of @p stress, at least
    /// c_rest (thesis at rest: φ² ηp k/(λφ + k); phases: ηp(φ) k/(λ(φ) + k),
    /// ηp(φ) = a G(φ) λ(φ)).
    template <int dim>
    double
    elastic_viscosity(const double                   volume_fraction,
                      const double                   k,
                      const SymmetricTensor<2, dim> &stress) const;

    /// Print the rheology, the derived dimensionless numbers and the scales
    /// used for them, and warnings about entries the choice ignores.
    void
    print(ConditionalOStream &out) const;

    Units    units    = Units::dimensionless;
    Rheology rheology = Rheology::thesis_mixture;
    Mixture  mixture  = Mixture::viscosity;
    /// The coefficient of ∂u/∂t: Res (dimensionless) or ρ in kg/m³ (SI).
    double density = 1.6667e-6;
    Phase  water;
    Phase  biofilm;
    double slip_parameter = 1;
    double diffusion      = 1e-5;
    bool   viscoelastic   = true; // false: τ ≡ 0, a Newtonian mixture
    /// Length and velocity scales: only for the derived numbers printed.
    double length_scale   = 1;
    double velocity_scale = 1;

  private:
    /// A property mixed linearly in the clipped φ.
    static double
    mix(const double water_value, const double biofilm_value, const double volume_fraction);

    /// A phase's ηp/(a λ), 0 if it is Newtonian.
    double
    modulus(const Phase &phase) const;

    std::vector<std::string> ignored_entries;
  };
} // namespace viscofilm

#endif
