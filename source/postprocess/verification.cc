#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/postprocess/verification.h>
#include <viscofilm/transport/volume_fraction.h>

#include <cmath>

namespace viscofilm
{
  template <int dim>
  void
  Verification<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    ParsedExpression<dim>::declare(prm,
                              "Body force",
                              zero_expression(dim),
                              "Body force \"fx; fy\" (3D: \"fx; fy; fz\") "
                              "added to the momentum equation, e.g. for a "
                              "manufactured solution.");
    prm.declare_entry("Exact solution",
                      "",
                      Patterns::Anything(),
                      "Empty, or the exact \"u; v; p\" (3D: \"u; v; w; p\") as "
                      "a muparser expression in x, y (, z), t: its L2 errors "
                      "are written to statistics.csv "
                      "(the pressure error modulo a constant when no boundary "
                      "is 'outflow').");
    prm.declare_entry("Exact stress",
                      "",
                      Patterns::Anything(),
                      "Empty, or the exact \"τ_xx; τ_xy; τ_yy\" (3D: \"τ_xx; "
                      "τ_xy; τ_xz; τ_yy; τ_yz; τ_zz\") in x, y (, z), t: "
                      "statistics.csv gets stress_l2_error.");
    prm.declare_entry("Exact volume fraction",
                      "",
                      Patterns::Anything(),
                      "Empty, or the exact φ in x, y (, z), t: statistics.csv gets "
                      "volume_fraction_l2_error.");
    declare_function_constants(prm);
    prm.leave_subsection();
  }


  template <int dim>
  void
  Verification<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    const std::string constants = prm.get("Function constants");
    body_force.parse(prm.get("Body force"),
                     constants,
                     "Verification/Body force");
    const auto optional_expression = [&](std::optional<ParsedExpression<dim>> &target,
                                         const std::string &name,
                                         const unsigned int n_components) {
      target.reset();
      if (!prm.get(name).empty())
        {
          target.emplace(n_components);
          target->parse(prm.get(name), constants, "Verification/" + name);
        }
    };
    optional_expression(exact_solution, "Exact solution", dim + 1);
    optional_expression(exact_stress, "Exact stress", n_symmetric_components<dim>);
    optional_expression(exact_volume_fraction, "Exact volume fraction", 1);
    prm.leave_subsection();
  }


  namespace
  {
    /// The norm @p norm of u_h − @p exact over the components @p mask selects
    /// (all: null), summed over the cells of every rank.
    template <int dim, typename VectorType>
    double
    global_error(const Mapping<dim> &         mapping,
                 const DoFHandler<dim> &      dof_handler,
                 const VectorType &           solution,
                 const Function<dim> &        exact,
                 const VectorTools::NormType  norm,
                 const Function<dim> *        mask = nullptr)
    {
      Vector<double> cellwise(dof_handler.get_triangulation().n_active_cells());
      VectorTools::integrate_difference(mapping,
                                        dof_handler,
                                        solution,
                                        exact,
                                        cellwise,
                                        QGauss<dim>(dof_handler.get_fe().degree + 2),
                                        norm,
                                        mask);
      return VectorTools::compute_global_error(dof_handler.get_triangulation(),
                                               cellwise,
                                               norm);
    }
  } // namespace


  template <int dim>
  std::pair<double, double>
  Verification<dim>::l2_errors(const double time) const
  {
    Assert(parameters.exact_solution, ExcInternalError());
    const ExpressionAt<dim>             exact = parameters.exact_solution->at(time);
    const ComponentSelectFunction<dim> velocity(std::make_pair(0, dim), dim + 1);
    const ComponentSelectFunction<dim> pressure(dim, dim + 1);
    const auto error = [&](const VectorTools::NormType norm, const Function<dim> &mask) {
      return global_error(
        stokes.mapping(), stokes.dof_handler(), stokes.solution(), exact, norm, &mask);
    };
    double pressure_error_squared = std::pow(error(VectorTools::L2_norm, pressure), 2);
    // Without the best constant shift: ‖e‖² − (∫e)²/|Ω|.
    if (pressure_up_to_constant)
      pressure_error_squared -=
        std::pow(error(VectorTools::mean, pressure), 2) /
        GridTools::volume(stokes.dof_handler().get_triangulation(), stokes.mapping());
    return {error(VectorTools::L2_norm, velocity),
            std::sqrt(std::max(pressure_error_squared, 0.0))};
  }


  template <int dim>
  double
  Verification<dim>::stress_l2_error(const double time) const
  {
    const ExpressionAt<dim> exact = parameters.exact_stress->at(time);
    const DoFHandler<dim> &dof_handler = stress.dof_handler();
    const QGauss<dim>      quadrature(dof_handler.get_fe().degree + 2);
    FEValues<dim>          fe_values(stress.mapping(),
                          dof_handler.get_fe(),
                          quadrature,
                          update_values | update_quadrature_points | update_JxW_values);
    FEValues<dim> phi_values(volume_fraction.dof_handler().get_fe(), quadrature, update_values);
    std::vector<Vector<double>> conformation(quadrature.size(),
                                             Vector<double>(n_symmetric_components<dim>));
    std::vector<Vector<double>> reference(quadrature.size(),
                                          Vector<double>(n_symmetric_components<dim>));
    std::vector<double>         phi(quadrature.size());
    double                      sum = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(stress.solution(), conformation);
          phi_values.reinit(cell_of(volume_fraction.dof_handler(), cell));
          phi_values.get_function_values(volume_fraction.solution(), phi);
          exact.vector_value_list(fe_values.get_quadrature_points(), reference);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const SymmetricTensor<2, dim> tau = stress.stress_of(conformation[q], phi[q]);
              double squared = 0;
              for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
                squared += std::pow(stored_component(tau, k) - reference[q][k], 2);
              sum += squared * fe_values.JxW(q);
            }
        }
    return std::sqrt(Utilities::MPI::sum(sum, dof_handler.get_communicator()));
  }


  template <int dim>
  double
  Verification<dim>::volume_fraction_l2_error(const double time) const
  {
    return global_error(volume_fraction.mapping(),
                        volume_fraction.dof_handler(),
                        volume_fraction.solution(),
                        parameters.exact_volume_fraction->at(time),
                        VectorTools::L2_norm);
  }


  template <int dim>
  Verification<dim>::Verification(const Parameters &         parameters,
                                  const StokesFlow<dim> &    stokes,
                                  const ElasticStress<dim> & stress,
                                  const VolumeFraction<dim> &volume_fraction,
                                  const bool                 pressure_up_to_constant)
    : parameters(parameters)
    , stokes(stokes)
    , stress(stress)
    , volume_fraction(volume_fraction)
    , pressure_up_to_constant(pressure_up_to_constant)
  {}


  template <int dim>
  void
  Verification<dim>::add_statistics(CsvFile &statistics, const double time) const
  {
    if (parameters.exact_solution)
      {
        const auto [velocity_error, pressure_error] = l2_errors(time);
        statistics.set("velocity_l2_error", velocity_error);
        statistics.set("pressure_l2_error", pressure_error);
      }
    if (parameters.exact_stress)
      statistics.set("stress_l2_error", stress_l2_error(time));
    if (parameters.exact_volume_fraction)
      statistics.set("volume_fraction_l2_error", volume_fraction_l2_error(time));
  }


  VISCOFILM_INSTANTIATE(Verification)
} // namespace viscofilm
