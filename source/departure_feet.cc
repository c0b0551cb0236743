#include <deal.II/base/mpi.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/matrix_free/fe_point_evaluation.h>

#include <viscofilm/departure_feet.h>
#include <viscofilm/input.h>

#include <algorithm>
#include <optional>
#include <sstream>

namespace viscofilm
{
  namespace
  {
    // Reference-cell distance within which a point counts as in a cell: the
    // default of RemotePointEvaluation, so that both paths agree.
    constexpr double unit_tolerance = 1e-6;

    const Mapping<2> &
    mapping()
    {
      return StaticMappingQ1<2>::mapping;
    }
  } // namespace


  PointEvaluator::PointEvaluator(
    const parallel::distributed::Triangulation<2> &triangulation,
    const unsigned int                             max_walk_steps)
    : triangulation(triangulation)
    , max_walk_steps(max_walk_steps)
    , remote(unit_tolerance)
  {}


  std::optional<std::pair<Triangulation<2>::active_cell_iterator, Point<2>>>
  PointEvaluator::walk(Triangulation<2>::active_cell_iterator cell,
                       const Point<2> &                       p) const
  {
    // Feet lie a few cells from their nodes; a longer walk is left to the
    // global search.
    for (unsigned int step = 0; step < max_walk_steps && !cell->is_artificial(); ++step)
      {
        const Point<2> unit = mapping().transform_real_to_unit_cell(cell, p);
        if (GeometryInfo<2>::distance_to_unit_cell(unit) < unit_tolerance)
          return std::make_pair(cell, unit);
        // Leave through the face p lies farthest beyond.
        unsigned int face   = 0;
        double       beyond = 0;
        for (unsigned int d = 0; d < 2; ++d)
          {
            if (-unit[d] > beyond)
              {
                beyond = -unit[d];
                face   = 2 * d;
              }
            if (unit[d] - 1 > beyond)
              {
                beyond = unit[d] - 1;
                face   = 2 * d + 1;
              }
          }
        if (cell->at_boundary(face))
          break;
        Triangulation<2>::cell_iterator next = cell->neighbor(face);
        while (next->has_children())
          {
            unsigned int nearest = 0;
            for (unsigned int c = 1; c < next->n_children(); ++c)
              if (next->child(c)->center().distance(p) <
                  next->child(nearest)->center().distance(p))
                nearest = c;
            next = next->child(nearest);
          }
        cell = next;
      }
    return std::nullopt;
  }


  void
  PointEvaluator::reinit(const std::vector<Point<2>> &                        points,
                         std::vector<Triangulation<2>::active_cell_iterator> &hints)
  {
    AssertDimension(points.size(), hints.size());
    n_points = points.size();
    local.clear();
    remote_points.clear();
    for (unsigned int i = 0; i < points.size(); ++i)
      if (const auto found = walk(hints[i], points[i]))
        {
          // The first cell on the walk that holds the point, even if the
          // point is on a face it shares: a discontinuous field is taken
          // from the side the walk came from, not averaged across the face.
          hints[i] = found->first;
          local.push_back({found->first, found->second, i});
        }
      else
        remote_points.push_back(i);
    std::sort(local.begin(), local.end(), [](const LocalPoint &a, const LocalPoint &b) {
      return a.cell < b.cell;
    });

    const MPI_Comm comm = triangulation.get_communicator();
    any_remote = Utilities::MPI::max(remote_points.empty() ? 0u : 1u, comm) > 0;
    if (any_remote)
      {
        std::vector<Point<2>> remote_locations;
        for (const unsigned int i : remote_points)
          remote_locations.push_back(points[i]);
        remote.reinit(remote_locations, triangulation, mapping());
      }
  }


  template <int n>
  std::vector<std::array<double, n>>
  PointEvaluator::evaluate(const CellEvaluation<n> &evaluate_cell) const
  {
    using Value = std::array<double, n>;
    std::vector<Value>    result(n_points, Value{});
    std::vector<Point<2>> unit_points;
    std::vector<Value>    values;
    for (auto begin = local.begin(); begin != local.end();)
      {
        auto end = begin;
        unit_points.clear();
        for (; end != local.end() && end->cell == begin->cell; ++end)
          unit_points.push_back(end->unit_point);
        values.resize(unit_points.size());
        evaluate_cell(begin->cell, make_array_view(unit_points), make_array_view(values));
        for (auto point = begin; point != end; ++point)
          result[point->point] = values[point - begin];
        begin = end;
      }
    if (!any_remote)
      return result;

    std::vector<Value> contributions, buffer;
    remote.template evaluate_and_process<Value>(
      contributions,
      buffer,
      [&](const ArrayView<Value> &values,
          const typename Utilities::MPI::RemotePointEvaluation<2>::CellData &data) {
        for (unsigned int c = 0; c < data.cells.size(); ++c)
          {
            const Triangulation<2>::active_cell_iterator cell(&triangulation,
                                                              data.cells[c].first,
                                                              data.cells[c].second);
            const unsigned int begin = data.reference_point_ptrs[c];
            const unsigned int count = data.reference_point_ptrs[c + 1] - begin;
            evaluate_cell(cell,
                          ArrayView<const Point<2>>(
                            data.reference_point_values.data() + begin, count),
                          ArrayView<Value>(values.data() + begin, count));
          }
      });
    const std::vector<unsigned int> &ptrs = remote.get_point_ptrs();
    for (unsigned int j = 0; j < remote_points.size(); ++j)
      {
        const unsigned int count = ptrs[j + 1] - ptrs[j];
        AssertThrow(count > 0,
                    ExcMessage("a point needed by the semi-Lagrangian scheme "
                               "lies in no cell of the mesh"));
        Value &mean = result[remote_points[j]];
        for (unsigned int c = ptrs[j]; c < ptrs[j + 1]; ++c)
          for (unsigned int k = 0; k < n; ++k)
            mean[k] += contributions[c][k] / count;
      }
    return result;
  }

