#include <viscofilm/core/input.h>
#include <viscofilm/material/model.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <utility>

namespace viscofilm
{
  namespace
  {
    const char *const phase_names[2] = {"Water", "Biofilm"};

    /// The entries a choice of Units and Rheology may ignore, with their
    /// defaults: a value other than the default is reported as ignored.
    const std::vector<std::pair<std::string, std::string>> optional_entries = {
      {"Reynolds number", "1.6667e-6"},
      {"Density", ""},
      {"Viscosity ratio", "500"},
      {"Weissenberg number", "2"},
      {"Mixture", "viscosity"},
      {"Water/Solvent viscosity", "1"},
      {"Water/Polymer viscosity", "0"},
      {"Water/Relaxation time", "0"},
      {"Biofilm/Solvent viscosity", "1"},
      {"Biofilm/Polymer viscosity", "500"},
      {"Biofilm/Relaxation time", "2"}};

    std::string
    get_entry(ParameterHandler &prm, const std::string &path)
    {
      const auto slash = path.find('/');
      if (slash == std::string::npos)
        return prm.get(path);
      prm.enter_subsection(path.substr(0, slash));
      const std::string value = prm.get(path.substr(slash + 1));
      prm.leave_subsection();
      return value;
    }

    double
    get_number(ParameterHandler &prm, const std::string &path)
    {
      const std::string text = get_entry(prm, path);
      try
        {
          std::size_t end   = 0;
          const double value = std::stod(text, &end);
          if (text.find_first_not_of(" \t", end) == std::string::npos)
            return value;
        }
      catch (const std::exception &)
        {}
      check_input(false, "Model/" + path + " must be a number, got '" + text + "'");
      return 0;
    }
  } // namespace


