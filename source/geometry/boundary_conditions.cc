#include <deal.II/base/function.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/component_mask.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <viscofilm/geometry/boundary_conditions.h>

#include <algorithm>
#include <map>
#include <set>

namespace viscofilm
{
  namespace
  {
    const char *type_names = "no slip|velocity|outflow|traction free|slip|pressure|periodic";

    template <int dim>
    const std::map<std::string, typename BoundaryConditions<dim>::Type> types = {
      {"no slip", BoundaryConditions<dim>::Type::no_slip},
      {"velocity", BoundaryConditions<dim>::Type::velocity},
      {"outflow", BoundaryConditions<dim>::Type::outflow},
      {"traction free", BoundaryConditions<dim>::Type::traction_free},
      {"slip", BoundaryConditions<dim>::Type::slip},
      {"pressure", BoundaryConditions<dim>::Type::pressure},
      {"periodic", BoundaryConditions<dim>::Type::periodic}};

    /// The velocity expression seen as a (dim + 1)-component (u, p)
    /// function, the layout of the Stokes element.
    template <int dim>
    class StokesVelocity : public Function<dim>
    {
    public:
      /// @p n_components: the element's (dim + 1 with the pressure, dim alone).
      StokesVelocity(const Function<dim> &velocity, const unsigned int n_components)
        : Function<dim>(n_components)
        , velocity(velocity)
      {}

      double
      value(const Point<dim> &p, const unsigned int component) const override
      {
        return component < dim ? velocity.value(p, component) : 0.0;
      }

    private:
      const Function<dim> &velocity;
    };

    /// The translation taking periodic boundary @p first to @p second: the
    /// difference of their coarse faces' mean centres.
    template <int dim>
    Tensor<1, dim>
    periodic_offset(const Triangulation<dim> &triangulation,
                    const types::boundary_id  first,
                    const types::boundary_id  second)
    {
      Tensor<1, dim> sum[2];
      unsigned int   n[2] = {0, 0};
      for (const auto &cell : triangulation.cell_iterators_on_level(0))
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() &&
              (face->boundary_id() == first || face->boundary_id() == second))
            {
              const unsigned int side = (face->boundary_id() == second);
              sum[side] += face->center();
              ++n[side];
            }
      return sum[1] / std::max(1u, n[1]) - sum[0] / std::max(1u, n[0]);
    }

