// Initial state: u = 0, p = 0, τ = 0 and the biofilm's volume fraction,
// softened by φ-scaled diffusion (MODEL.md §3-4, thesis eq. 2.50).
#ifndef viscofilm_initial_conditions_h
#define viscofilm_initial_conditions_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/biofilm/image.h>
#include <viscofilm/core/input.h>

#include <map>
#include <string>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class InitialConditions
  {
  public:
    InitialConditions() = default;
    /// Not copied: the expression at t = 0 refers to this object's.
    InitialConditions(const InitialConditions &) = delete;

    static void
    declare_parameters(ParameterHandler &prm);
    /// @p directory: the parameter file's (Image/File); @p domain: the
    /// mesh's bounding box (the image must cover the biofilm in it).
    void
    parse_parameters(ParameterHandler &      prm,
                     const std::string &      directory,
                     const BoundingBox<dim> & domain);

    /// The named profiles (φ = 0.1 inside) and their expressions.
    static const std::map<std::string, std::string> &
    presets();

    /// φ(x, y) at t = 0, before softening: the expression or the image.
    const Function<dim> &
    initial_volume_fraction() const;

    /// The spacing below which initial_volume_fraction() has no detail:
    /// the image's smallest pixel edge; 0 for an expression (resolved at
    /// φ's nodes).
    double
    input_resolution() const;

    /// φ as an expression (Volume fraction not "image").
    ParsedExpression<dim> volume_fraction{1};

    /// Volume fraction = image: φ from the image.
    bool         from_image = false;
    BiofilmImage<dim> image;

    /// τ at t = 0, its stored components (dimension.h) (the thesis: 0).
    ParsedExpression<dim> stress{n_symmetric_components<dim>};

    unsigned int softening_steps     = 0;
    double       softening_time_step = 0.03125;

  private:
    /// The expression at t = 0, what initial_volume_fraction() returns
    /// without an image (it refers to volume_fraction).
    const ExpressionAt<dim> volume_fraction_at_start{volume_fraction, 1, 0};
  };
} // namespace viscofilm

#endif
