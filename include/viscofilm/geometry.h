// The channel: a rectangle meshed with quadrilaterals (MODEL.md §3).
#ifndef viscofilm_geometry_h
#define viscofilm_geometry_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <deal.II/distributed/tria.h>

#include <array>

namespace viscofilm
{
  using namespace dealii;

  /// Boundary ids, as deal.II's colorized rectangle numbers them.
  namespace BoundaryId
  {
    constexpr types::boundary_id inlet  = 0; // x = min
    constexpr types::boundary_id outlet = 1; // x = max
    constexpr types::boundary_id bottom = 2; // y = min
    constexpr types::boundary_id top    = 3; // y = max
  } // namespace BoundaryId

  class Geometry
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// Square-ish coarse cells refined globally; boundary ids as BoundaryId.
    void
    make_grid(parallel::distributed::Triangulation<2> &triangulation) const;

    /// The coarse mesh alone (what a saved mesh is loaded into).
    void
    make_coarse_grid(parallel::distributed::Triangulation<2> &triangulation) const;

    /// Edge length of the initial cells (the thesis' Δx at refinement 5).
    double
    initial_cell_size() const;

    bool
    contains(const Point<2> &p) const;

    double
    area() const;

    Point<2>     lower_left;
    Point<2>     upper_right;
    unsigned int initial_refinement = 5;

  private:
    /// Coarse cells per direction, chosen so that coarse cells are squares.
    std::array<unsigned int, 2>
    coarse_repetitions() const;
  };
} // namespace viscofilm

#endif
