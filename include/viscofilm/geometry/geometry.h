// The domain and its mesh: the thesis' channel (a rectangle, MODEL.md §3; a
// box in 3D), a channel with a cylinder (across the channel, along z, in 3D),
// or a quadrilateral/hexahedral mesh read from a gmsh file; and the named
// boundaries of that mesh.
#ifndef viscofilm_geometry_h
#define viscofilm_geometry_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/grid/tria.h>

#include <viscofilm/core/dimension.h>

#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// Boundary ids of the built-in meshes: GridGenerator::plate_with_a_hole's
  /// colorized numbering (the channel's z sides renumbered to match). Ids are
  /// internal; the parameter file names boundaries.
  namespace BoundaryId
  {
    constexpr types::boundary_id inlet    = 0; // x = min
    constexpr types::boundary_id outlet   = 1; // x = max
    constexpr types::boundary_id bottom   = 2; // y = min
    constexpr types::boundary_id top      = 3; // y = max
    constexpr types::boundary_id cylinder = 4; // channel with cylinder
    constexpr types::boundary_id front    = 5; // z = min (3D)
    constexpr types::boundary_id back     = 6; // z = max (3D)
  } // namespace BoundaryId

  template <int dim>
  class Geometry
  {
  public:
    enum class Mesh
    {
      channel,
      channel_with_cylinder,
      gmsh
    };

    /// A boundary of the mesh, as the parameter file names it.
    struct NamedBoundary
    {
      types::boundary_id id;
      std::string        name;
      /// Boundary conditions/<name>/Type's default; empty: none (must be set).
      std::string default_type;
      /// The coordinate axis every face's normal is parallel to; -1: none.
      int normal_axis;
    };

    static void
    declare_parameters(ParameterHandler &prm);
    /// @p directory: that of the parameter file, which a relative Mesh file
    /// is read from. Reads a gmsh file to learn its boundaries.
    void
    parse_parameters(ParameterHandler &prm, const std::string &directory = "");

    /// The coarse mesh with its manifolds (also what a saved mesh is loaded
    /// into); boundary ids as boundaries() lists them.
    void
    make_coarse_grid(Triangulation<dim> &triangulation) const;

    /// The initial mesh from the coarse one: Initial global refinement,
    /// then Cylinder refinement's bands around the cylinder and its wake.
    void
    refine_initial_mesh(Triangulation<dim> &triangulation) const;

    /// The boundaries of the mesh, ordered by id.
    const std::vector<NamedBoundary> &
    boundaries() const;

    /// Edge length of the initial cells: the thesis' Δx at refinement 5 for
    /// the channel, the smallest coarse edge refined for the other meshes.
    double
    initial_cell_size() const;

    /// The degree of the map from the reference cell of every cell, for
    /// every field and every position (FEValues, nodes, feet, forces): 2
    /// if the coarse mesh has a curved manifold (the cylinder), else 1 (the
    /// channel and gmsh meshes: MappingQ1, deal.II's default mapping).
    /// Problem builds that map once per run (Problem::mapping).
    unsigned int
    mapping_degree() const;

    Mesh         mesh = Mesh::channel;
    /// The channel's corners; for a gmsh mesh its bounding box.
    Point<dim>   lower_left;
    Point<dim>   upper_right;
    Point<dim>   cylinder_centre;
    double       cylinder_radius    = 1;
    std::string  mesh_file;          // as resolved against the .prm's directory
    unsigned int initial_refinement = 5;
    /// Graded refinement towards the cylinder and its wake (doc/numerics.md,
    /// "Meshes graded towards the cylinder").
    unsigned int cylinder_refinement          = 0;
    double       cylinder_refinement_distance = 1;
    double       wake_refinement_length       = 0;

  private:
    /// Coarse cells per direction of the channel, so that they are squares.
    std::vector<unsigned int>
    coarse_repetitions() const;

    std::vector<NamedBoundary> named_boundaries;
    double                     smallest_coarse_edge = 1;
    bool                       curved               = false; // see mapping_degree()
  };
} // namespace viscofilm

#endif