    /// The coordinate along which @p offset mostly points.
    template <int dim>
    unsigned int
    main_direction(const Tensor<1, dim> &offset)
    {
      unsigned int direction = 0;
      for (unsigned int d = 1; d < dim; ++d)
        if (std::abs(offset[d]) > std::abs(offset[direction]))
          direction = d;
      return direction;
    }
  } // namespace


  template <int dim>
  void
  BoundaryConditions<dim>::declare_parameters(
    ParameterHandler &                          prm,
    const std::vector<typename Geometry<dim>::NamedBoundary> &boundaries)
  {
    prm.enter_subsection("Boundary conditions");
    for (const typename Geometry<dim>::NamedBoundary &boundary : boundaries)
      {
        prm.enter_subsection(boundary.name);
        // A boundary without a default Type (gmsh) accepts "" so that a
        // missing Type gets our message, not the pattern's.
        prm.declare_entry(
          "Type",
          boundary.default_type,
          Patterns::Selection(std::string(boundary.default_type.empty() ? "|" : "") +
                              type_names),
          "no slip: u = 0. velocity: u = Velocity. outflow: the tangential "
          "velocity takes Velocity's tangential part, the normal traction is "
          "zero (do-nothing, MODEL.md §4). traction free: σ·n = 0. slip: "
          "u·n = 0 and zero tangential traction (a symmetry plane). pressure: "
          "as outflow with normal traction σn·n = −Pressure. periodic: "
          "identified with Periodic partner by a translation. Built-in meshes: "
          "the thesis' types (Cylinder, and in 3D Front and Back: no slip); a "
          "gmsh boundary has none and must be given one.");
        ParsedExpression<dim>::declare(prm,
                                  "Velocity",
                                  zero_expression(dim),
                                  "Boundary velocity \"u; v\" (3D: \"u; v; "
                                  "w\") (velocity; the tangential part for "
                                  "outflow and pressure).");
        ParsedExpression<dim>::declare(prm,
                                  "Pressure",
                                  "0",
                                  "P of Type = pressure: the normal traction "
                                  "σn·n = −P, an expression of x, y (, z), "
                                  "t.");
        prm.declare_entry("Periodic partner",
                          "",
                          Patterns::Anything(),
                          "Type = periodic: the name of the boundary this one "
                          "is identified with (periodic too, a translate).");
        declare_function_constants(prm);
        prm.declare_entry("Volume fraction",
                          "0",
                          Patterns::Double(0, 1),
                          "φ on the parts of this boundary where the flow "
                          "enters (u·n < 0), in [0, 1]. The thesis: 0.");
        ParsedExpression<dim>::declare(prm,
                                  "Stress",
                                  zero_expression(n_symmetric_components<dim>),
                                  "Elastic stress \"τxx; τxy; τyy\" (3D: "
                                  "\"τxx; τxy; τxz; τyy; τyz; τzz\") carried in "
                                  "where the flow enters (u·n < 0). 0: the "
                                  "relaxed state.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  template <int dim>
  void
  BoundaryConditions<dim>::parse_parameters(
    ParameterHandler &                          prm,
    const std::vector<typename Geometry<dim>::NamedBoundary> &named_boundaries)
  {
    boundaries.clear();
    boundaries.resize(named_boundaries.size());
    std::vector<std::string> partners(boundaries.size());
    prm.enter_subsection("Boundary conditions");
    for (unsigned int b = 0; b < boundaries.size(); ++b)
      {
        Boundary &        boundary = boundaries[b];
        const std::string path     = "Boundary conditions/" + named_boundaries[b].name;
        boundary.name              = named_boundaries[b].name;
        boundary.id                = named_boundaries[b].id;
        boundary.normal_axis       = named_boundaries[b].normal_axis;
        prm.enter_subsection(boundary.name);
        const std::string type = prm.get("Type");
        check_input(!type.empty(),
                    path + "/Type is not set: choose one of " +
                      std::string(type_names));
        boundary.type = types<dim>.at(type);
        const std::string constants = prm.get("Function constants");
        boundary.velocity.parse(prm.get("Velocity"), constants, path + "/Velocity");
        boundary.pressure.parse(prm.get("Pressure"), constants, path + "/Pressure");
        partners[b]              = Utilities::trim(prm.get("Periodic partner"));
        boundary.volume_fraction = prm.get_double("Volume fraction");
        boundary.stress.parse(prm.get("Stress"), constants, path + "/Stress");
        prm.leave_subsection();
      }
    prm.leave_subsection();

    for (unsigned int b = 0; b < boundaries.size(); ++b)
      if (boundaries[b].type == Type::periodic)
        {
          const std::string parameter =
            "Boundary conditions/" + boundaries[b].name + "/Periodic partner";
          check_input(!partners[b].empty(),
                      parameter + " is not set: a periodic boundary needs the "
                                  "name of the boundary it is identified with");
          boundaries[b].periodic_partner = id(partners[b], parameter);
          const Boundary &partner = boundary(boundaries[b].periodic_partner);
          check_input(partner.id != boundaries[b].id,
                      parameter + ": a boundary cannot be its own partner");
          check_input(partner.type == Type::periodic &&
                        partners[&partner - boundaries.data()] == boundaries[b].name,
                      parameter + " = " + partner.name + ", but " +
                        partner.name + " is not periodic with partner " +
                        boundaries[b].name);
        }

    bool        velocity_fixed = false;
    std::string listing;
    for (const Boundary &boundary : boundaries)
      {
        velocity_fixed = velocity_fixed || boundary.type == Type::no_slip ||
                         boundary.type == Type::velocity;
        for (const auto &[name, type] : types<dim>)
          if (type == boundary.type)
            listing += (listing.empty() ? "" : ", ") + boundary.name + " " + name;
      }
    check_input(velocity_fixed,
                "Boundary conditions: at least one boundary's Type must be "
                "'no slip' or 'velocity', otherwise the velocity is not "
                "determined (the types are: " + listing + ")");
  }


  template <int dim>
  void
  BoundaryConditions<dim>::constrain_velocity(const Mapping<dim> &     mapping,
                                              const DoFHandler<dim> &    dof_handler,
                                         const double               time,
                                         AffineConstraints<double> &constraints,
                                         const bool                 homogeneous) const
  {
    const unsigned int               n_components = dof_handler.get_fe().n_components();
    const Functions::ZeroFunction<dim> zero(n_components);
    const Functions::ZeroFunction<dim> zero_velocity(dim);
    // Walls first: a dof on a corner keeps the first constraint it gets, and
    // the no-slip value is the physically right one there.
    for (const Type type : {Type::no_slip, Type::velocity, Type::pressure, Type::slip})
      for (const Boundary &boundary : boundaries)
        {
          // outflow is pressure with P = 0.
          const Type boundary_type =
            (boundary.type == Type::outflow ? Type::pressure : boundary.type);
          if (boundary_type != type)
            continue;
          const ExpressionAt<dim>   velocity_now = boundary.velocity.at(time);
          const StokesVelocity<dim> velocity(velocity_now, n_components);

          if (type == Type::slip && boundary.normal_axis < 0)
            VectorTools::compute_no_normal_flux_constraints(
              dof_handler, 0, {boundary.id}, constraints, mapping);
          else if (type == Type::pressure && boundary.normal_axis < 0)
            {
              // Tangential velocity on a boundary not normal to an axis.
              const std::map<types::boundary_id, const Function<dim> *> values = {
                {boundary.id,
                 homogeneous ? static_cast<const Function<dim> *>(&zero_velocity) :
                               &velocity_now}};
              VectorTools::compute_nonzero_tangential_flux_constraints(
                dof_handler, 0, {boundary.id}, values, constraints, mapping);
            }
          else
            {
              // On a boundary normal to a coordinate axis: the normal
              // component (slip), the tangential ones (pressure); elsewhere
              // every velocity component.
              ComponentMask mask(n_components, false);
              for (unsigned int d = 0; d < dim; ++d)
                mask.set(d,
                         type == Type::slip     ? int(d) == boundary.normal_axis :
                         type == Type::pressure ? int(d) != boundary.normal_axis :
                                                  true);
              if (homogeneous || type == Type::no_slip || type == Type::slip)
                VectorTools::interpolate_boundary_values(
                  mapping, dof_handler, boundary.id, zero, constraints, mask);
              else
                VectorTools::interpolate_boundary_values(
                  mapping, dof_handler, boundary.id, velocity, constraints, mask);
            }
        }
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::has_periodic_pair() const
  {
    return std::any_of(boundaries.begin(), boundaries.end(), [](const Boundary &boundary) {
      return boundary.type == Type::periodic;
    });
  }


  template <int dim>
  void
  BoundaryConditions<dim>::add_periodicity(
    parallel::distributed::Triangulation<dim> &triangulation) const
  {
    std::vector<GridTools::PeriodicFacePair<
      typename parallel::distributed::Triangulation<dim>::cell_iterator>>
      pairs;
    for (const Boundary &boundary : boundaries)
      if (boundary.type == Type::periodic && boundary.id < boundary.periodic_partner)
        {
          const Tensor<1, dim> offset =
            periodic_offset(triangulation, boundary.id, boundary.periodic_partner);
          unsigned int n_faces = 0;
          for (const auto &cell : triangulation.cell_iterators_on_level(0))
            for (const auto &face : cell->face_iterators())
              n_faces += face->at_boundary() && (face->boundary_id() == boundary.id ||
                                                 face->boundary_id() ==
                                                   boundary.periodic_partner);
          const std::size_t n_before = pairs.size();
          try
            {
              GridTools::collect_periodic_faces(triangulation,
                                                boundary.id,
                                                boundary.periodic_partner,
                                                main_direction(offset),
                                                pairs,
                                                offset);
            }
          catch (const std::exception &)
            {
              pairs.resize(n_before);
            }
          check_input(2 * (pairs.size() - n_before) == n_faces,
                      "Boundary conditions/" + boundary.name +
                        "/Periodic partner = " +
                        this->boundary(boundary.periodic_partner).name +
                        ": the two boundaries are not translates of each "
                        "other face by face on the coarse mesh");
        }
    if (!pairs.empty())
      triangulation.add_periodicity(pairs);
  }


  template <int dim>
  void
  BoundaryConditions<dim>::constrain_periodic(const DoFHandler<dim> & dof_handler,
                                         AffineConstraints<double> &constraints) const
  {
    for (const Boundary &boundary : boundaries)
      if (boundary.type == Type::periodic && boundary.id < boundary.periodic_partner)
        {
          const Tensor<1, dim> offset = periodic_offset(
            dof_handler.get_triangulation(), boundary.id, boundary.periodic_partner);
          std::vector<GridTools::PeriodicFacePair<typename DoFHandler<dim>::cell_iterator>> pairs;
          GridTools::collect_periodic_faces(dof_handler,
                                            boundary.id,
                                            boundary.periodic_partner,
                                            main_direction(offset),
                                            pairs,
                                            offset);
          DoFTools::make_periodicity_constraints<dim, dim>(pairs, constraints);
        }
  }


  template <int dim>
  const typename BoundaryConditions<dim>::Boundary &
  BoundaryConditions<dim>::boundary(const types::boundary_id id) const
  {
    for (const Boundary &boundary : boundaries)
      if (boundary.id == id)
        return boundary;
    AssertThrow(false, ExcMessage("no boundary condition for boundary id " +
                                  std::to_string(id)));
    return boundaries.front();
  }


  template <int dim>
  types::boundary_id
  BoundaryConditions<dim>::id(const std::string &name, const std::string &parameter) const
  {
    std::string known;
    for (const Boundary &boundary : boundaries)
      {
        if (boundary.name == name)
          return boundary.id;
        known += (known.empty() ? "" : ", ") + boundary.name;
      }
    check_input(false,
                parameter + ": no boundary is named \"" + name +
                  "\"; the mesh's boundaries are " + known);
    return 0;
  }


  template <int dim>
  std::set<types::boundary_id>
  BoundaryConditions<dim>::traction_boundary_ids() const
  {
    std::set<types::boundary_id> ids;
    for (const Boundary &boundary : boundaries)
      if (boundary.type == Type::outflow || boundary.type == Type::pressure ||
          boundary.type == Type::traction_free)
        ids.insert(boundary.id);
    return ids;
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::fixes_pressure_level() const
  {
    return !traction_boundary_ids().empty();
  }

  template <int dim>
  double
  mean_normal_velocity(const FEFaceValuesBase<dim> &      stokes_face,
                       const std::vector<Tensor<1, dim>> &velocity)
  {
    double flux = 0, area = 0;
    for (const unsigned int q : stokes_face.quadrature_point_indices())
      {
        flux += velocity[q] * stokes_face.normal_vector(q) * stokes_face.JxW(q);
        area += stokes_face.JxW(q);
      }
    return flux / area;
  }


  VISCOFILM_INSTANTIATE(BoundaryConditions)
#define INSTANTIATE(dim)                                                              \
  template double mean_normal_velocity<dim>(const FEFaceValuesBase<dim> &,            \
                                            const std::vector<Tensor<1, dim>> &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