  template std::vector<std::array<double, 3>>
  PointEvaluator::evaluate<3>(const CellEvaluation<3> &) const;
  template std::vector<std::array<double, 4>>
  PointEvaluator::evaluate<4>(const CellEvaluation<4> &) const;
  template std::vector<std::array<double, 6>>
  PointEvaluator::evaluate<6>(const CellEvaluation<6> &) const;


  unsigned int
  PointEvaluator::n_remote_points() const
  {
    return remote_points.size();
  }


  std::vector<std::array<double, 6>>
  evaluate_velocity(const PointEvaluator &                    points,
                    const DoFHandler<2> &                     stokes_dofs,
                    const TrilinosWrappers::MPI::BlockVector &stokes_solution)
  {
    FEPointEvaluation<2, 2> velocity(mapping(),
                                     stokes_dofs.get_fe(),
                                     update_values | update_gradients,
                                     0);
    std::vector<double> dof_values(stokes_dofs.get_fe().n_dofs_per_cell());
    return points.evaluate<6>(
      [&](const Triangulation<2>::active_cell_iterator &cell,
          const ArrayView<const Point<2>> &             unit_points,
          const ArrayView<std::array<double, 6>> &      values) {
        const DoFHandler<2>::active_cell_iterator dof_cell(&stokes_dofs.get_triangulation(),
                                                           cell->level(),
                                                           cell->index(),
                                                           &stokes_dofs);
        dof_cell->get_dof_values(stokes_solution, dof_values.begin(), dof_values.end());
        velocity.reinit(cell, unit_points);
        velocity.evaluate(dof_values,
                          EvaluationFlags::values | EvaluationFlags::gradients);
        for (unsigned int q = 0; q < unit_points.size(); ++q)
          {
            const Tensor<1, 2>               u    = velocity.get_value(q);
            const Tensor<1, 2, Tensor<1, 2>> grad = velocity.get_gradient(q);
            values[q] = {{u[0], u[1], grad[0][0], grad[0][1], grad[1][0], grad[1][1]}};
          }
      });
  }


