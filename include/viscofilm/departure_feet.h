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

#include <deal.II/lac/trilinos_parallel_block_vector.h>

#include <viscofilm/geometry.h>

#include <array>
#include <functional>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// What one cell computes at the reference points of the requested points
  /// that lie in it (one value of n numbers per point).
  template <int n>
  using CellEvaluation =
    std::function<void(const Triangulation<2>::active_cell_iterator &cell,
                       const ArrayView<const Point<2>> &         unit_points,
                       const ArrayView<std::array<double, n>> &  values)>;

  /**
   * Evaluate at the points given to @p cache.reinit(): each point is handled
   * by the rank owning a cell around it. A point on an edge or vertex shared
   * by several cells gets the mean of their values (so a discontinuous
   * gradient is averaged). Collective; throws if a point is not found.
   */
  template <int n>
  std::vector<std::array<double, n>>
  evaluate_at_points(const Utilities::MPI::RemotePointEvaluation<2> &cache,
                     const CellEvaluation<n> &                       evaluate_cell);

  /// u and ∇u (u, v, ∂u/∂x, ∂u/∂y, ∂v/∂x, ∂v/∂y) at the points of
  /// @p cache, from the velocity part of a (ghosted) Stokes solution.
  std::vector<std::array<double, 6>>
  evaluate_velocity(const Utilities::MPI::RemotePointEvaluation<2> &cache,
                    const DoFHandler<2> &                           stokes_dofs,
                    const TrilinosWrappers::MPI::BlockVector &      stokes_solution);

  class DepartureFeet
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
    };

    /// Per time step, summed over all ranks and all point sets.
    struct Statistics
    {
      unsigned int max_newton_iterations = 0;
      unsigned int n_left_cell           = 0; // foot outside the cells around x
      unsigned int n_left_domain         = 0; // foot moved to the boundary
    };

    DepartureFeet(const Parameters &                             parameters,
                  const Geometry &                               geometry,
                  const parallel::distributed::Triangulation<2> &triangulation);

    /**
     * The feet y of the points x: y = x − k u((x + y)/2), the implicit
     * midpoint rule along the characteristic, solved by Newton's method
     * (∇G = I + (k/2) ∇u) from y = x. @p cells are the cells the points
     * came from (to count the feet that left them). u is the velocity part
     * of @p stokes_solution (ghosted) on @p stokes_dofs. A foot outside the
     * channel is moved to the nearest boundary point. Collective.
     */
    std::vector<Point<2>>
    compute(const std::vector<Point<2>> &                         points,
            const std::vector<Triangulation<2>::active_cell_iterator> &cells,
            const DoFHandler<2> &                                 stokes_dofs,
            const TrilinosWrappers::MPI::BlockVector &            stokes_solution,
            const double                                          time_step);

    /// Statistics since the last reset_statistics().
    const Statistics &
    statistics() const;

    void
    reset_statistics();

  private:
    /// Is @p y in a cell sharing the point @p x of @p cell?
    bool
    inside_patch(const Triangulation<2>::active_cell_iterator &cell,
                 const Point<2> &                              x,
                 const Point<2> &                              y) const;

    /// The nearest point of the channel (the point itself if inside).
    Point<2>
    project_into_domain(const Point<2> &p) const;

    const Parameters &                             parameters;
    const Geometry &                               geometry;
    const parallel::distributed::Triangulation<2> &triangulation;
    Statistics                                     accumulated;
  };
} // namespace viscofilm

#endif
