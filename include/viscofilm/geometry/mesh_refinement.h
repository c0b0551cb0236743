// Adaptive refinement at the biofilm interface: which cells to refine or
// coarsen.
#ifndef viscofilm_mesh_refinement_h
#define viscofilm_mesh_refinement_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <viscofilm/core/dimension.h>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class VolumeFraction;

  template <int dim>
  class MeshRefinement
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      /// @p initial_level: Geometry/Initial global refinement, which must lie
      /// between the minimum and maximum level.
      void
      parse_parameters(ParameterHandler &prm, const unsigned int initial_level);

      bool         adaptive  = false;
      unsigned int interval  = 10;
      unsigned int min_level = 0;
      unsigned int max_level = 0;
      double       threshold = 0.005;
      bool         interface_indicator = false;
      bool         biofilm_indicator   = true;
      bool         velocity_indicator  = true;
      double       velocity_threshold = 0.002;
    };

    explicit MeshRefinement(const Parameters &parameters);

    /// The input φ at t = 0 when it has detail between φ's nodes (an
    /// image): the φ indicators take its values on a grid of @p spacing
    /// (the pixel size) in each cell as well, so that a feature thinner
    /// than a cell refines it.
    struct InitialInput
    {
      const Function<dim> &phi;
      double               spacing;
    };

    /// Flag for refinement the cells where a chosen indicator exceeds its
    /// threshold: φ's variation across the cell (interface), also φ itself
    /// (biofilm), the velocity error indicator (velocity); for coarsening
    /// those where all are below a quarter of it (if @p coarsen); within
    /// the level bounds. The φ indicators look at the detached fraction
    /// @p detached (if not null) as at φ, each on its own. Returns whether
    /// any cell was flagged (collective).
    bool
    flag_cells(parallel::distributed::Triangulation<dim> &triangulation,
               const VolumeFraction<dim> &              volume_fraction,
               const VolumeFraction<dim> *              detached,
               const StokesFlow<dim> &                stokes,
               const bool                               coarsen,
               const InitialInput *                     input = nullptr) const;

  private:
    const Parameters &parameters;
  };
} // namespace viscofilm

#endif
