#include <viscofilm/biofilm/initial_conditions.h>

namespace viscofilm
{
  template <int dim>
  const std::map<std::string, std::string> &
  InitialConditions<dim>::presets()
  {
    // On the unit square, centred on x = 0.5 at the bottom wall y = 0. The
    // thesis does not give its shapes; these follow its figures 4.1 and 4.4.
    // In 3D they do not depend on z: ridges across the channel.
    static const std::map<std::string, std::string> profiles = {
      // stalk of half-width 0.04 up to y = 0.2 under a disc of radius 0.1
      {"bulb",
       "if(abs(x-0.5) < 0.04 & y < 0.2 | (x-0.5)^2 + (y-0.22)^2 < 0.01, 0.1, 0)"},
      // a layer of thickness 0.05 over the whole bottom wall
      {"flat", "if(y < 0.05, 0.1, 0)"},
      // half-ellipse mounds: half-width a, height b
      {"short", "if((x-0.5)^2/0.15^2 + y^2/0.1^2 < 1, 0.1, 0)"},  // a .15 b .1
      {"tall", "if((x-0.5)^2/0.1^2 + y^2/0.3^2 < 1, 0.1, 0)"},    // a .1  b .3
      {"fat", "if((x-0.5)^2/0.25^2 + y^2/0.15^2 < 1, 0.1, 0)"},   // a .25 b .15
      {"thin", "if((x-0.5)^2/0.05^2 + y^2/0.2^2 < 1, 0.1, 0)"}}; // a .05 b .2
    return profiles;
  }


  template <int dim>
  void
  InitialConditions<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial conditions");
    std::string names;
    for (const auto &preset : presets())
      names += (names.empty() ? "" : ", ") + preset.first;
    ParsedExpression<dim>::declare(prm,
                              "Volume fraction",
                              "0",
                              "Biofilm volume fraction φ at t = 0, in [0, 1] (the "
                              "thesis: 0.1 inside the biofilm, 0 in water), one "
                              "of the named profiles " + names +
                                " (doc/parameters.md), or image: φ from the "
                                "subsection Image (doc/images.md).");
    ParsedExpression<dim>::declare(prm,
                              "Stress",
                              zero_expression(n_symmetric_components<dim>),
                              "Elastic stress \"τ_xx; τ_xy; τ_yy\" (3D: \"τ_xx; "
                              "τ_xy; τ_xz; τ_yy; τ_yz; τ_zz\") at t = 0 (the "
                              "thesis: 0).");
    declare_function_constants(prm);
    prm.declare_entry("Softening steps",
                      "0",
                      Patterns::Integer(0),
                      "Implicit Euler steps of ∂φ/∂t = ∇·(D φ ∇φ) applied to "
                      "the initial φ (eq. 2.50). The thesis: 8000 steps of Δx.");
    prm.declare_entry("Softening time step",
                      "0.03125",
                      Patterns::Double(0),
                      "Time step of the softening, > 0. The thesis: Δx = 1/32.");
    BiofilmImage<dim>::declare_parameters(prm);
    prm.leave_subsection();
  }


  template <int dim>
  void
  InitialConditions<dim>::parse_parameters(ParameterHandler & prm,
                                      const std::string &     directory,
                                      const BoundingBox<dim> &domain)
  {
    prm.enter_subsection("Initial conditions");
    const std::string text   = prm.get("Volume fraction");
    const auto        preset = presets().find(text);
    from_image               = (text == "image");
    if (from_image)
      image.parse_parameters(prm, directory, domain);
    else
      volume_fraction.parse(preset != presets().end() ? preset->second : text,
                            prm.get("Function constants"),
                            "Initial conditions/Volume fraction");
    stress.parse(prm.get("Stress"),
                 prm.get("Function constants"),
                 "Initial conditions/Stress");
    softening_steps     = prm.get_integer("Softening steps");
    softening_time_step = prm.get_double("Softening time step");
    prm.leave_subsection();
    check_input(softening_time_step > 0,
                "Initial conditions/Softening time step must be > 0, got 0");
  }


  template <int dim>
  double
  InitialConditions<dim>::input_resolution() const
  {
    return from_image ? image.smallest_pixel() : 0.;
  }


  template <int dim>
  const Function<dim> &
  InitialConditions<dim>::initial_volume_fraction() const
  {
    if (from_image)
      return image.volume_fraction();
    return volume_fraction_at_start;
  }

  VISCOFILM_INSTANTIATE(InitialConditions)
} // namespace viscofilm
