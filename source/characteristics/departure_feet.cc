#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/matrix_free/fe_point_evaluation.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/core/input.h>
#include <viscofilm/postprocess/output.h>

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
    // The quadratic map of curved cells is not watertight at a hanging
    // face: the coarse cell's edge is one parabola, its refined neighbours'
    // are two, through points on the manifold, and the sliver between them
    // (O(h³), found 1.46 R from the cylinder's centre on a graded mesh)
    // lies in no cell. A point that no cell holds within unit_tolerance is
    // taken from a cell it lies within this distance of.
    constexpr double sliver_tolerance = 1e-2;
  } // namespace


  template <int dim>
  PointEvaluator<dim>::PointEvaluator(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const Mapping<dim> &                           mapping,
    const unsigned int                             max_walk_steps)
    : triangulation(triangulation)
    , cell_mapping(mapping)
    , max_walk_steps(max_walk_steps)
  {}


  template <int dim>
  const Mapping<dim> &
  PointEvaluator<dim>::mapping() const
  {
    return cell_mapping;
  }


  namespace
  {
    /// @p p in @p cell's reference coordinates, or nothing where the
    /// bilinear map has no inverse (far from a distorted cell).
    template <int dim>
    std::optional<Point<dim>>
    unit_point(const Mapping<dim> &                                mapping,
               const typename Triangulation<dim>::cell_iterator &cell,
               const Point<dim> &                                 p)
    {
      try
        {
          return mapping.transform_real_to_unit_cell(cell, p);
        }
      catch (const typename Mapping<dim>::ExcTransformationFailed &)
        {
          return std::nullopt;
        }
    }
  } // namespace


  template <int dim>
  typename PointEvaluator<dim>::Trace
  PointEvaluator<dim>::trace(typename Triangulation<dim>::active_cell_iterator cell,
                        const Point<dim> &                       from,
                        const Point<dim> &                       to) const
  {
    // Feet lie a few cells from their nodes; a longer walk is left to the
    // global search.
    Point<dim> a = from, b = to; // the segment, in the frame of cell
    for (unsigned int step = 0; step < max_walk_steps && !cell->is_artificial(); ++step)
      {
        std::optional<Point<dim>> mapped_b = unit_point(cell_mapping, cell, b);
        if (mapped_b &&
            GeometryInfo<dim>::distance_to_unit_cell(*mapped_b) < unit_tolerance)
          return {cell, *mapped_b, b, numbers::invalid_unsigned_int, true, {}};
        // Where b is too far from a distorted cell for the inverse map,
        // aim at a point of the segment closer to a; if that point is still
        // in the cell, walk on from it.
        Point<dim> target = b;
        for (unsigned int halving = 0; !mapped_b && halving < 40; ++halving)
          {
            target   = a + 0.5 * (target - a);
            mapped_b = unit_point(cell_mapping, cell, target);
          }
        const std::optional<Point<dim>> mapped_a = unit_point(cell_mapping, cell, a);
        if (!mapped_b || !mapped_a)
          break;
        if (GeometryInfo<dim>::distance_to_unit_cell(*mapped_b) < unit_tolerance)
          {
            a = target;
            continue;
          }
        const Point<dim> unit_b = *mapped_b;
        // The face through which the segment a–b leaves the cell (in
        // reference coordinates: exact on parallelograms): the first one
        // b lies beyond, by more than the tolerance (a segment along a
        // wall, b beyond it by round-off, leaves through the far face).
        const Point<dim> unit_a = GeometryInfo<dim>::project_to_unit_cell(*mapped_a);
        unsigned int face = numbers::invalid_unsigned_int;
        double       exit = std::numeric_limits<double>::max();
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (unit_b[d] < -unit_tolerance && unit_a[d] / (unit_a[d] - unit_b[d]) < exit)
              {
                exit = unit_a[d] / (unit_a[d] - unit_b[d]);
                face = 2 * d;
              }
            if (unit_b[d] > 1 + unit_tolerance &&
                (1 - unit_a[d]) / (unit_b[d] - unit_a[d]) < exit)
              {
                exit = (1 - unit_a[d]) / (unit_b[d] - unit_a[d]);
                face = 2 * d + 1;
              }
          }
        if (face == numbers::invalid_unsigned_int) // b within round-off of the cell
          return {cell, unit_b, b, numbers::invalid_unsigned_int, true, {}};
        Point<dim> unit_exit = unit_a + exit * (unit_b - unit_a);
        unit_exit[face / 2]  = face % 2;
        unit_exit = GeometryInfo<dim>::project_to_unit_cell(unit_exit);
        const Point<dim> crossing =
          cell_mapping.transform_unit_to_real_cell(cell, unit_exit);

        typename Triangulation<dim>::cell_iterator next;
        if (cell->has_periodic_neighbor(face))
          {
            // Continue on the partner side, shifted by the period (face
            // centres of equal faces; a coarser partner's face is our
            // parent's).
            next = cell->periodic_neighbor(face);
            const Point<dim> here =
              cell->periodic_neighbor_is_coarser(face) ? cell->parent()->face(face)->center() :
                                                         cell->face(face)->center();
            const Tensor<1, dim> period =
              next->face(cell->periodic_neighbor_face_no(face))->center() - here;
            a = crossing + period;
            b += period;
          }
        else if (cell->at_boundary(face))
          return {cell, unit_exit, crossing, face, true, {}}; // the cut
        else
          {
            next = cell->neighbor(face);
            a    = crossing;
          }
        // Into the child of a refined neighbour that holds the crossing.
        while (next->has_children())
          {
            unsigned int nearest  = 0;
            double       distance = std::numeric_limits<double>::max();
            for (unsigned int c = 0; c < next->n_children(); ++c)
              {
                const std::optional<Point<dim>> unit = unit_point(cell_mapping, next->child(c), a);
                const double d = unit ? GeometryInfo<dim>::distance_to_unit_cell(*unit) :
                                        std::numeric_limits<double>::max();
                if (d < distance)
                  {
                    distance = d;
                    nearest  = c;
                  }
              }
            next = next->child(nearest);
          }
        cell = next;
      }
    Trace lost;
    lost.point  = b;
    lost.inside = a;
    return lost;
  }


  template <int dim>
  void
  PointEvaluator<dim>::reinit(const std::vector<Point<dim>> &                    origins,
                         const std::vector<Point<dim>> &                         points,
                         std::vector<typename Triangulation<dim>::active_cell_iterator> &hints)
  {
    AssertDimension(points.size(), hints.size());
    AssertDimension(points.size(), origins.size());
    n_points = points.size();
    local.clear();
    remote_points.clear();
    located.resize(n_points);
    std::vector<Point<dim>> inside; // per remote point: Trace::inside
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        const Trace found = trace(hints[i], origins[i], points[i]);
        located[i]        = found.point;
        if (found.found)
          {
            // The first cell on the walk that holds the point, even if the
            // point is on a face it shares: a discontinuous field is taken
            // from the side the walk came from, not averaged across the face.
            hints[i] = found.cell;
            local.push_back({found.cell, found.unit_point, i});
          }
        else
          {
            remote_points.push_back(i);
            inside.push_back(found.inside);
          }
      }
    std::sort(local.begin(), local.end(), [](const LocalPoint &a, const LocalPoint &b) {
      return a.cell < b.cell;
    });

    const MPI_Comm comm = triangulation.get_communicator();
    any_remote = Utilities::MPI::max(remote_points.empty() ? 0u : 1u, comm) > 0;
    if (any_remote)
      {
        std::vector<Point<dim>> remote_locations;
        for (const unsigned int i : remote_points)
          remote_locations.push_back(located[i]);
        // Whether every rank's points lie in cells; remote holds the search.
        const auto search = [&]() {
          for (const double tolerance : {unit_tolerance, sliver_tolerance})
            {
              remote = std::make_unique<Utilities::MPI::RemotePointEvaluation<dim>>(tolerance);
              remote->reinit(remote_locations, triangulation, cell_mapping);
              if (Utilities::MPI::max(remote->all_points_found() ? 0u : 1u, comm) == 0)
                return true;
            }
          return false;
        };
        // A target beyond the domain's bounding box (a foot that left this
        // rank's cells, then the domain through an inlet, at CFL > 1) is
        // moved back along its segment to just inside the box: deal.II
        // 9.4's search costs O(cells) for a point in no cell, ten times over
        // in the bisection below (2 ranks, CFL 40: 28 s a step instead of
        // 0.4 s), and where the domain is a box, its face is the boundary.
        const BoundingBox<dim> box = domain_box();
        for (unsigned int j = 0; j < remote_locations.size(); ++j)
          {
            remote_locations[j]     = clip(box, inside[j], remote_locations[j]);
            located[remote_points[j]] = remote_locations[j];
          }
        if (!search())
          {
            // A target outside the domain whose walk left this rank's cells
            // before it reached the boundary (a Newton iterate beyond a wall
            // at CFL > 1; with one rank the walk cuts it there): evaluated at
            // the point of its segment within |segment|/2^10 of the boundary,
            // by bisection between the walk's last point, in the domain, and
            // the target. Not a cut: the caller is not told, so such a foot
            // takes the field next to the boundary, not inflow data (at a
            // no-slip wall, where Newton iterates run off, the two agree).
            std::vector<Point<dim>> outside(remote_locations.size());
            std::vector<bool>       bisected(remote_locations.size());
            for (unsigned int round = 0; round <= 10; ++round)
              {
                const std::vector<unsigned int> ptrs = remote->get_point_ptrs();
                for (unsigned int j = 0; j < remote_locations.size(); ++j)
                  {
                    const bool found = ptrs[j + 1] > ptrs[j];
                    if (!bisected[j] && !found)
                      {
                        bisected[j] = true;
                        outside[j]  = remote_locations[j];
                      }
                    else if (bisected[j])
                      (found ? inside[j] : outside[j]) = remote_locations[j];
                    if (bisected[j])
                      remote_locations[j] =
                        round < 10 ? Point<dim>(0.5 * (inside[j] + outside[j])) : inside[j];
                  }
                search();
              }
            for (unsigned int j = 0; j < remote_locations.size(); ++j)
              located[remote_points[j]] = remote_locations[j];
          }
      }
  }


  template <int dim>
  BoundingBox<dim>
  PointEvaluator<dim>::domain_box() const
  {
    Point<dim> low, high;
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = std::numeric_limits<double>::max();
        high[d] = std::numeric_limits<double>::lowest();
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const BoundingBox<dim> cell_box = cell_mapping.get_bounding_box(cell);
          for (unsigned int d = 0; d < dim; ++d)
            {
              low[d]  = std::min(low[d], cell_box.lower_bound(d));
              high[d] = std::max(high[d], cell_box.upper_bound(d));
            }
        }
    const MPI_Comm comm = triangulation.get_communicator();
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = Utilities::MPI::min(low[d], comm);
        high[d] = Utilities::MPI::max(high[d], comm);
      }
    return BoundingBox<dim>(std::make_pair(low, high));
  }


  template <int dim>
  Point<dim>
  PointEvaluator<dim>::clip(const BoundingBox<dim> &box,
                            const Point<dim> &      from,
                            const Point<dim> &      to)
  {
    double fraction = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        if (to[d] < box.lower_bound(d))
          fraction = std::min(fraction, (box.lower_bound(d) - from[d]) / (to[d] - from[d]));
        if (to[d] > box.upper_bound(d))
          fraction = std::min(fraction, (box.upper_bound(d) - from[d]) / (to[d] - from[d]));
      }
    // From outside the box (a curved boundary's bulge beyond the mapping's
    // support points): no clip.
    if (fraction == 1 || !box.point_inside(from))
      return to;
    // Just inside: a point on a face is another O(cells) search.
    return from + std::max(fraction * (1 - 1e-9), 0.0) * (to - from);
  }


  template <int dim>
  const std::vector<Point<dim>> &
  PointEvaluator<dim>::located_points() const
  {
    return located;
  }


  template <int dim>
  template <int n>
  std::vector<std::array<double, n>>
  PointEvaluator<dim>::evaluate(const CellEvaluation<dim, n> &evaluate_cell) const
  {
    using Value = std::array<double, n>;
    std::vector<Value>    result(n_points, Value{});
    std::vector<Point<dim>> unit_points;
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
    remote->template evaluate_and_process<Value>(
      contributions,
      buffer,
      [&](const ArrayView<Value> &values,
          const typename Utilities::MPI::RemotePointEvaluation<dim>::CellData &data) {
        for (unsigned int c = 0; c < data.cells.size(); ++c)
          {
            const typename Triangulation<dim>::active_cell_iterator cell(&triangulation,
                                                              data.cells[c].first,
                                                              data.cells[c].second);
            const unsigned int begin = data.reference_point_ptrs[c];
            const unsigned int count = data.reference_point_ptrs[c + 1] - begin;
            evaluate_cell(cell,
                          ArrayView<const Point<dim>>(
                            data.reference_point_values.data() + begin, count),
                          ArrayView<Value>(values.data() + begin, count));
          }
      });
    const std::vector<unsigned int> &ptrs = remote->get_point_ptrs();
    for (unsigned int j = 0; j < remote_points.size(); ++j)
      {
        const unsigned int count = ptrs[j + 1] - ptrs[j];
        AssertThrow(count > 0, ExcMessage([&]() {
                      std::ostringstream message;
                      message << "a point needed by the semi-Lagrangian scheme, ("
                              << located[remote_points[j]]
                              << "), lies in no cell of the mesh";
                      return message.str();
                    }()));
        Value &mean = result[remote_points[j]];
        for (unsigned int c = ptrs[j]; c < ptrs[j + 1]; ++c)
          for (unsigned int k = 0; k < n; ++k)
            mean[k] += contributions[c][k] / count;
      }
    return result;
  }

  template <int dim>
  std::vector<std::array<double, n_velocity_values<dim>>>
  evaluate_velocity(const PointEvaluator<dim> &                    points,
                    const DoFHandler<dim> &                     stokes_dofs,
                    const TrilinosWrappers::MPI::BlockVector &stokes_solution)
  {
    FEPointEvaluation<dim, dim> velocity(points.mapping(),
                                     stokes_dofs.get_fe(),
                                     update_values | update_gradients,
                                     0);
    std::vector<double> dof_values(stokes_dofs.get_fe().n_dofs_per_cell());
    return points.template evaluate<n_velocity_values<dim>>(
      [&](const typename Triangulation<dim>::active_cell_iterator &cell,
          const ArrayView<const Point<dim>> &             unit_points,
          const ArrayView<std::array<double, n_velocity_values<dim>>> & values) {
        cell_of(stokes_dofs, cell)->get_dof_values(stokes_solution, dof_values.begin(), dof_values.end());
        velocity.reinit(cell, unit_points);
        velocity.evaluate(dof_values,
                          EvaluationFlags::values | EvaluationFlags::gradients);
        for (unsigned int q = 0; q < unit_points.size(); ++q)
          {
            const Tensor<1, dim>               u    = velocity.get_value(q);
            const Tensor<1, dim, Tensor<1, dim>> grad = velocity.get_gradient(q);
            for (unsigned int d = 0; d < dim; ++d)
              {
                values[q][d] = u[d];
                for (unsigned int e = 0; e < dim; ++e)
                  values[q][dim + dim * d + e] = grad[d][e];
              }
          }
      });
  }


  template <int dim>
  void
  DepartureFeet<dim>::Parameters::declare_parameters(ParameterHandler &prm)
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
                      "(each with a line search on the residual) is traced "
                      "by explicit midpoint sub-steps instead (statistics.csv: "
                      "feet_substepped).");
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


  template <int dim>
  void
  DepartureFeet<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Departure feet");
    newton_tolerance      = prm.get_double("Newton tolerance");
    max_newton_iterations = prm.get_integer("Maximum Newton iterations");
    max_walk_steps        = prm.get_integer("Maximum walk steps");
    prm.leave_subsection();
    check_input(newton_tolerance > 0,
                "Departure feet/Newton tolerance must be > 0, got 0");
  }


  template <int dim>
  DepartureFeet<dim>::DepartureFeet(
    const Parameters &                             parameters,
    const parallel::distributed::Triangulation<dim> &triangulation,
    const Mapping<dim> &                           mapping)
    : parameters(parameters)
    , triangulation(triangulation)
    , evaluator(triangulation, mapping, parameters.max_walk_steps)
  {}


  template <int dim>
  bool
  DepartureFeet<dim>::inside_patch(const typename Triangulation<dim>::active_cell_iterator &cell,
                              const Point<dim> &                              x,
                              const Point<dim> &                              y) const
  {
    // The cell's box, widened by one cell across each face x lies on: the
    // patch of cells sharing x on our rectangular meshes.
    const BoundingBox<dim> box   = cell->bounding_box();
    Point<dim>             lower = box.get_boundary_points().first;
    Point<dim>             upper = box.get_boundary_points().second;
    for (unsigned int d = 0; d < dim; ++d)
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


  template <int dim>
  bool
  DepartureFeet<dim>::cut_at_boundary(
    const typename Triangulation<dim>::active_cell_iterator &cell,
    const Point<dim> &                                       x,
    const double                                             tolerance,
    Point<dim> &                                             foot,
    typename PointEvaluator<dim>::Trace &                    cut) const
  {
    // Does the characteristic enter through the boundary?
    const typename PointEvaluator<dim>::Trace trace = evaluator.trace(cell, x, foot);
    if (!trace.found || trace.cut_face == numbers::invalid_unsigned_int ||
        trace.point.distance(foot) <= tolerance)
      return false;
    foot = trace.point;
    cut  = trace;
    return true;
  }


  template <int dim>
  bool
  DepartureFeet<dim>::enters(const typename PointEvaluator<dim>::Trace &cut,
                             const DoFHandler<dim> &                    stokes_dofs,
                             const TrilinosWrappers::MPI::BlockVector & stokes_solution,
                             const double                               max_speed,
                             FEPointEvaluation<dim, dim> &              velocity,
                             FEFaceValues<dim> &                        face_normals) const
  {
    std::vector<double> dof_values(stokes_dofs.get_fe().n_dofs_per_cell());
    cell_of(stokes_dofs, cut.cell)->get_dof_values(stokes_solution, dof_values.begin(), dof_values.end());
    velocity.reinit(cut.cell, make_array_view(&cut.unit_point, &cut.unit_point + 1));
    velocity.evaluate(dof_values, EvaluationFlags::values);
    // Outward normal of face f: ∓∇ξ_d, d = f/2, a row of J^{-1}.
    const unsigned int f = cut.cut_face;
    Tensor<1, dim>     normal;
    for (unsigned int e = 0; e < dim; ++e)
      normal[e] = velocity.inverse_jacobian(0)[f / 2][e];
    normal *= (f % 2 == 0 ? -1. : 1.) / normal.norm();
    // A flow that follows a curved wall crosses the wall's quadratic image
    // at small angles of either sign (the image's slope is off by θ³/32 on
    // a circle's arc of angle θ): a cut at an angle below the face's
    // turning squared (at least θ²/12) is no inflow. Zero on a plane face;
    // on a coarse curved face it also ignores a shallow real inflow, which
    // then keeps the interior value at the cut.
    face_normals.reinit(cut.cell, f);
    double turning = 0;
    for (const unsigned int q : face_normals.quadrature_point_indices())
      turning = std::max(turning, (face_normals.normal_vector(q) - normal).norm_square());
    const Tensor<1, dim> u = velocity.get_value(0);
    return u * normal < -std::max(inflow_threshold * max_speed, turning * u.norm());
  }


  template <int dim>
  void
  DepartureFeet<dim>::trace_by_substeps(
    std::vector<unsigned int>                                     unsolved,
    const std::vector<double> &                                   max_gradient,
    const std::vector<Point<dim>> &                               points,
    const std::vector<typename Triangulation<dim>::active_cell_iterator> &cells,
    const DoFHandler<dim> &                                       stokes_dofs,
    const TrilinosWrappers::MPI::BlockVector &                    stokes_solution,
    const double                                                  time_step,
    const double                                                  tolerance,
    std::vector<Point<dim>> &                                     feet,
    std::vector<typename PointEvaluator<dim>::Trace> &            cuts,
    unsigned int &                                                n_left_domain)
  {
    // Sub-steps h with h|∇u| ≤ 1/2 for the largest ∇u the Newton iterates
    // saw; one count on all ranks, whose evaluations are collective. At
    // most max_substeps: iterates that ran far off can see a ∇u that is not
    // on the characteristic (in the pillar example's breakdown one step's
    // sub-steps ran for minutes before this cap).
    constexpr unsigned int max_substeps = 64;
    unsigned int n_substeps = 0;
    for (const unsigned int i : unsolved)
      n_substeps = std::max(n_substeps, static_cast<unsigned int>(std::ceil(2 * time_step * max_gradient[i])));
    n_substeps = std::min(Utilities::MPI::max(n_substeps, triangulation.get_communicator()),
                          max_substeps);
    const double h = time_step / std::max(n_substeps, 1u);
    for (const unsigned int i : unsolved)
      feet[i] = points[i];
    // Each point is reached along the segment from its node, like the
    // Newton iterates: wrapped across periodic faces, cut at the boundary.
    std::vector<Tensor<1, dim>>                                    half_step;
    std::vector<Point<dim>>                                        origins, targets;
    std::vector<typename Triangulation<dim>::active_cell_iterator> hints;
    for (unsigned int evaluation = 0; evaluation < 2 * n_substeps; ++evaluation)
      {
        const bool midpoint = evaluation % 2 == 1;
        origins.resize(unsolved.size());
        targets.resize(unsolved.size());
        hints.resize(unsolved.size());
        for (unsigned int j = 0; j < unsolved.size(); ++j)
          {
            origins[j] = points[unsolved[j]];
            hints[j]   = cells[unsolved[j]];
            targets[j] = midpoint ? feet[unsolved[j]] - 0.5 * h * half_step[j] : feet[unsolved[j]];
          }
        evaluator.reinit(origins, targets, hints);
        const auto values = evaluate_velocity(evaluator, stokes_dofs, stokes_solution);
        half_step.resize(unsolved.size());
        std::vector<unsigned int> still_unsolved;
        for (unsigned int j = 0; j < unsolved.size(); ++j)
          {
            Tensor<1, dim> v;
            for (unsigned int d = 0; d < dim; ++d)
              v[d] = values[j][d];
            if (!midpoint)
              {
                half_step[j] = v;
                continue;
              }
            const unsigned int i = unsolved[j];
            feet[i] -= h * v;
            if (cut_at_boundary(cells[i], points[i], tolerance, feet[i], cuts[i]))
              ++n_left_domain;
            else
              still_unsolved.push_back(i);
          }
        if (midpoint)
          unsolved.swap(still_unsolved);
      }
  }


  template <int dim>
  std::vector<Point<dim>>
  DepartureFeet<dim>::compute(
    const std::vector<Point<dim>> &                              points,
    const std::vector<typename Triangulation<dim>::active_cell_iterator> &cells,
    const DoFHandler<dim> &                                      stokes_dofs,
    const TrilinosWrappers::MPI::BlockVector &                   stokes_solution,
    const double                                                 time_step)
  {
    const MPI_Comm comm      = triangulation.get_communicator();
    const double   tolerance = parameters.newton_tolerance *
                             GridTools::minimal_cell_diameter(triangulation) /
                             std::sqrt(double(dim));

    // The iterates y, unwrapped across periodic faces (the segment x–y is
    // the characteristic); a foot cut at the boundary stops there.
    std::vector<Point<dim>>                             feet(points);
    std::vector<typename PointEvaluator<dim>::Trace>    cuts(points.size());
    std::vector<typename Triangulation<dim>::active_cell_iterator> hints;
    std::vector<unsigned int>                           active(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      active[i] = i;
    // Newton with a backtracking line search on |G|: y = accepted +
    // length · step. Where k|∇u|/2 is O(1) and ∇u jumps between cells, full
    // steps cycle or run away; a trial that does not decrease |G| is halved
    // toward the last accepted iterate, and evaluated in the next round
    // with the other points. A full step that decreases |G| is accepted:
    // where undamped Newton converges monotonically nothing changes.
    std::vector<Point<dim>>     accepted(points);
    std::vector<double>         accepted_residual(points.size(), std::numeric_limits<double>::max());
    std::vector<Tensor<1, dim>> step(points.size());
    std::vector<double>         length(points.size(), 1.);
    std::vector<unsigned int>   n_steps(points.size(), 0);
    // A trial cut at the boundary becomes the foot only if |G| decreases
    // there too and the flow enters there: only then does the
    // characteristic come in through the boundary. An iterate that ran
    // away through a wall or an outflow is halved instead.
    std::vector<bool> cut_pending(points.size(), false);
    // The shortest trial step: a point whose |G| does not decrease along
    // its Newton direction even this close is stuck.
    constexpr double min_length = 1. / 1024;
    // Points Newton did not solve, and the largest |∇u| their iterates saw.
    std::vector<unsigned int> unsolved;
    std::vector<double>       max_gradient(points.size(), 0.);

    unsigned int iteration     = 0; // rounds: Newton steps and halvings
    unsigned int n_left_domain = 0;
    double       max_speed     = 0; // at the points (the first midpoints)
    // u at the cuts and the cut faces' normals, for the inflow test
    // (enters()): one evaluator each per call.
    FEPointEvaluation<dim, dim> velocity(evaluator.mapping(),
                                         stokes_dofs.get_fe(),
                                         update_values | update_gradients,
                                         0);
    FEFaceValues<dim>           face_normals(evaluator.mapping(),
                                   stokes_dofs.get_fe(),
                                   QGauss<dim - 1>(2),
                                   update_normal_vectors);
    while (Utilities::MPI::max(static_cast<unsigned int>(active.size()), comm) > 0)
      {
        ++iteration;

        // Midpoints along the segment from x's own cell: cut at the boundary
        // and wrapped like the feet.
        std::vector<Point<dim>> origins(active.size()), midpoints(active.size());
        hints.resize(active.size());
        for (unsigned int j = 0; j < active.size(); ++j)
          {
            origins[j]   = points[active[j]];
            midpoints[j] = Point<dim>(0.5 * (points[active[j]] + feet[active[j]]));
            hints[j]     = cells[active[j]];
          }
        evaluator.reinit(origins, midpoints, hints);
        const auto values = evaluate_velocity(evaluator, stokes_dofs, stokes_solution);
        if (iteration == 1)
          {
            for (const auto &v : values)
              {
                double square = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  square += v[d] * v[d];
                max_speed = std::max(max_speed, std::sqrt(square));
              }
            max_speed = Utilities::MPI::max(max_speed, comm);
          }

        std::vector<unsigned int> still_active;
        for (unsigned int j = 0; j < active.size(); ++j)
          {
            const unsigned int i = active[j];
            const auto &       v = values[j];
            Tensor<1, dim>     G = feet[i] - points[i];
            Tensor<2, dim>     jacobian; // ∇G = I + (k/2) ∇u
            double             gradient_square = 0; // |∇u|²
            for (unsigned int d = 0; d < dim; ++d)
              {
                G[d] += time_step * v[d];
                for (unsigned int e = 0; e < dim; ++e)
                  {
                    jacobian[d][e] = (d == e) + 0.5 * time_step * v[dim + dim * d + e];
                    gradient_square += v[dim + dim * d + e] * v[dim + dim * d + e];
                  }
              }
            const double residual = G.norm();
            max_gradient[i] = std::max(max_gradient[i], std::sqrt(gradient_square));
            if (cut_pending[i])
              {
                if ((residual < accepted_residual[i] || residual <= tolerance) &&
                    enters(cuts[i], stokes_dofs, stokes_solution, max_speed, velocity, face_normals))
                  {
                    ++n_left_domain;
                    continue;
                  }
                cut_pending[i] = false;
                cuts[i]        = {};
                length[i] /= 2;
              }
            else if (residual <= tolerance)
              continue;
            else if (residual < accepted_residual[i])
              {
                accepted[i]          = feet[i];
                accepted_residual[i] = residual;
                step[i]              = -(invert(jacobian) * G);
                length[i]            = 1;
                ++n_steps[i];
              }
            else
              length[i] /= 2;
            if (n_steps[i] > parameters.max_newton_iterations || length[i] < min_length)
              {
                unsolved.push_back(i);
                continue;
              }
            feet[i]        = accepted[i] + length[i] * step[i];
            cut_pending[i] = cut_at_boundary(cells[i], points[i], tolerance, feet[i], cuts[i]);
            still_active.push_back(i);
          }
        active.swap(still_active);
      }
    trace_by_substeps(unsolved, max_gradient, points, cells, stokes_dofs, stokes_solution,
                      time_step, tolerance, feet, cuts, n_left_domain);

    // Walk to each foot from its point's own cell: a foot on that cell's
    // boundary (a stagnant node's) takes that cell's values (upwind).
    std::vector<typename Triangulation<dim>::active_cell_iterator> own_cells(cells);
    evaluator.reinit(points, feet, own_cells);

    // Inflow where u·n < 0 at the cut, relative to the velocity scale as
    // VolumeFraction's inflow faces (inflow_threshold).
    inflow.assign(points.size(), numbers::invalid_boundary_id);
    for (unsigned int i = 0; i < points.size(); ++i)
      if (cuts[i].found && enters(cuts[i], stokes_dofs, stokes_solution, max_speed, velocity, face_normals))
        inflow[i] = cuts[i].cell->face(cuts[i].cut_face)->boundary_id();

    unsigned int n_left_cell = 0;
    for (unsigned int i = 0; i < points.size(); ++i)
      if (!inside_patch(cells[i], points[i], evaluator.located_points()[i]))
        ++n_left_cell;

    accumulated.max_newton_iterations =
      std::max(accumulated.max_newton_iterations, iteration);
    accumulated.n_left_cell += Utilities::MPI::sum(n_left_cell, comm);
    accumulated.n_left_domain += Utilities::MPI::sum(n_left_domain, comm);
    accumulated.n_substepped += Utilities::MPI::sum(static_cast<unsigned int>(unsolved.size()), comm);
    return evaluator.located_points();
  }


  template <int dim>
  const std::vector<types::boundary_id> &
  DepartureFeet<dim>::inflow_boundaries() const
  {
    return inflow;
  }


  template <int dim>
  const PointEvaluator<dim> &
  DepartureFeet<dim>::at_feet() const
  {
    return evaluator;
  }


  template <int dim>
  void
  DepartureFeet<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    statistics.set("feet_newton_iterations", accumulated.max_newton_iterations);
    statistics.set("feet_left_cell", accumulated.n_left_cell);
    statistics.set("feet_left_domain", accumulated.n_left_domain);
    statistics.set("feet_substepped", accumulated.n_substepped);
  }


  template <int dim>
  void
  DepartureFeet<dim>::reset_statistics()
  {
    accumulated = Statistics();
  }


  VISCOFILM_INSTANTIATE(PointEvaluator)
  VISCOFILM_INSTANTIATE(DepartureFeet)

  // PointEvaluator::evaluate for φ (1), VolumeFraction's feet (3),
  // ElasticStress' c and the evaluating rank, and u and ∇u.
#define INSTANTIATE(dim)                                                        \
  template std::vector<std::array<double, 1>>                                  \
  PointEvaluator<dim>::evaluate<1>(const CellEvaluation<dim, 1> &) const;      \
  template std::vector<std::array<double, 3>>                                  \
  PointEvaluator<dim>::evaluate<3>(const CellEvaluation<dim, 3> &) const;      \
  template std::vector<std::array<double, n_symmetric_components<dim> + 1>>    \
  PointEvaluator<dim>::evaluate<n_symmetric_components<dim> + 1>(              \
    const CellEvaluation<dim, n_symmetric_components<dim> + 1> &) const;       \
  template std::vector<std::array<double, n_velocity_values<dim>>>             \
  PointEvaluator<dim>::evaluate<n_velocity_values<dim>>(                       \
    const CellEvaluation<dim, n_velocity_values<dim>> &) const;                \
  template std::vector<std::array<double, n_velocity_values<dim>>>             \
  evaluate_velocity<dim>(const PointEvaluator<dim> &,                          \
                         const DoFHandler<dim> &,                              \
                         const TrilinosWrappers::MPI::BlockVector &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
