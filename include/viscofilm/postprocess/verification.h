// Manufactured solutions: a body force and an exact solution to measure
// errors against (used by the convergence tests).
#ifndef viscofilm_verification_h
#define viscofilm_verification_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/function_parser.h>

#include <viscofilm/core/input.h>

#include <optional>
#include <utility>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class ElasticStress;
  template <int dim>
  class VolumeFraction;

  template <int dim>
  class Verification
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// f in the momentum equation (zero unless set).
    ParsedExpression<dim> body_force{dim};

    /// L2 errors (velocity, pressure) of the Stokes solution at @p time
    /// against the exact solution; with @p pressure_up_to_constant the best
    /// constant shift of the pressure is removed first.
    std::pair<double, double>
    l2_errors(const StokesFlow<dim> &stokes,
              const double              time,
              const bool                pressure_up_to_constant) const;

    /// L2 error of τ (from c and φ) against the exact stress at @p time.
    double
    stress_l2_error(const ElasticStress<dim> & stress,
                    const VolumeFraction<dim> &volume_fraction,
                    const double          time) const;

    /// L2 error of φ against the exact volume fraction at @p time.
    double
    volume_fraction_l2_error(const VolumeFraction<dim> &volume_fraction,
                             const double          time) const;

    /// (u, v, p) (3D: (u, v, w, p)) when an exact solution is given: statistics.csv then gets
    /// velocity_l2_error and pressure_l2_error.
    std::optional<ParsedExpression<dim>> exact_solution;

    /// τ's stored components (dimension.h), if given: statistics.csv gets stress_l2_error.
    std::optional<ParsedExpression<dim>> exact_stress;

    /// φ, if given: statistics.csv gets volume_fraction_l2_error.
    std::optional<ParsedExpression<dim>> exact_volume_fraction;
  };
} // namespace viscofilm

#endif