  void
  Model::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Model");
    prm.declare_entry("Units",
                      "dimensionless",
                      Patterns::Selection("dimensionless|SI"),
                      "dimensionless: the thesis' scaled equations (Reynolds "
                      "number, viscosities relative to the water's solvent "
                      "viscosity, times in units of T0). SI: the dimensional "
                      "equations, ρ ∂u/∂t = ∇·(2 ηs(φ) D(u)) − ∇p + ∇·(s τ), "
                      "with Density in kg/m³, viscosities in Pa·s, relaxation "
                      "times and every time in s, lengths in m, velocities in "
                      "m/s; the outputs are in the same units (pressure and "
                      "stress in Pa). See doc/parameters.md, \"Units\".");
    prm.declare_entry("Rheology",
                      "thesis mixture",
                      Patterns::Selection("thesis mixture|phases"),
                      "thesis mixture: η(φ) = ηs + (ηp − ηs) φ and the φ-scaled "
                      "Oldroyd-B/JS stress φ τ (thesis eq. 2.8, 2.34); reads "
                      "Viscosity ratio and Weissenberg number (dimensionless) or "
                      "Water/Solvent viscosity, Biofilm/Polymer viscosity and "
                      "Biofilm/Relaxation time (SI). phases: water and biofilm "
                      "are each an Oldroyd-B/JS fluid (Water, Biofilm "
                      "subsections: ηs, ηp, λ), their properties mixed linearly "
                      "in φ (Mixture), τ acting unscaled on the flow.");
    prm.declare_entry("Mixture",
                      "viscosity",
                      Patterns::Selection("viscosity|modulus|geometric"),
                      "Rheology = phases: how the phases' elasticity is mixed "
                      "in φ. viscosity: ηp and λ each linear in φ, so the "
                      "modulus ηp/λ is the biofilm's at every φ > 0 beside a "
                      "Newtonian water. modulus: the modulus G = ηp/λ and λ "
                      "each linear in φ, ηp(φ) = G(φ) λ(φ): beside a Newtonian "
                      "water G vanishes with φ, as the thesis mixture's "
                      "φ-scaled stress does (doc/numerics.md, \"Rheology and "
                      "units\"). geometric: G linear in φ as with modulus, λ "
                      "the geometric mean λw^(1−φ) λb^φ (logarithmic mixing), "
                      "so that a dilute fringe of biofilm in the water relaxes "
                      "about as fast as the water's λ (> 0 then); "
                      "doc/rheology.md. ηs is linear in φ in all three.");
    prm.declare_entry("Reynolds number",
                      "1.6667e-6",
                      Patterns::Double(0),
                      "Units = dimensionless: Res = ρ U0 L0 / ηs, multiplying "
                      "the material derivative Du/Dt = ∂u/∂t + u·∇u "
                      "(semi-Lagrangian: u^n read at the departure feet). "
                      "Table 4.1: 1.6667e-6. 0 gives steady Stokes.");
    prm.declare_entry("Density",
                      "",
                      Patterns::Anything(),
                      "Units = SI (required there): ρ in kg/m³, multiplying "
                      "the material derivative Du/Dt = ∂u/∂t + u·∇u "
                      "(semi-Lagrangian: u^n read at the departure feet). 0 "
                      "gives steady Stokes.");
    prm.declare_entry("Viscosity ratio",
                      "500",
                      Patterns::Double(0),
                      "Thesis mixture, dimensionless: ηp/ηs, biofilm over "
                      "solvent viscosity, > 0. Table 4.1: 500.");
    prm.declare_entry("Weissenberg number",
                      "2",
                      Patterns::Double(0),
                      "Thesis mixture, dimensionless: Wi = λ/T0, relaxation time "
                      "over the time scale, > 0. Table 4.1: 2 (λ = 120 s, T0 = "
                      "60 s).");
    prm.declare_entry("Slip parameter",
                      "1",
                      Patterns::Double(-1, 1),
                      "Johnson–Segalman a in [-1, 1], not 0: 1 upper convected "
                      "(Oldroyd-B), -1 lower convected.");
    prm.declare_entry("Diffusion coefficient",
                      "1e-5",
                      Patterns::Double(0),
                      "D in ∂φ/∂t + u·∇φ = ∇·(D φ ∇φ) (thesis eq. 3.45), >= 0, "
                      "in the input's units (m²/s with Units = SI).");
    prm.declare_entry("Viscoelastic",
                      "true",
                      Patterns::Bool(),
                      "true: the Oldroyd-B / Johnson–Segalman stress τ acts on "
                      "the flow. false: τ ≡ 0 everywhere (a Newtonian mixture of "
                      "viscosity η(φ); Initial conditions/Stress is ignored); no "
                      "departure feet for the stress, no Picard loop.");
    prm.declare_entry("Length scale",
                      "1",
                      Patterns::Double(0),
                      "L, only for the derived numbers printed at start (Re = "
                      "ρUL/ηs, Wi = λU/L); the equations do not use it. > 0.");
    prm.declare_entry("Velocity scale",
                      "1",
                      Patterns::Double(0),
                      "U, only for the derived numbers printed at start; the "
                      "equations do not use it. > 0.");
    for (const char *name : phase_names)
      {
        const bool water = (std::string(name) == "Water");
        prm.enter_subsection(name);
        prm.declare_entry("Solvent viscosity",
                          "1",
                          Patterns::Anything(),
                          std::string("ηs of the ") + (water ? "water" : "biofilm") +
                            ", > 0 (Pa·s with Units = SI; relative to the "
                            "scale of the equations otherwise). Read by "
                            "Rheology = phases" +
                            (water ? " and by the thesis mixture in SI." : "."));
        prm.declare_entry("Polymer viscosity",
                          water ? "0" : "500",
                          Patterns::Anything(),
                          std::string("ηp of the ") + (water ? "water" : "biofilm") +
                            ", >= 0 (0: a Newtonian phase). Read by Rheology = "
                            "phases" +
                            (water ? "." : " and by the thesis mixture in SI."));
        prm.declare_entry("Relaxation time",
                          water ? "0" : "2",
                          Patterns::Anything(),
                          std::string("λ of the ") + (water ? "water" : "biofilm") +
                            ", > 0 where Polymer viscosity > 0 (s with Units "
                            "= SI). Read by Rheology = phases" +
                            (water ? "." : " and by the thesis mixture in SI."));
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  Model::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Model");
    units    = prm.get("Units") == "SI" ? Units::SI : Units::dimensionless;
    rheology = prm.get("Rheology") == "phases" ? Rheology::phases :
                                                 Rheology::thesis_mixture;
    const std::string mixture_name = prm.get("Mixture");
    mixture = mixture_name == "modulus"   ? Mixture::modulus :
              mixture_name == "geometric" ? Mixture::geometric :
                                            Mixture::viscosity;
    slip_parameter = prm.get_double("Slip parameter");
    diffusion      = prm.get_double("Diffusion coefficient");
    viscoelastic   = prm.get_bool("Viscoelastic");
    length_scale   = prm.get_double("Length scale");
    velocity_scale = prm.get_double("Velocity scale");
    check_input(length_scale > 0,
                "Model/Length scale must be > 0 (it divides Wi = λU/L), got " +
                  to_text(length_scale));
    check_input(velocity_scale > 0,
                "Model/Velocity scale must be > 0, got " + to_text(velocity_scale));

    const bool si     = (units == Units::SI);
    const bool phases = (rheology == Rheology::phases);
    // The entries this choice reads; the others keep their defaults.
    std::vector<std::string> used;
    if (si)
      {
        check_input(!prm.get("Density").empty(),
                    "Model/Density (kg/m³) is required with Model/Units = SI");
        density = get_number(prm, "Density");
        check_input(density >= 0,
                    "Model/Density must be >= 0 (kg/m³), got " + to_text(density));
        used.push_back("Density");
      }
    else
      {
        density = prm.get_double("Reynolds number");
        used.push_back("Reynolds number");
      }
    if (phases)
      {
        used.push_back("Mixture");
        for (const char *name : phase_names)
          {
            const std::string phase = name;
            Phase &p = (phase == "Water" ? water : biofilm);
            p.solvent_viscosity = get_number(prm, phase + "/Solvent viscosity");
            p.polymer_viscosity = get_number(prm, phase + "/Polymer viscosity");
            p.relaxation_time   = get_number(prm, phase + "/Relaxation time");
            for (const char *entry :
                 {"/Solvent viscosity", "/Polymer viscosity", "/Relaxation time"})
              used.push_back(phase + entry);
          }
      }
    else if (si)
      {
        water   = Phase{get_number(prm, "Water/Solvent viscosity"), 0, 0};
        biofilm = Phase{0,
                        get_number(prm, "Biofilm/Polymer viscosity"),
                        get_number(prm, "Biofilm/Relaxation time")};
        used.insert(used.end(),
                    {"Water/Solvent viscosity",
                     "Biofilm/Polymer viscosity",
                     "Biofilm/Relaxation time"});
      }
    else
      {
        // The dimensionless thesis: viscosities relative to ηs, times to T0.
        water   = Phase{1.0, 0, 0};
        biofilm = Phase{0,
                        prm.get_double("Viscosity ratio"),
                        prm.get_double("Weissenberg number")};
        used.insert(used.end(), {"Viscosity ratio", "Weissenberg number"});
      }
    ignored_entries.clear();
    for (const auto &[entry, default_value] : optional_entries)
      if (std::find(used.begin(), used.end(), entry) == used.end() &&
          get_entry(prm, entry) != default_value)
        ignored_entries.push_back(entry);
    prm.leave_subsection();

    check_input(slip_parameter != 0,
                "Model/Slip parameter must be in [-1, 1] and not 0: the "
                "conformation shift ηp/(a Wi) is undefined at a = 0 (MODEL.md §2)");
    if (phases)
      for (const char *name : phase_names)
        {
          const Phase &     p      = (std::string(name) == "Water" ? water : biofilm);
          const std::string prefix = std::string("Model/") + name + "/";
          check_input(p.solvent_viscosity > 0,
                      prefix + "Solvent viscosity must be > 0 (the Stokes "
                               "operator needs a viscosity in every phase), got " +
                        to_text(p.solvent_viscosity));
          check_input(p.polymer_viscosity >= 0,
                      prefix + "Polymer viscosity must be >= 0, got " +
                        to_text(p.polymer_viscosity));
          check_input(p.relaxation_time > 0 ||
                        (p.polymer_viscosity == 0 && p.relaxation_time == 0),
                      prefix + "Relaxation time must be > 0 (or 0 with Polymer "
                               "viscosity = 0: a Newtonian phase), got " +
                        to_text(p.relaxation_time));
          // ln λ is mixed: a Newtonian phase needs a relaxation time of its
          // own, the time the dilute biofilm relaxes in.
          check_input(mixture != Mixture::geometric || p.relaxation_time > 0,
                      prefix + "Relaxation time must be > 0 with Model/Mixture "
                               "= geometric (λ is mixed as λw^(1−φ) λb^φ), got " +
                        to_text(p.relaxation_time));
        }
    else if (si)
      {
        check_input(water.solvent_viscosity > 0,
                    "Model/Water/Solvent viscosity must be > 0 (Pa·s), got " +
                      to_text(water.solvent_viscosity));
        check_input(biofilm.polymer_viscosity > 0,
                    "Model/Biofilm/Polymer viscosity must be > 0 (Pa·s) with "
                    "Rheology = thesis mixture, got " +
                      to_text(biofilm.polymer_viscosity));
        check_input(biofilm.relaxation_time > 0,
                    "Model/Biofilm/Relaxation time must be > 0 (s) with "
                    "Rheology = thesis mixture, got " +
                      to_text(biofilm.relaxation_time));
      }
    else
      {
        check_input(biofilm.polymer_viscosity > 0,
                    "Model/Viscosity ratio must be > 0, got " +
                      to_text(biofilm.polymer_viscosity));
        check_input(biofilm.relaxation_time > 0,
                    "Model/Weissenberg number must be > 0, got " +
                      to_text(biofilm.relaxation_time));
      }
  }


