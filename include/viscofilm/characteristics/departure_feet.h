// Departure feet of the semi-Lagrangian stress update (MODEL.md §3 step 1,
// thesis eq. 3.34-3.38) and the evaluation of fields at arbitrary points of
// the distributed mesh, in any cell on any MPI rank.
#ifndef viscofilm_departure_feet_h
#define viscofilm_departure_feet_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/trilinos_parallel_block_vector.h>

#include <deal.II/matrix_free/fe_point_evaluation.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/core/reporter.h>

#include <array>
#include <functional>
#include <optional>
#include <memory>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// What one cell computes at the reference points of the requested points
  /// that lie in it (one value of n numbers per point).
  template <int dim, int n>
  using CellEvaluation =
    std::function<void(const typename Triangulation<dim>::active_cell_iterator &cell,
                       const ArrayView<const Point<dim>> &         unit_points,
                       const ArrayView<std::array<double, n>> &  values)>;

  /**
   * Fields at arbitrary points of the distributed mesh. Each point comes with
   * a hint, a cell near it (the cell of the node or quadrature point it was
   * traced back from); the point is found by walking from the hint across
   * faces, O(cells walked) per point. A point in a locally owned cell, or in
   * ghost cells only, is evaluated on this rank (ghosted vectors hold the
   * values of ghost cells); the others go to
   * Utilities::MPI::RemotePointEvaluation, which finds them on the rank that
   * owns them. (deal.II 9.4's search alone costs O(all cells) per point on a
   * cell face, which made the feet 70 % of a time step at Δx = 1/256.) A
   * point on a face or vertex takes the value of the first cell on the walk
   * that holds it, i.e. of the hint cell if it holds the point: a
   * discontinuous field is taken from the hint's side, never averaged. Only
   * a point beyond the ghost layer that RemotePointEvaluation finds on a
   * face gets the mean over the cells sharing it.
   *
   * A point is reached along the segment from an origin in the hint cell
   * (the node it was traced back from): a segment that leaves the mesh
   * through a boundary face is cut there (the point becomes the crossing),
   * one that leaves through a periodic face continues on the partner side,
   * translated by the period (the point becomes its periodic image in the
   * mesh). No description of the domain is needed, only its cells. A
   * segment that leaves the rank's cells (beyond the ghost layer) and then
   * the mesh cannot be cut: its point becomes the segment's point next to
   * the boundary, found by bisection (reinit()).
   */
  template <int dim>
  class PointEvaluator
  {
  public:
    /// A walk crosses at most @p max_walk_steps cells before the point is
    /// left to the global search.
    PointEvaluator(const parallel::distributed::Triangulation<dim> &triangulation,
                   const Mapping<dim> &                           mapping,
                   const unsigned int                             max_walk_steps);

    /// The map from the reference cell the points are located with.
    const Mapping<dim> &
    mapping() const;

    /// Where the segment from a point in a cell towards a target ends.
    struct Trace
    {
      /// The cell reached, and the point's reference coordinates there.
      typename Triangulation<dim>::active_cell_iterator cell;
      Point<dim>                               unit_point;
      /// The target, translated across the periodic faces crossed, or the
      /// crossing with the boundary face @p cut_face of @p cell.
      Point<dim> point;
      unsigned int cut_face = numbers::invalid_unsigned_int;
      /// False: an artificial cell or the step limit stopped the walk; then
      /// @p point is the target translated across the periodic faces so far,
      /// and @p inside the last point of the walk, which lies in the domain.
      bool       found = false;
      Point<dim> inside;
    };

    /// Walk from @p cell, which holds @p from, along the segment to @p to,
    /// cell to cell across the faces it crosses (exit face from the
    /// reference coordinates).
    Trace
    trace(typename Triangulation<dim>::active_cell_iterator cell,
          const Point<dim> &                       from,
          const Point<dim> &                       to) const;

    /// Locate @p points, each reached along the segment from @p origins in
    /// its cell of @p hints (see trace()); @p hints become the cells found,
    /// good hints for points near these. Collective.
    void
    reinit(const std::vector<Point<dim>> &                         origins,
           const std::vector<Point<dim>> &                         points,
           std::vector<typename Triangulation<dim>::active_cell_iterator> &hints);

    /// The points of the last reinit() where they were evaluated: cut at
    /// (or, beyond the ghost layer, bisected to) the boundary, translated
    /// across periodic faces.
    const std::vector<Point<dim>> &
    located_points() const;

    /// The values of @p evaluate_cell at the points of the last reinit().
    /// Collective; throws if a point lies in no cell of the mesh.
    template <int n>
    std::vector<std::array<double, n>>
    evaluate(const CellEvaluation<dim, n> &evaluate_cell) const;

  private:
    /// The domain's bounding box (of every rank's cells, through the
    /// mapping).
    BoundingBox<dim>
    domain_box() const;

    /// The point of the segment @p from → @p to just before it leaves @p
    /// box; @p to if that is in @p box (its faces included) or @p from is
    /// not.
    static Point<dim>
    clip(const BoundingBox<dim> &box, const Point<dim> &from, const Point<dim> &to);

    struct LocalPoint
    {
      typename Triangulation<dim>::active_cell_iterator cell;
      Point<dim>                               unit_point;
      unsigned int                           point; // index in reinit()'s points
    };

    const parallel::distributed::Triangulation<dim> &triangulation;
    const Mapping<dim> &                           cell_mapping;
    const unsigned int                             max_walk_steps;
    std::vector<LocalPoint>                        local; // sorted by cell
    std::vector<unsigned int>                      remote_points;
    bool                                           any_remote = false; // on any rank
    std::unique_ptr<Utilities::MPI::RemotePointEvaluation<dim>> remote;
    unsigned int                                   n_points = 0;
    std::vector<Point<dim>>                        located;
  };

  /// u and ∇u at a point: u_d at [d], ∂u_d/∂x_e at [dim + dim d + e].
  template <int dim>
  constexpr unsigned int n_velocity_values = dim + dim * dim;

  /// u and ∇u (n_velocity_values<dim>) at the points of @p points, from the
  /// velocity part of a (ghosted) Stokes solution.
  template <int dim>
  std::vector<std::array<double, n_velocity_values<dim>>>
  evaluate_velocity(const PointEvaluator<dim> &                    points,
                    const DoFHandler<dim> &                     stokes_dofs,
                    const TrilinosWrappers::MPI::BlockVector &stokes_solution);

  template <int dim>
  class DepartureFeet : public Reporter<dim>
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      double       newton_tolerance      = 1e-10;
      unsigned int max_newton_iterations = 20;
      unsigned int max_walk_steps        = 64;
    };

    /// Per time step, summed over all ranks and all point sets.
    struct Statistics
    {
      unsigned int max_newton_iterations = 0;
      unsigned int n_left_cell           = 0; // foot outside the cells around x
      unsigned int n_left_domain         = 0; // foot cut at the boundary
      unsigned int n_substepped          = 0; // traced by sub-steps, not Newton
    };

    DepartureFeet(const Parameters &                             parameters,
                  const parallel::distributed::Triangulation<dim> &triangulation,
                  const Mapping<dim> &                           mapping);

    /**
     * The feet y of the points x: y = x − k u((x + y)/2), the implicit
     * midpoint rule along the characteristic, solved by Newton's method
     * (∇G = I + (k/2) ∇u) from y = x with a backtracking line search on
     * |G|; where it fails (no root, or stuck where ∇u jumps between cells)
     * within `Maximum Newton iterations`, the foot is traced by explicit
     * midpoint sub-steps (trace_by_substeps()). @p cells are the cells the points
     * came from: a foot in (or on the boundary of) its point's cell is
     * evaluated there, upwind (and the feet that left them are counted). u is the velocity part
     * of @p stokes_solution (ghosted) on @p stokes_dofs. A characteristic
     * that leaves the mesh is cut where the segment x–y crosses the
     * boundary (midpoints too), and wraps round across periodic faces
     * (PointEvaluator::trace()). at_feet() then evaluates fields at the
     * feet, inflow_boundaries() says which feet lie on an inflow boundary.
     * Returns the feet (cut, wrapped into the mesh). Collective.
     */
    std::vector<Point<dim>>
    compute(const std::vector<Point<dim>> &                              points,
            const std::vector<typename Triangulation<dim>::active_cell_iterator> &cells,
            const DoFHandler<dim> &                                 stokes_dofs,
            const TrilinosWrappers::MPI::BlockVector &            stokes_solution,
            const double                                          time_step);

    /// Located at the feet of the last compute().
    const PointEvaluator<dim> &
    at_feet() const;

    /// Per point of the last compute(): the boundary id where its
    /// characteristic enters the domain (cut on a boundary face where
    /// enters() holds), or numbers::invalid_boundary_id. A foot cut on a
    /// wall that the flow follows is no inflow: it keeps the interior value
    /// at the cut.
    const std::vector<types::boundary_id> &
    inflow_boundaries() const;

    /// statistics.csv: the Statistics since the last reset_statistics()
    /// (feet_newton_iterations, feet_left_cell, feet_left_domain,
    /// feet_substepped).
    void
    add_statistics(CsvFile &statistics, const double time) const override;

    void
    reset_statistics();

  private:
    /// Where the segment from @p x in @p cell to @p foot leaves the mesh by
    /// more than @p tolerance: @p foot becomes the crossing, @p cut its
    /// trace, and true.
    bool
    cut_at_boundary(const typename Triangulation<dim>::active_cell_iterator &cell,
                    const Point<dim> &                                       x,
                    double                                                   tolerance,
                    Point<dim> &                                             foot,
                    typename PointEvaluator<dim>::Trace &                    cut) const;

    /// Does the flow enter the domain at @p cut (u·n < −inflow_threshold
    /// @p max_speed, and on a curved face at an angle larger than the
    /// face's turning squared)? @p velocity and @p face_normals: the
    /// caller's evaluator of u on @p stokes_dofs and face values with
    /// normals, built once per compute().
    bool
    enters(const typename PointEvaluator<dim>::Trace &cut,
           const DoFHandler<dim> &                    stokes_dofs,
           const TrilinosWrappers::MPI::BlockVector & stokes_solution,
           double                                     max_speed,
           FEPointEvaluation<dim, dim> &              velocity,
           FEFaceValues<dim> &                        face_normals) const;

    /// The feet of the points @p unsolved (indices into @p points) by
    /// explicit midpoint (RK2) sub-steps along the characteristic, as many
    /// as h |∇u| ≤ 1/2 needs for the largest |∇u| in @p max_gradient (at
    /// most 64); cut at the boundary like the Newton iterates. Collective.
    void
    trace_by_substeps(std::vector<unsigned int>                                     unsolved,
                      const std::vector<double> &                                   max_gradient,
                      const std::vector<Point<dim>> &                               points,
                      const std::vector<typename Triangulation<dim>::active_cell_iterator> &cells,
                      const DoFHandler<dim> &                                       stokes_dofs,
                      const TrilinosWrappers::MPI::BlockVector &                    stokes_solution,
                      double                                                        time_step,
                      double                                                        tolerance,
                      std::vector<Point<dim>> &                                     feet,
                      std::vector<typename PointEvaluator<dim>::Trace> &            cuts,
                      unsigned int &                                                n_left_domain);

    /// Is @p y in a cell sharing the point @p x of @p cell?
    bool
    inside_patch(const typename Triangulation<dim>::active_cell_iterator &cell,
                 const Point<dim> &                              x,
                 const Point<dim> &                              y) const;

    const Parameters &                             parameters;
    const parallel::distributed::Triangulation<dim> &triangulation;
    PointEvaluator<dim>                            evaluator; // midpoints, then feet
    Statistics                                     accumulated;
    std::vector<types::boundary_id>                inflow;
  };
} // namespace viscofilm

#endif
