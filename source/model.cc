#include <viscofilm/input.h>
#include <viscofilm/model.h>

#include <algorithm>

namespace viscofilm
{
  void
  Model::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Model");
    prm.declare_entry("Reynolds number",
                      "1.6667e-6",
                      Patterns::Double(0),
                      "Res = ρ U0 L0 / ηs, multiplying ∂u/∂t (inertia u·∇u is "
                      "dropped). Table 4.1: 1.6667e-6. 0 gives steady Stokes.");
    prm.declare_entry("Viscosity ratio",
                      "500",
                      Patterns::Double(0),
                      "ηp/ηs: biofilm over solvent viscosity, > 0. Table 4.1: 500.");
    prm.declare_entry("Weissenberg number",
                      "2",
                      Patterns::Double(0),
                      "Wi = λ/T0, relaxation time over the time scale, > 0. "
                      "Table 4.1: 2 (λ = 120 s, T0 = 60 s).");
    prm.declare_entry("Slip parameter",
                      "1",
                      Patterns::Double(-1, 1),
                      "Johnson–Segalman a in [-1, 1], not 0: 1 upper convected "
                      "(Oldroyd-B), -1 lower convected.");
    prm.declare_entry("Diffusion coefficient",
                      "1e-5",
                      Patterns::Double(0),
                      "D in ∂φ/∂t + u·∇φ = ∇·(D φ ∇φ) (thesis eq. 3.45), >= 0.");
    prm.declare_entry("Viscoelastic",
                      "true",
                      Patterns::Bool(),
                      "true: the Oldroyd-B / Johnson–Segalman stress τ acts on "
                      "the flow. false: τ ≡ 0 everywhere (a Newtonian mixture of "
                      "viscosity η(φ); Initial conditions/Stress is ignored); no "
                      "departure feet for the stress, no Picard loop.");
    prm.leave_subsection();
  }


  void
  Model::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Model");
    reynolds_number = prm.get_double("Reynolds number");
    viscosity_ratio = prm.get_double("Viscosity ratio");
    weissenberg     = prm.get_double("Weissenberg number");
    slip_parameter  = prm.get_double("Slip parameter");
    diffusion       = prm.get_double("Diffusion coefficient");
    viscoelastic    = prm.get_bool("Viscoelastic");
    prm.leave_subsection();

    check_input(viscosity_ratio > 0,
                "Model/Viscosity ratio must be > 0, got " +
                  to_text(viscosity_ratio));
    check_input(slip_parameter != 0,
                "Model/Slip parameter must be in [-1, 1] and not 0: the "
                "conformation shift ηp/(a Wi) is undefined at a = 0 (MODEL.md §2)");
    check_input(weissenberg > 0,
                "Model/Weissenberg number must be > 0, got " +
                  to_text(weissenberg));
  }


  double
  Model::viscosity(const double volume_fraction) const
  {
    const double phi = std::clamp(volume_fraction, 0.0, 1.0);
    return 1.0 + (viscosity_ratio - 1.0) * phi;
  }


  void
  Model::print(ConditionalOStream &out) const
  {
    out << "Model: Reynolds number Res = " << reynolds_number
        << ", viscosity ratio ηp/ηs = " << viscosity_ratio
        << ", Weissenberg number Wi = " << weissenberg
        << ", slip parameter a = " << slip_parameter
        << ", diffusion D = " << diffusion
        << (viscoelastic ? "" : "; elastic stress off") << std::endl;
  }
} // namespace viscofilm