  double
  Model::clipped(const double volume_fraction)
  {
    return std::clamp(volume_fraction, 0.0, 1.0);
  }


  double
  Model::mix(const double water_value,
             const double biofilm_value,
             const double volume_fraction)
  {
    return water_value + (biofilm_value - water_value) * clipped(volume_fraction);
  }


  double
  Model::viscosity(const double volume_fraction) const
  {
    return rheology == Rheology::thesis_mixture ?
             mix(water.solvent_viscosity, biofilm.polymer_viscosity, volume_fraction) :
             mix(water.solvent_viscosity, biofilm.solvent_viscosity, volume_fraction);
  }


  double
  Model::viscosity_ratio() const
  {
    const double water = viscosity(0.0), biofilm = viscosity(1.0);
    const double low = std::min(water, biofilm), high = std::max(water, biofilm);
    return low > 0 ? high / low : std::numeric_limits<double>::infinity();
  }


  double
  Model::relaxed_conformation() const
  {
    return rheology == Rheology::thesis_mixture ?
             biofilm.polymer_viscosity / (slip_parameter * biofilm.relaxation_time) :
             1.0;
  }


  template <int dim>
  SymmetricTensor<2, dim>
  Model::stress(const SymmetricTensor<2, dim> &conformation,
                const double                   volume_fraction) const
  {
    return stress_modulus(volume_fraction) *
           (conformation - relaxed_conformation() * unit_symmetric_tensor<dim>());
  }