  void
  DepartureFeet::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Departure feet");
    prm.declare_entry("Newton tolerance",
                      "1e-10",
                      Patterns::Double(0),
                      "Newton's method for the implicit midpoint rule stops when "
                      "|y − x + k u((x+y)/2)| is below this times the smallest "
                      "cell size. > 0.");
    prm.declare_entry("Maximum Newton iterations",
                      "20",
                      Patterns::Integer(1, 1000),
                      "A foot not found within this many Newton iterations "
                      "stops the run with the point and its residual.");
    prm.declare_entry("Maximum walk steps",
                      "64",
                      Patterns::Integer(1),
                      "A point (a midpoint or a foot) is searched by walking "
                      "across at most this many cells from its node's cell; "
                      "one not reached, or behind the ghost layer, is found by "
                      "deal.II's global search instead (O(cells) per point on "
                      "a face, and a point found on a face there gets the mean "
                      "of the cells sharing it). Raise it for feet more than "
                      "this many cells away (CFL numbers far above 1).");
    prm.leave_subsection();
  }


  void
  DepartureFeet::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Departure feet");
    newton_tolerance      = prm.get_double("Newton tolerance");
    max_newton_iterations = prm.get_integer("Maximum Newton iterations");
    max_walk_steps        = prm.get_integer("Maximum walk steps");
    prm.leave_subsection();
    check_input(newton_tolerance > 0,
                "Departure feet/Newton tolerance must be > 0, got 0");
  }


  DepartureFeet::DepartureFeet(
    const Parameters &                             parameters,
    const Geometry &                               geometry,
    const parallel::distributed::Triangulation<2> &triangulation)
    : parameters(parameters)
    , geometry(geometry)
    , triangulation(triangulation)
    , evaluator(triangulation, parameters.max_walk_steps)
  {}


  bool
  DepartureFeet::inside_patch(const Triangulation<2>::active_cell_iterator &cell,
                              const Point<2> &                              x,
                              const Point<2> &                              y) const
  {
    // The cell's box, widened by one cell across each face x lies on: the
    // patch of cells sharing x on our rectangular meshes.
    const BoundingBox<2> box   = cell->bounding_box();
    Point<2>             lower = box.get_boundary_points().first;
    Point<2>             upper = box.get_boundary_points().second;
    for (unsigned int d = 0; d < 2; ++d)
      {
        const double width = upper[d] - lower[d];
        const double tol   = 1e-10 * width;
        const bool   on_lower = std::abs(x[d] - lower[d]) < tol;
        const bool   on_upper = std::abs(x[d] - upper[d]) < tol;
        if (on_lower)
          lower[d] -= width;
        if (on_upper)
          upper[d] += width;
        if (y[d] < lower[d] - tol || y[d] > upper[d] + tol)
          return false;
      }
    return true;
  }


  Point<2>
  DepartureFeet::project_into_domain(const Point<2> &p) const
  {
    Point<2> q;
    for (unsigned int d = 0; d < 2; ++d)
      q[d] = std::clamp(p[d], geometry.lower_left[d], geometry.upper_right[d]);
    return q;
  }


  std::vector<Point<2>>
  DepartureFeet::compute(
    const std::vector<Point<2>> &                              points,
    const std::vector<Triangulation<2>::active_cell_iterator> &cells,
    const DoFHandler<2> &                                      stokes_dofs,
    const TrilinosWrappers::MPI::BlockVector &                 stokes_solution,
    const double                                               time_step)
  {
    const MPI_Comm comm      = triangulation.get_communicator();
    const double   tolerance =
      parameters.newton_tolerance *
      GridTools::minimal_cell_diameter(triangulation) / std::sqrt(2.0);

    std::vector<Point<2>>                               feet(points);
    std::vector<Triangulation<2>::active_cell_iterator> hints(cells);
    std::vector<unsigned int>                           active(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      active[i] = i;

    unsigned int                             iteration = 0;
    unsigned int                             n_left_domain = 0;
    while (Utilities::MPI::max(static_cast<unsigned int>(active.size()), comm) > 0)
      {
        AssertThrow(
          iteration < parameters.max_newton_iterations,
          ExcMessage([&]() {
            std::ostringstream message;
            message << "the departure foot of " << active.size()
                    << " point(s) on this rank was not found in "
                    << parameters.max_newton_iterations
                    << " Newton iterations (Departure feet/Maximum Newton "
                       "iterations)";
            if (!active.empty())
              message << ", e.g. of (" << points[active[0]] << "), last iterate ("
                      << feet[active[0]] << ")";
            return message.str();
          }()));
        ++iteration;

        std::vector<Point<2>>                               midpoints(active.size());
        std::vector<Triangulation<2>::active_cell_iterator> midpoint_cells(active.size());
        for (unsigned int j = 0; j < active.size(); ++j)
          {
            midpoints[j] = project_into_domain(
              Point<2>(0.5 * (points[active[j]] + feet[active[j]])));
            midpoint_cells[j] = hints[active[j]];
          }
        evaluator.reinit(midpoints, midpoint_cells);
        const auto values = evaluate_velocity(evaluator, stokes_dofs, stokes_solution);
        for (unsigned int j = 0; j < active.size(); ++j)
          hints[active[j]] = midpoint_cells[j];

        std::vector<unsigned int> still_active;
        for (unsigned int j = 0; j < active.size(); ++j)
          {
            const unsigned int  i = active[j];
            const auto &        v = values[j];
            const Tensor<1, 2>  G = feet[i] - points[i] +
                                   time_step * Tensor<1, 2>({v[0], v[1]});
            if (G.norm() <= tolerance)
              continue;
            Tensor<2, 2> jacobian;
            jacobian[0][0] = 1 + 0.5 * time_step * v[2];
            jacobian[0][1] = 0.5 * time_step * v[3];
            jacobian[1][0] = 0.5 * time_step * v[4];
            jacobian[1][1] = 1 + 0.5 * time_step * v[5];
            const Point<2> next = feet[i] - invert(jacobian) * G;
            feet[i]             = project_into_domain(next);
            if (feet[i].distance(next) > tolerance)
              ++n_left_domain; // the characteristic enters through the boundary
            else
              still_active.push_back(i);
          }
        active.swap(still_active);
      }

    // Walk to each foot from its point's own cell: a foot on that cell's
    // boundary (a stagnant node's) takes that cell's values (upwind).
    std::vector<Triangulation<2>::active_cell_iterator> own_cells(cells);
    evaluator.reinit(feet, own_cells);

    unsigned int n_left_cell = 0;
    for (unsigned int i = 0; i < points.size(); ++i)
      if (!inside_patch(cells[i], points[i], feet[i]))
        ++n_left_cell;

    accumulated.max_newton_iterations =
      std::max(accumulated.max_newton_iterations, iteration);
    accumulated.n_left_cell += Utilities::MPI::sum(n_left_cell, comm);
    accumulated.n_left_domain += Utilities::MPI::sum(n_left_domain, comm);
    return feet;
  }


  const PointEvaluator &
  DepartureFeet::at_feet() const
  {
    return evaluator;
  }


  const DepartureFeet::Statistics &
  DepartureFeet::statistics() const
  {
    return accumulated;
  }


  void
  DepartureFeet::reset_statistics()
  {
    accumulated = Statistics();
  }
} // namespace viscofilm
