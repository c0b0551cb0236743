// Velocity boundary conditions on the four sides of the channel (MODEL.md §4).
#ifndef viscofilm_boundary_conditions_h
#define viscofilm_boundary_conditions_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>

#include <viscofilm/dimension.h>
#include <viscofilm/input.h>

#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  class BoundaryConditions
  {
  public:
    enum class Type
    {
      no_slip,  // u = v = 0
      velocity, // u, v from the expression
      outflow   // tangential velocity from the expression, normal natural
    };

    struct Boundary
    {
      std::string        name;
      types::boundary_id id   = 0;
      Type               type = Type::no_slip;
      ParsedExpression   velocity{dim};
      double             volume_fraction = 0; // φ where the flow enters
      /// τ where the flow enters (xx; xy; yy), 0: the relaxed state.
      ParsedExpression stress{n_symmetric_components};
    };

    BoundaryConditions();

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// Add the velocity constraints at time @p time to @p constraints for a
    /// Stokes element whose components 0, 1 are the velocity.
    void
    constrain_velocity(const DoFHandler<2> &        dof_handler,
                       const double                 time,
                       AffineConstraints<double> &constraints) const;

    /// With an outflow boundary the outlet fixes the pressure level;
    /// otherwise the pressure is determined up to a constant.
    bool
    has_outflow() const;

    /// The boundary with id @p id; every boundary id of the mesh has one.
    const Boundary &
    boundary(const types::boundary_id id) const;

    /// The id of the boundary named @p name; an unknown name throws ExcInput
    /// naming @p parameter and the names there are.
    types::boundary_id
    id(const std::string &name, const std::string &parameter) const;

    std::vector<Boundary> boundaries;
  };
} // namespace viscofilm

#endif
