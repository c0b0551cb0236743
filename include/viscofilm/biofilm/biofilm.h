// The biofilm as the loads and the release both see it: its outline, its
// strength and the walls it grows on (prm subsection Detachment).
#ifndef viscofilm_biofilm_h
#define viscofilm_biofilm_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <algorithm>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class BoundaryConditions;

  /// A boundary named in a parameter, and its id.
  struct NamedBoundaryId
  {
    std::string        name;
    types::boundary_id id;
  };

  /// The boundaries named in the comma-separated list @p names, each
  /// resolved with @p boundary_conditions (an unknown or repeated name names
  /// @p parameter).
  template <int dim>
  std::vector<NamedBoundaryId>
  named_boundaries(const std::string &             names,
                   const std::string &             parameter,
                   const BoundaryConditions<dim> &boundary_conditions);

  template <int dim>
  struct Biofilm
  {
    /// Declare Stress threshold, Interface volume fraction and Walls in the
    /// current subsection (Detachment declares them in its own).
    static void
    declare_entries(ParameterHandler &prm);
    /// Walls' names are resolved with @p boundary_conditions.
    void
    parse_entries(ParameterHandler &prm, const BoundaryConditions<dim> &boundary_conditions);

    /// σ_vm above which the biofilm counts as prone to detach; the
    /// strength of the release.
    double stress_threshold = 1.0;
    /// The biofilm is φ >= this; its interface the contour φ = this.
    double interface_level = 0.05;
    /// The walls it grows on: of the wall shear stress, and those the
    /// release's connectivity starts from.
    std::vector<NamedBoundaryId> walls;

    /// Whether boundary @p id is one of walls.
    bool
    is_wall(const types::boundary_id id) const
    {
      return std::any_of(walls.begin(), walls.end(), [id](const NamedBoundaryId &wall) {
        return wall.id == id;
      });
    }
  };
} // namespace viscofilm

#endif
