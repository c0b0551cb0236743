// Material model: dimensionless numbers and the mixture viscosity (MODEL.md §2).
#ifndef viscofilm_model_h
#define viscofilm_model_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

namespace viscofilm
{
  using namespace dealii;

  class Model
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// η(φ) = 1 + (ηp/ηs − 1) φ, thesis eq. 2.8; φ is clipped to [0, 1]
    /// because a Q2 interpolant of a step overshoots.
    double
    viscosity(const double volume_fraction) const;

    /// Print the dimensionless numbers (and the physical input, if given).
    void
    print(ConditionalOStream &out) const;

    double reynolds_number  = 1.6667e-6;
    double viscosity_ratio  = 500;
    double weissenberg      = 2;
    double slip_parameter   = 1;
    double diffusion        = 1e-5;
    bool   viscoelastic     = true; // false: τ ≡ 0, a Newtonian mixture
  };
} // namespace viscofilm

#endif