  double
  Model::modulus(const Phase &phase) const
  {
    return phase.polymer_viscosity == 0 ?
             0.0 :
             phase.polymer_viscosity / (slip_parameter * phase.relaxation_time);
  }


  double
  Model::stress_modulus(const double volume_fraction) const
  {
    if (rheology == Rheology::thesis_mixture)
      return 1.0;
    if (mixture != Mixture::viscosity)
      return mix(modulus(water), modulus(biofilm), volume_fraction);
    // Mixture = viscosity: the modulus of the phase with ηp and λ mixed.
    return modulus(
      Phase{0,
            mix(water.polymer_viscosity, biofilm.polymer_viscosity, volume_fraction),
            relaxation_time(volume_fraction)});
  }


  double
  Model::relaxation_time(const double volume_fraction) const
  {
    if (mixture == Mixture::geometric)
      return water.relaxation_time *
             std::pow(biofilm.relaxation_time / water.relaxation_time,
                      clipped(volume_fraction));
    return mix(water.relaxation_time, biofilm.relaxation_time, volume_fraction);
  }


  template <int dim>
  SymmetricTensor<2, dim>
  Model::conformation(const SymmetricTensor<2, dim> &stress,
                      const double                   volume_fraction) const
  {
    const SymmetricTensor<2, dim> relaxed =
      relaxed_conformation() * unit_symmetric_tensor<dim>();
    const double modulus = stress_modulus(volume_fraction);
    return modulus == 0 ? relaxed : stress / modulus + relaxed;
  }


  double
  Model::stress_coupling(const double volume_fraction) const
  {
    return rheology == Rheology::thesis_mixture ? clipped(volume_fraction) : 1.0;
  }


  Model::Relaxation
  Model::relaxation(const double volume_fraction) const
  {
    if (rheology == Rheology::phases)
      return {relaxation_time(volume_fraction), 1.0, 1.0};
    // φ L(c) + c/λ = ηp/(a λ²) I (eq. 2.40).
    const double lambda = biofilm.relaxation_time;
    return {clipped(volume_fraction), 1.0 / lambda, relaxed_conformation() / lambda};
  }


