// Manufactured solutions: a body force and an exact solution to measure
// errors against (used by the convergence tests).
#ifndef viscofilm_verification_h
#define viscofilm_verification_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/function_parser.h>

#include <viscofilm/core/input.h>
#include <viscofilm/core/reporter.h>

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

  /// Manufactured solutions: the body force and the exact solutions of a
  /// verification run (Parameters), and their errors in statistics.csv.
  template <int dim>
  class Verification : public Reporter<dim>
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// f in the momentum equation (zero unless set).
      ParsedExpression<dim> body_force{dim};

      /// (u, v, p) (3D: (u, v, w, p)) when an exact solution is given:
      /// statistics.csv then gets velocity_l2_error and pressure_l2_error.
      std::optional<ParsedExpression<dim>> exact_solution;

      /// τ's stored components (dimension.h), if given: statistics.csv gets
      /// stress_l2_error.
      std::optional<ParsedExpression<dim>> exact_stress;

      /// φ, if given: statistics.csv gets volume_fraction_l2_error.
      std::optional<ParsedExpression<dim>> exact_volume_fraction;
    };

    /// @p pressure_up_to_constant: no boundary fixes the pressure's level,
    /// so its error is taken after the best constant shift.
    Verification(const Parameters &         parameters,
                 const StokesFlow<dim> &    stokes,
                 const ElasticStress<dim> & stress,
                 const VolumeFraction<dim> &volume_fraction,
                 const bool                 pressure_up_to_constant);

    /// The errors of the exact solutions given, at @p time.
    void
    add_statistics(CsvFile &statistics, const double time) const override;

  private:
    /// L2 errors (velocity, pressure) of the Stokes solution at @p time.
    std::pair<double, double>
    l2_errors(const double time) const;

    /// L2 error of τ (from c and φ) against the exact stress at @p time.
    double
    stress_l2_error(const double time) const;

    /// L2 error of φ against the exact volume fraction at @p time.
    double
    volume_fraction_l2_error(const double time) const;

    const Parameters &         parameters;
    const StokesFlow<dim> &    stokes;
    const ElasticStress<dim> & stress;
    const VolumeFraction<dim> &volume_fraction;
    const bool                 pressure_up_to_constant;
  };
} // namespace viscofilm

#endif
