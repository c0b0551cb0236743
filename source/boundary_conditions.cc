#include <deal.II/base/function.h>

#include <deal.II/fe/component_mask.h>

#include <deal.II/numerics/vector_tools.h>

#include <viscofilm/boundary_conditions.h>
#include <viscofilm/geometry.h>

namespace viscofilm
{
  namespace
  {
    const std::array<const char *, 4> boundary_names = {
      {"Inlet", "Outlet", "Bottom", "Top"}};

    const std::array<const char *, 4> default_types = {
      {"velocity", "outflow", "no slip", "no slip"}};

    /// The 2-component velocity expression seen as a 3-component (u, v, p)
    /// function, the layout of the Stokes element.
    class StokesVelocity : public Function<2>
    {
    public:
      StokesVelocity(const Function<2> &velocity)
        : Function<2>(3)
        , velocity(velocity)
      {}

      double
      value(const Point<2> &p, const unsigned int component) const override
      {
        return component < 2 ? velocity.value(p, component) : 0.0;
      }

    private:
      const Function<2> &velocity;
    };
  } // namespace


  BoundaryConditions::BoundaryConditions()
  {
    boundaries.resize(4);
    for (unsigned int b = 0; b < 4; ++b)
      {
        boundaries[b].name = boundary_names[b];
        boundaries[b].id   = b;
      }
  }


  void
  BoundaryConditions::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    for (unsigned int b = 0; b < 4; ++b)
      {
        prm.enter_subsection(boundary_names[b]);
        prm.declare_entry(
          "Type",
          default_types[b],
          Patterns::Selection("no slip|velocity|outflow"),
          "no slip: u = v = 0. velocity: (u, v) = Velocity. outflow: the "
          "tangential component takes Velocity's value (v on the inlet and "
          "outlet, u on the bottom and top), the normal one is natural "
          "(do-nothing traction, MODEL.md §4).");
        ParsedExpression::declare(prm,
                                  "Velocity",
                                  "0; 0",
                                  "Boundary velocity \"u; v\".");
        declare_function_constants(prm);
        prm.declare_entry("Volume fraction",
                          "0",
                          Patterns::Double(0, 1),
                          "φ on the parts of this boundary where the flow "
                          "enters (u·n < 0), in [0, 1]. The thesis: 0.");
        ParsedExpression::declare(prm,
                                  "Stress",
                                  "0; 0; 0",
                                  "Elastic stress \"τxx; τxy; τyy\" carried in "
                                  "where the flow enters (u·n < 0). 0: the "
                                  "relaxed state.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  BoundaryConditions::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    for (Boundary &boundary : boundaries)
      {
        prm.enter_subsection(boundary.name);
        const std::string type = prm.get("Type");
        boundary.type          = (type == "no slip" ? Type::no_slip :
                                  type == "velocity" ? Type::velocity :
                                                       Type::outflow);
        boundary.velocity.parse(prm.get("Velocity"),
                                prm.get("Function constants"),
                                "Boundary conditions/" + boundary.name +
                                  "/Velocity");
        boundary.volume_fraction = prm.get_double("Volume fraction");
        boundary.stress.parse(prm.get("Stress"),
                              prm.get("Function constants"),
                              "Boundary conditions/" + boundary.name + "/Stress");
        prm.leave_subsection();
      }
    prm.leave_subsection();

    bool all_outflow = true;
    for (const Boundary &boundary : boundaries)
      all_outflow = all_outflow && boundary.type == Type::outflow;
    check_input(!all_outflow,
                "Boundary conditions: at least one boundary's Type must be "
                "'no slip' or 'velocity'; with four 'outflow' boundaries the "
                "velocity is not determined");
  }


  void
  BoundaryConditions::constrain_velocity(const DoFHandler<2> &      dof_handler,
                                         const double               time,
                                         AffineConstraints<double> &constraints) const
  {
    // Walls first: a dof on a corner keeps the first constraint it gets, and
    // the no-slip value is the physically right one there.
    for (const Type type : {Type::no_slip, Type::velocity, Type::outflow})
      for (unsigned int b = 0; b < 4; ++b)
        if (boundaries[b].type == type)
          {
            boundaries[b].velocity.function().set_time(time);
            const StokesVelocity velocity(boundaries[b].velocity.function());

            const bool   normal_is_x = (b == BoundaryId::inlet ||
                                      b == BoundaryId::outlet);
            ComponentMask mask(3, false);
            if (type == Type::outflow)
              mask.set(normal_is_x ? 1 : 0, true);
            else
              {
                mask.set(0, true);
                mask.set(1, true);
              }

            if (type == Type::no_slip)
              VectorTools::interpolate_boundary_values(
                dof_handler, b, Functions::ZeroFunction<2>(3), constraints, mask);
            else
              VectorTools::interpolate_boundary_values(
                dof_handler, b, velocity, constraints, mask);
          }
  }


  const BoundaryConditions::Boundary &
  BoundaryConditions::boundary(const types::boundary_id id) const
  {
    for (const Boundary &boundary : boundaries)
      if (boundary.id == id)
        return boundary;
    AssertThrow(false, ExcMessage("no boundary condition for boundary id " +
                                  std::to_string(id)));
    return boundaries.front();
  }


  types::boundary_id
  BoundaryConditions::id(const std::string &name, const std::string &parameter) const
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


  bool
  BoundaryConditions::has_outflow() const
  {
    for (const Boundary &boundary : boundaries)
      if (boundary.type == Type::outflow)
        return true;
    return false;
  }
} // namespace viscofilm
