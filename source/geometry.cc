#include <deal.II/grid/grid_generator.h>

#include <viscofilm/geometry.h>
#include <viscofilm/input.h>

#include <cmath>

namespace viscofilm
{
  void
  Geometry::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Lower left corner",
                      "0, 0",
                      Patterns::Anything(),
                      "Corner (x, y) of the channel at the inlet and the bottom "
                      "wall, in units of L0 (1 cm).");
    prm.declare_entry("Upper right corner",
                      "1, 1",
                      Patterns::Anything(),
                      "Corner (x, y) of the channel at the outlet and the top "
                      "wall. Must exceed the lower left corner in x and y.");
    prm.declare_entry("Initial global refinement",
                      "5",
                      Patterns::Integer(0, 12),
                      "Number of global refinements of the coarse mesh (square "
                      "cells of edge min(width, height)). 5 gives the thesis' "
                      "Δx = 1/32 on the unit square.");
    prm.leave_subsection();
  }


  void
  Geometry::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    lower_left =
      parse_point(prm.get("Lower left corner"), "Geometry/Lower left corner");
    upper_right =
      parse_point(prm.get("Upper right corner"), "Geometry/Upper right corner");
    initial_refinement = prm.get_integer("Initial global refinement");
    prm.leave_subsection();

    check_input(upper_right[0] > lower_left[0] &&
                  upper_right[1] > lower_left[1],
                "Geometry/Upper right corner must exceed Geometry/Lower left "
                "corner in both x and y");
    const auto n = coarse_repetitions();
    check_input(n[0] <= 64 && n[1] <= 64,
                "Geometry: the channel's aspect ratio must be at most 64");
  }


  std::array<unsigned int, 2>
  Geometry::coarse_repetitions() const
  {
    const Tensor<1, 2> extent = upper_right - lower_left;
    const double       edge   = std::min(extent[0], extent[1]);
    return {{static_cast<unsigned int>(std::max(1.0, std::round(extent[0] / edge))),
             static_cast<unsigned int>(std::max(1.0, std::round(extent[1] / edge)))}};
  }


  void
  Geometry::make_coarse_grid(parallel::distributed::Triangulation<2> &triangulation) const
  {
    const auto n = coarse_repetitions();
    GridGenerator::subdivided_hyper_rectangle(
      triangulation, {n[0], n[1]}, lower_left, upper_right, /*colorize*/ true);
  }


  void
  Geometry::make_grid(parallel::distributed::Triangulation<2> &triangulation) const
  {
    make_coarse_grid(triangulation);
    triangulation.refine_global(initial_refinement);
  }


  double
  Geometry::initial_cell_size() const
  {
    const Tensor<1, 2> extent = upper_right - lower_left;
    return extent[0] / coarse_repetitions()[0] / std::pow(2.0, initial_refinement);
  }


  bool
  Geometry::contains(const Point<2> &p) const
  {
    const double tol = 1e-12 * (upper_right - lower_left).norm();
    return p[0] >= lower_left[0] - tol && p[0] <= upper_right[0] + tol &&
           p[1] >= lower_left[1] - tol && p[1] <= upper_right[1] + tol;
  }


  double
  Geometry::area() const
  {
    const Tensor<1, 2> extent = upper_right - lower_left;
    return extent[0] * extent[1];
  }
} // namespace viscofilm
