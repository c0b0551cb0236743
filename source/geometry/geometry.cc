// InverseQuadraticApproximation: the copied TransfiniteInterpolationManifold holds them.
#include <deal.II/fe/mapping_q_internal.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <viscofilm/geometry/geometry.h>
#include <viscofilm/core/input.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace viscofilm
{
  namespace
  {
    /// The cylinder's manifolds (GridGenerator::plate_with_a_hole's ids).
    constexpr types::manifold_id polar_manifold       = 0;
    constexpr types::manifold_id transfinite_manifold = 1;

    /// The cylinder's surface: a circle about the centre in 2D, a cylinder
    /// along z through it in 3D.
    template <int dim>
    std::unique_ptr<Manifold<dim>>
    cylinder_manifold(const Point<dim> &centre)
    {
      if (dim == 2)
        return std::make_unique<PolarManifold<dim>>(centre);
      Tensor<1, dim> axis;
      axis[dim - 1] = 1;
      return std::make_unique<CylindricalManifold<dim>>(axis, centre);
    }

    /**
     * deal.II's TransfiniteInterpolationManifold whose clones copy its state.
     * deal.II 9.4 re-initialises each clone (every copy_triangulation(): the
     * multigrid's coarse meshes) on the triangulation the original was
     * initialised on, as it is now: once refined and graded, its table of
     * coarse cells is sized by the finest level but indexed by every active
     * cell, and the writes past its end corrupted the heap (the multigrid's
     * set-up on a graded cylinder mesh, 2 ranks). A copy keeps the coarse
     * mesh's table.
     */
    template <int dim>
    class CopyableTransfiniteManifold : public TransfiniteInterpolationManifold<dim>
    {
    public:
      std::unique_ptr<Manifold<dim>>
      clone() const override
      {
        return std::make_unique<CopyableTransfiniteManifold<dim>>(*this);
      }
    };


    /// The distance from the cylinder's axis to the nearest side of the
    /// channel, in the plane (x, y) across the axis.
    template <int dim>
    double
    distance_to_nearest_side(const Point<dim> &centre,
                             const Point<dim> &lower_left,
                             const Point<dim> &upper_right)
    {
      double distance = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < 2; ++d)
        distance =
          std::min({distance, centre[d] - lower_left[d], upper_right[d] - centre[d]});
      return distance;
    }

    /// What a boundary of a gmsh mesh is, and gmsh's name for its group.
    template <int dim>
    const std::string boundary_entity = (dim == 2 ? "boundary lines" : "boundary faces");
    template <int dim>
    const std::string physical_group = (dim == 2 ? "Physical Curve" : "Physical Surface");

    /// Physical names of the (dim − 1)-dimensional groups in a gmsh file's
    /// $PhysicalNames section, by tag (deal.II's GridIn skips the section).
    template <int dim>
    std::map<types::boundary_id, std::string>
    read_physical_names(const std::string &filename)
    {
      std::map<types::boundary_id, std::string> names;
      std::ifstream                             file(filename);
      std::string                               line;
      while (std::getline(file, line) && Utilities::trim(line) != "$PhysicalNames")
        ;
      unsigned int n = 0;
      if (!(file >> n))
        return names;
      for (unsigned int i = 0; i < n && std::getline(file >> std::ws, line); ++i)
        {
          std::istringstream entry(line);
          int                group_dim = 0;
          unsigned int       tag       = 0;
          entry >> group_dim >> tag;
          std::string name;
          std::getline(entry >> std::ws, name);
          name = Utilities::trim(name);
          if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
            name = name.substr(1, name.size() - 2);
          if (group_dim == dim - 1 && !name.empty())
            names[tag] = name;
        }
      return names;
    }
  } // namespace


  template <int dim>
  void
  Geometry<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension of the run: 2 or 3. Points are then "
                      "written \"x, y\" or \"x, y, z\", expressions use x, "
                      "y (, z) and t, vectors have dim components and "
                      "symmetric tensors dim(dim+1)/2 (xx; xy; yy or xx; xy; "
                      "xz; yy; yz; zz).");
    prm.declare_entry("Mesh",
                      "channel",
                      Patterns::Selection("channel|channel with cylinder|gmsh"),
                      "channel: the rectangle (3D: box) between the corners, "
                      "boundaries Inlet (x min), Outlet (x max), Bottom (y "
                      "min), Top (y max), and in 3D Front (z min), Back (z "
                      "max). channel with cylinder: the same with a cylinder "
                      "(boundary Cylinder) cut out; in 3D its axis is along z "
                      "and it spans the channel from Front to Back. gmsh: the "
                      "quadrilateral (3D: hexahedral) mesh in Mesh file; its "
                      "boundaries are the physical groups of its boundary "
                      "lines (3D: surfaces), named as in the file.");
    prm.declare_entry("Lower left corner",
                      dim == 2 ? "0, 0" : "0, 0, 0",
                      Patterns::Anything(),
                      "Corner (x, y) (3D: (x, y, z)) of the channel at the "
                      "inlet and the bottom (and front) wall, in units of L0 "
                      "(1 cm).");
    prm.declare_entry("Upper right corner",
                      dim == 2 ? "1, 1" : "1, 1, 1",
                      Patterns::Anything(),
                      "Corner (x, y) (3D: (x, y, z)) of the channel at the "
                      "outlet and the top (and back) wall. Must exceed the "
                      "lower left corner in every coordinate.");
    prm.declare_entry("Initial global refinement",
                      "5",
                      Patterns::Integer(0, 12),
                      "Number of global refinements of the coarse mesh (square "
                      "(3D: cubic) cells of edge the channel's smallest side "
                      "for the channel). 5 gives the thesis' Δx = 1/32 on the "
                      "unit square.");
    prm.declare_entry("Cylinder centre",
                      dim == 2 ? "0, 0" : "0, 0, 0",
                      Patterns::Anything(),
                      "Centre (x, y) of the cylinder (channel with cylinder); "
                      "in 3D a point (x, y, z) on its axis, which is parallel "
                      "to z (its z does not matter).");
    prm.declare_entry("Cylinder radius",
                      "1",
                      Patterns::Double(0),
                      "Radius of the cylinder (channel with cylinder); the "
                      "cylinder must keep a gap of a tenth of the distance "
                      "from its centre to the nearest channel side (in x and "
                      "y).");
    prm.declare_entry("Cylinder refinement",
                      "0",
                      Patterns::Integer(0, 8),
                      "Refinements beyond Initial global refinement near the "
                      "cylinder and along its wake (channel with cylinder): "
                      "the n-th refines the cells with a vertex within "
                      "Cylinder refinement distance / 2^(n-1) of the cylinder "
                      "or of the wake's centreline, a mesh graded towards "
                      "them. 0: the uniform mesh.");
    prm.declare_entry("Cylinder refinement distance",
                      "1",
                      Patterns::Double(0),
                      "Width of the band (from the cylinder's surface and the "
                      "wake's centreline) that the first Cylinder refinement "
                      "refines, in units of length; each further one halves "
                      "it. > 0.");
    prm.declare_entry("Wake refinement length",
                      "0",
                      Patterns::Double(0),
                      "Length of the wake's centreline that Cylinder "
                      "refinement also refines around: from the cylinder's "
                      "rear along +x (the line y = the centre's y; 3D: the "
                      "plane through the axis). 0: the cylinder only.");
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::Anything(),
                      "gmsh mesh (.msh, format 2 or 4, quadrilaterals only; "
                      "3D: hexahedra only), relative to the parameter file's "
                      "directory.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Geometry<dim>::parse_parameters(ParameterHandler &prm, const std::string &directory)
  {
    prm.enter_subsection("Geometry");
    // main() runs Problem<Dimension>.
    AssertThrow(prm.get_integer("Dimension") == dim, ExcInternalError());
    const std::string mesh_name = prm.get("Mesh");
    mesh = (mesh_name == "channel" ? Mesh::channel :
            mesh_name == "gmsh"    ? Mesh::gmsh :
                                     Mesh::channel_with_cylinder);
    lower_left =
      parse_point<dim>(prm.get("Lower left corner"), "Geometry/Lower left corner");
    upper_right =
      parse_point<dim>(prm.get("Upper right corner"), "Geometry/Upper right corner");
    initial_refinement = prm.get_integer("Initial global refinement");
    cylinder_centre =
      parse_point<dim>(prm.get("Cylinder centre"), "Geometry/Cylinder centre");
    cylinder_radius = prm.get_double("Cylinder radius");
    mesh_file       = prm.get("Mesh file");
    cylinder_refinement          = prm.get_integer("Cylinder refinement");
    cylinder_refinement_distance = prm.get_double("Cylinder refinement distance");
    wake_refinement_length       = prm.get_double("Wake refinement length");
    prm.leave_subsection();
    check_input(cylinder_refinement_distance > 0,
                "Geometry/Cylinder refinement distance must be > 0, got " +
                  to_text(cylinder_refinement_distance));
    check_input(cylinder_refinement == 0 || mesh == Mesh::channel_with_cylinder,
                "Geometry/Cylinder refinement = " + to_text(cylinder_refinement) +
                  " needs Geometry/Mesh = channel with cylinder");

    if (mesh != Mesh::gmsh)
      {
        bool ordered = true;
        for (unsigned int d = 0; d < dim; ++d)
          ordered = ordered && upper_right[d] > lower_left[d];
        check_input(ordered,
                    "Geometry/Upper right corner must exceed Geometry/Lower "
                    "left corner in every coordinate");
      }
    if (mesh == Mesh::channel)
      {
        for (const unsigned int n : coarse_repetitions())
          check_input(n <= 64,
                      "Geometry: the channel's aspect ratio must be at most 64");
      }
    else if (mesh == Mesh::channel_with_cylinder)
      {
        const double gap =
          distance_to_nearest_side(cylinder_centre, lower_left, upper_right);
        check_input(cylinder_radius > 0 && cylinder_radius < 0.9 * gap,
                    "Geometry/Cylinder radius = " + to_text(cylinder_radius) +
                      ": the cylinder must lie inside the channel with a margin "
                      "(radius > 0 and below 0.9 times the distance " +
                      to_text(gap) + " from Geometry/Cylinder centre to the "
                      "nearest side of the channel)");
      }
    else
      {
        check_input(!mesh_file.empty(),
                    "Geometry/Mesh file: Geometry/Mesh = gmsh needs a mesh file");
        if (std::filesystem::path(mesh_file).is_relative())
          mesh_file = (std::filesystem::path(directory) / mesh_file).string();
        check_input(std::filesystem::is_regular_file(mesh_file),
                    "Geometry/Mesh file: \"" + mesh_file + "\" does not exist");
      }

    // Learn the boundaries (and check the file) from a serial coarse mesh.
    Triangulation<dim> coarse;
    make_coarse_grid(coarse);
    std::map<types::boundary_id, std::set<int>> axes; // of each face's normal
    smallest_coarse_edge = std::numeric_limits<double>::max();
    for (const auto &cell : coarse.active_cell_iterators())
      {
        for (const unsigned int l : cell->line_indices())
          smallest_coarse_edge =
            std::min(smallest_coarse_edge, cell->line(l)->diameter());
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              // Normal along axis d: every vertex has the same x_d.
              int axis = -1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  bool flat = true;
                  for (const unsigned int v : face->vertex_indices())
                    flat = flat && std::abs(face->vertex(v)[d] - face->vertex(0)[d]) <=
                                     1e-10 * face->diameter();
                  if (flat)
                    axis = d;
                }
              axes[face->boundary_id()].insert(axis);
            }
      }

    // On a curved boundary the bilinear map makes each cell's edge a chord,
    // a geometry error of O(h²) that limited the cylinder's drag to second
    // order in h (and the stress update to first order where node
    // positions and velocity gradients were taken with it). The quadratic
    // map puts the edge and interior support points on the manifolds
    // (doc/numerics.md, "The mapping").
    curved = false;
    for (const auto &cell : coarse.active_cell_iterators())
      {
        curved = curved || cell->manifold_id() != numbers::flat_manifold_id;
        for (const auto &face : cell->face_iterators())
          curved = curved || face->manifold_id() != numbers::flat_manifold_id;
      }

    std::map<types::boundary_id, std::string> names;
    if (mesh == Mesh::gmsh)
      {
        check_input(axes.count(0) == 0,
                    "Geometry/Mesh file \"" + mesh_file + "\": some " +
                      boundary_entity<dim> + " belong to no physical group; put "
                      "every one in one (gmsh: " + physical_group<dim> + "), its "
                      "name is what Boundary conditions calls it");
        names = read_physical_names<dim>(mesh_file);
      }
    else
      names = {{BoundaryId::inlet, "Inlet"},
               {BoundaryId::outlet, "Outlet"},
               {BoundaryId::bottom, "Bottom"},
               {BoundaryId::top, "Top"},
               {BoundaryId::cylinder, "Cylinder"},
               {BoundaryId::front, "Front"},
               {BoundaryId::back, "Back"}};
    const std::map<types::boundary_id, std::string> default_types = {
      {BoundaryId::inlet, "velocity"},
      {BoundaryId::outlet, "outflow"},
      {BoundaryId::bottom, "no slip"},
      {BoundaryId::top, "no slip"},
      {BoundaryId::cylinder, "no slip"},
      {BoundaryId::front, "no slip"},
      {BoundaryId::back, "no slip"}};

    named_boundaries.clear();
    std::set<std::string> used;
    for (const auto &[id, face_axes] : axes)
      {
        NamedBoundary boundary;
        boundary.id   = id;
        boundary.name = names.count(id) ? names[id] : std::to_string(id);
        boundary.default_type =
          (mesh == Mesh::gmsh ? std::string() : default_types.at(id));
        boundary.normal_axis = (face_axes.size() == 1 ? *face_axes.begin() : -1);
        check_input(used.insert(boundary.name).second,
                    "Geometry/Mesh file \"" + mesh_file +
                      "\": two boundary groups are named \"" + boundary.name +
                      "\"");
        named_boundaries.push_back(boundary);
      }

    if (mesh == Mesh::gmsh)
      std::tie(lower_left, upper_right) =
        GridTools::compute_bounding_box(coarse).get_boundary_points();
  }


  template <int dim>
  std::vector<unsigned int>
  Geometry<dim>::coarse_repetitions() const
  {
    const Tensor<1, dim> extent = upper_right - lower_left;
    double               edge   = extent[0];
    for (unsigned int d = 1; d < dim; ++d)
      edge = std::min(edge, extent[d]);
    std::vector<unsigned int> n(dim);
    for (unsigned int d = 0; d < dim; ++d)
      n[d] = static_cast<unsigned int>(std::max(1.0, std::round(extent[d] / edge)));
    return n;
  }


  template <int dim>
  void
  Geometry<dim>::make_coarse_grid(Triangulation<dim> &triangulation) const
  {
    if (mesh == Mesh::channel)
      {
        GridGenerator::subdivided_hyper_rectangle(
          triangulation, coarse_repetitions(), lower_left, upper_right, /*colorize*/ true);
        // colorize numbers z min and z max 4 and 5: BoundaryId's front, back.
        for (const auto &face : triangulation.active_face_iterators())
          if (face->at_boundary() && face->boundary_id() >= 4)
            face->set_boundary_id(face->boundary_id() == 4 ? BoundaryId::front :
                                                             BoundaryId::back);
      }
    else if (mesh == Mesh::channel_with_cylinder)
      {
        // A square of half-size h around the hole (h: the distance to the
        // nearest side), padded to the channel's sides.
        const double h =
          distance_to_nearest_side(cylinder_centre, lower_left, upper_right);
        // 3D: the 2D mesh extruded over the depth in layers of about h,
        // centred on the channel's middle in z.
        const double depth  = upper_right[dim - 1] - lower_left[dim - 1];
        Point<dim>   centre = cylinder_centre;
        if (dim == 3)
          centre[dim - 1] = 0.5 * (lower_left[dim - 1] + upper_right[dim - 1]);
        const unsigned int layers =
          static_cast<unsigned int>(std::max(1.0, std::round(depth / h)));
        GridGenerator::plate_with_a_hole(triangulation,
                                         cylinder_radius,
                                         h,
                                         cylinder_centre[1] - h - lower_left[1],
                                         upper_right[1] - cylinder_centre[1] - h,
                                         cylinder_centre[0] - h - lower_left[0],
                                         upper_right[0] - cylinder_centre[0] - h,
                                         centre,
                                         polar_manifold,
                                         transfinite_manifold,
                                         depth,
                                         layers + 1,
                                         /*colorize*/ true);
        // Refined vertices on the cylinder, and smoothly placed around it.
        triangulation.set_manifold(polar_manifold, *cylinder_manifold(centre));
        CopyableTransfiniteManifold<dim> transfinite;
        transfinite.initialize(triangulation);
        triangulation.set_manifold(transfinite_manifold, transfinite);
      }
    else
      {
        Triangulation<dim> serial;
        GridIn<dim>        grid_in;
        grid_in.attach_triangulation(serial);
        std::ifstream file(mesh_file);
        try
          {
            grid_in.read_msh(file);
          }
        catch (const std::exception &e)
          {
            check_input(false,
                        "Geometry/Mesh file \"" + mesh_file +
                          "\" could not be read as a gmsh mesh: " +
                          error_message(e));
          }
        check_input(serial.all_reference_cells_are_hyper_cube(),
                    "Geometry/Mesh file \"" + mesh_file + "\" contains " +
                      (dim == 2 ? "triangles; the solver needs quadrilaterals "
                                  "(gmsh: Recombine Surface, Mesh.RecombineAll = 1)" :
                                  "tetrahedra, prisms or pyramids; the solver "
                                  "needs hexahedra (gmsh: Recombine and "
                                  "Mesh.Recombine3DAll = 1, or a transfinite "
                                  "structured mesh)"));
        triangulation.copy_triangulation(serial);
      }
  }


  template <int dim>
  void
  Geometry<dim>::refine_initial_mesh(Triangulation<dim> &triangulation) const
  {
    triangulation.refine_global(initial_refinement);
    // Distance in the plane across the axis from the cylinder's surface and
    // from the wake's centreline segment behind it.
    const double wake_end = cylinder_centre[0] + cylinder_radius + wake_refinement_length;
    const auto   distance = [&](const Point<dim> &p) {
      const double dx = p[0] - cylinder_centre[0], dy = p[1] - cylinder_centre[1];
      double       d  = std::max(0.0, std::hypot(dx, dy) - cylinder_radius);
      if (wake_refinement_length > 0 && dx >= 0)
        d = std::min(d, std::hypot(std::max(0.0, p[0] - wake_end), dy));
      return d;
    };
    for (unsigned int n = 0; n < cylinder_refinement; ++n)
      {
        const double band = cylinder_refinement_distance / std::pow(2.0, n);
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              if (distance(cell->vertex(v)) < band)
                {
                  cell->set_refine_flag();
                  break;
                }
        triangulation.execute_coarsening_and_refinement();
      }
  }


  template <int dim>
  const std::vector<typename Geometry<dim>::NamedBoundary> &
  Geometry<dim>::boundaries() const
  {
    return named_boundaries;
  }


  template <int dim>
  double
  Geometry<dim>::initial_cell_size() const
  {
    const double coarse_edge =
      (mesh == Mesh::channel ? (upper_right - lower_left)[0] / coarse_repetitions()[0] :
                               smallest_coarse_edge);
    return coarse_edge / std::pow(2.0, initial_refinement);
  }


  template <int dim>
  unsigned int
  Geometry<dim>::mapping_degree() const
  {
    return curved ? 2 : 1;
  }


  VISCOFILM_INSTANTIATE(Geometry)
} // namespace viscofilm
