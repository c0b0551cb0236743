#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/core/input.h>
#include <viscofilm/geometry/mesh_refinement.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/transport/volume_fraction.h>

#include <algorithm>

namespace viscofilm
{
  template <int dim>
  void
  MeshRefinement<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh refinement");
    prm.declare_entry("Adaptive",
                      "false",
                      Patterns::Bool(),
                      "Refine the mesh at the biofilm interface and coarsen it "
                      "away from it, at the start and every Interval steps.");
    prm.declare_entry("Interval",
                      "10",
                      Patterns::Integer(1),
                      "Time steps between mesh adaptations.");
    prm.declare_entry("Minimum level",
                      "3",
                      Patterns::Integer(0, 12),
                      "Coarsest refinement level (global refinements of the "
                      "coarse mesh); <= Geometry/Initial global refinement.");
    prm.declare_entry("Maximum level",
                      "7",
                      Patterns::Integer(0, 12),
                      "Finest refinement level; >= Geometry/Initial global "
                      "refinement. 7 gives Δx = 1/128 at the interface.");
    prm.declare_entry("Indicator",
                      "biofilm, velocity",
                      Patterns::MultipleSelection("interface|biofilm|velocity"),
                      "What the mesh resolves, one or more of: interface (φ "
                      "varies across the cell by more than Refinement "
                      "threshold), biofilm (the interface and the cells where "
                      "φ exceeds Refinement threshold: the elastic stress lives "
                      "there; both look at the detached fraction φ_d of "
                      "Detachment/Release as at φ), velocity (Kelly's indicator of the velocity error "
                      "exceeds Velocity threshold × max|u|: the flow around the "
                      "biofilm and at the walls).");
    prm.declare_entry("Refinement threshold",
                      "0.005",
                      Patterns::Double(0),
                      "The φ threshold of the interface and biofilm indicators, "
                      "> 0. 0.005 is a twentieth of the biofilm's φ = 0.1; at "
                      "viscosity ratio 500 it already makes the viscosity 3.5 "
                      "times the water's.");
    prm.declare_entry("Velocity threshold",
                      "0.002",
                      Patterns::Double(0),
                      "The threshold of the velocity indicator, relative to "
                      "max|u|. > 0.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  MeshRefinement<dim>::Parameters::parse_parameters(ParameterHandler &prm,
                                   const unsigned int initial_level)
  {
    prm.enter_subsection("Mesh refinement");
    adaptive  = prm.get_bool("Adaptive");
    interval  = prm.get_integer("Interval");
    min_level = prm.get_integer("Minimum level");
    max_level = prm.get_integer("Maximum level");
    threshold = prm.get_double("Refinement threshold");
    const std::vector<std::string> indicators =
      Utilities::split_string_list(prm.get("Indicator"));
    const auto chosen = [&](const std::string &name) {
      return std::find(indicators.begin(), indicators.end(), name) != indicators.end();
    };
    interface_indicator = chosen("interface");
    biofilm_indicator   = chosen("biofilm");
    velocity_indicator  = chosen("velocity");
    velocity_threshold  = prm.get_double("Velocity threshold");
    prm.leave_subsection();
    if (!adaptive)
      return;
    check_input(interface_indicator || biofilm_indicator || velocity_indicator,
                "Mesh refinement/Indicator must name one or more of interface, "
                "biofilm, velocity; got nothing");
    check_input(threshold > 0, "Mesh refinement/Refinement threshold must be > 0, got 0");
    check_input(velocity_threshold > 0,
                "Mesh refinement/Velocity threshold must be > 0, got 0");
    check_input(min_level <= initial_level && initial_level <= max_level,
                "Mesh refinement/Minimum level (" + std::to_string(min_level) +
                  ") <= Geometry/Initial global refinement (" +
                  std::to_string(initial_level) +
                  ") <= Mesh refinement/Maximum level (" +
                  std::to_string(max_level) + ") must hold");
  }


  template <int dim>
  MeshRefinement<dim>::MeshRefinement(const Parameters &parameters)
    : parameters(parameters)
  {}


  template <int dim>
  bool
  MeshRefinement<dim>::flag_cells(parallel::distributed::Triangulation<dim> &triangulation,
                             const VolumeFraction<dim> &volume_fraction,
                             const VolumeFraction<dim> *detached,
                             const StokesFlow<dim> & stokes,
                             const bool            coarsen,
                             const InitialInput *  input) const
  {
    // Velocity part: off before the first Stokes solve (u = 0).
    const double  max_velocity = parameters.velocity_indicator ? stokes.max_velocity() : 0;
    Vector<float> velocity_error;
    if (max_velocity > 0)
      velocity_error = stokes.velocity_error_indicator();

    const DoFHandler<dim> &dofs = volume_fraction.dof_handler();
    const Quadrature<dim>  nodes(dofs.get_fe().get_unit_support_points());
    FEValues<dim>          fe_values(dofs.get_fe(), nodes, update_values);
    std::vector<double>  phi, phi_detached(nodes.size());
    unsigned int         n_flagged = 0;
    // The φ indicators of one fraction's values in a cell, relative to
    // their threshold: its variation across the cell (interface), and
    // itself (biofilm).
    const auto fraction_need = [&](const std::vector<double> &values) {
      const auto [low, high] = std::minmax_element(values.begin(), values.end());
      double need = 0;
      if (parameters.interface_indicator)
        need = (*high - *low) / parameters.threshold;
      if (parameters.biofilm_indicator)
        need = std::max(
          {need, (*high - *low) / parameters.threshold, *high / parameters.threshold});
      return need;
    };
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          phi.resize(nodes.size());
          fe_values.get_function_values(volume_fraction.solution(), phi);
          if (input != nullptr)
            {
              // A grid of points at most input->spacing apart over the cell.
              const unsigned int n = std::min<unsigned int>(
                64, std::ceil(cell->minimum_vertex_distance() / input->spacing));
              const QIterated<dim> grid(QTrapezoid<1>(), std::max(n, 1u));
              for (const Point<dim> &unit : grid.get_points())
                phi.push_back(input->phi.value(
                  volume_fraction.mapping().transform_unit_to_real_cell(cell, unit)));
            }
          // Each measure relative to its threshold; the largest counts:
          // > 1 refine, < 1/4 coarsen. The detached fraction φ_d by its
          // own indicators, not those of φ + φ_d: a release leaves φ + φ_d
          // as it was, but fronts in both, each of which the transport
          // must resolve (doc/detachment.md).
          double need = fraction_need(phi);
          if (detached != nullptr)
            {
              fe_values.reinit(cell_of(detached->dof_handler(), cell));
              fe_values.get_function_values(detached->solution(), phi_detached);
              need = std::max(need, fraction_need(phi_detached));
            }
          if (max_velocity > 0)
            need = std::max(need,
                            velocity_error[cell->active_cell_index()] /
                              (parameters.velocity_threshold * max_velocity));
          const unsigned int level = cell->level();
          if (need > 1 && level < parameters.max_level)
            {
              cell->set_refine_flag();
              ++n_flagged;
            }
          else if (coarsen && need < 0.25 && level > parameters.min_level)
            {
              cell->set_coarsen_flag();
              ++n_flagged;
            }
        }
    return Utilities::MPI::sum(n_flagged, triangulation.get_communicator()) > 0;
  }

  VISCOFILM_INSTANTIATE(MeshRefinement)
} // namespace viscofilm