  template <int dim>
  double
  Model::elastic_viscosity(const double                   volume_fraction,
                           const double                   k,
                           const SymmetricTensor<2, dim> &stress) const
  {
    // c^{n+1} = (w E c Eᵀ + kβ I)/(w + kα) with E ≈ I + kΦ: Δc = w k (Φc +
    // cΦᵀ)/(w + kα), 2 a c_rest w k D(u)/(w + kα) at rest and at most
    // c_max/c_rest times that when stretched; τ = G Δc, the flow sees s τ.
    const Relaxation r = relaxation(volume_fraction);
    if (r.weight + k * r.alpha == 0)
      return 0;
    const double c_max =
      std::max(relaxed_conformation(),
               eigenvalues(conformation(stress, volume_fraction))[0]);
    return stress_coupling(volume_fraction) * stress_modulus(volume_fraction) *
           std::abs(slip_parameter) * c_max * r.weight * k / (r.weight + k * r.alpha);
  }


  void
  Model::print(ConditionalOStream &out) const
  {
    const bool si = (units == Units::SI);
    out << "Model: " << (si ? "SI units" : "dimensionless") << ", rheology "
        << (rheology == Rheology::phases ? "phases" : "thesis mixture")
        << (si ? ", density ρ = " : ", Reynolds number Res = ") << density
        << ", slip parameter a = " << slip_parameter
        << ", diffusion D = " << diffusion
        << (viscoelastic ? "" : "; elastic stress off") << std::endl;
    const double U = velocity_scale, L = length_scale;
    if (rheology == Rheology::thesis_mixture)
      {
        const double ratio = biofilm.polymer_viscosity / water.solvent_viscosity;
        out << "  solvent viscosity ηs = " << water.solvent_viscosity
            << ", biofilm viscosity ηp = " << biofilm.polymer_viscosity
            << ", relaxation time λ = " << biofilm.relaxation_time << std::endl
            << "  derived (U = Velocity scale = " << U << ", L = Length scale = " << L
            << ", used only here): Re = ρUL/ηs = "
            << density * U * L / water.solvent_viscosity
            << ", Wi = λU/L = " << biofilm.relaxation_time * U / L
            << ", viscosity ratio ηp/ηs = " << ratio
            << ", β = ηs/(ηs + ηp) = " << 1 / (1 + ratio) << std::endl;
      }
    else
      {
        out << "  derived (U = Velocity scale = " << U << ", L = Length scale = " << L
            << ", used only here): Re = ρUL/ηs(water) = "
            << density * U * L / water.solvent_viscosity << std::endl
            << "  mixed in φ (Mixture = "
            << (mixture == Mixture::modulus ?
                  "modulus): ηs, G = ηp/(aλ) and λ linear" :
                mixture == Mixture::geometric ?
                  "geometric): ηs and G = ηp/(aλ) linear, λ = λw^(1−φ) λb^φ" :
                  "viscosity): ηs, ηp and λ linear")
            << std::endl;
        for (const char *name : phase_names)
          {
            const Phase &p     = (std::string(name) == "Water" ? water : biofilm);
            const double total = p.solvent_viscosity + p.polymer_viscosity;
            out << "  " << name << ": ηs = " << p.solvent_viscosity
                << ", ηp = " << p.polymer_viscosity
                << ", λ = " << p.relaxation_time
                << "; Wi = λU/L = " << p.relaxation_time * U / L
                << ", β = ηs/(ηs + ηp) = " << p.solvent_viscosity / total
                << ", viscosity (ηs + ηp)/ηs(water) = "
                << total / water.solvent_viscosity << std::endl;
          }
      }
    for (const std::string &entry : ignored_entries)
      out << "Warning: Model/" << entry << " is set but ignored with Units = "
          << (si ? "SI" : "dimensionless") << " and Rheology = "
          << (rheology == Rheology::phases ? "phases" : "thesis mixture")
          << " (doc/parameters.md, \"Units\")" << std::endl;
  }


#define INSTANTIATE(dim)                                                         \
  template SymmetricTensor<2, dim> Model::stress(const SymmetricTensor<2, dim> &, \
                                                 const double) const;            \
  template SymmetricTensor<2, dim> Model::conformation(                           \
    const SymmetricTensor<2, dim> &, const double) const;                         \
  template double Model::elastic_viscosity(const double,                          \
                                           const double,                          \
                                           const SymmetricTensor<2, dim> &) const;
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
