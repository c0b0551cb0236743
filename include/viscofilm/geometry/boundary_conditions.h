// Boundary conditions on the named boundaries of the mesh (MODEL.md §4): each
// boundary of Geometry gets a Type and its data.
#ifndef viscofilm_boundary_conditions_h
#define viscofilm_boundary_conditions_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/geometry/geometry.h>
#include <viscofilm/core/input.h>

#include <set>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// Flow enters where u·n < −inflow_threshold · max|u|: a wall whose u·n is
  /// round-off is no inflow boundary.
  constexpr double inflow_threshold = 1e-8;

  /// The mean of u·n over the boundary face on which @p stokes_face was
  /// last reinitialised (with normals and JxW), @p velocity the velocity at
  /// its quadrature points.
  template <int dim>
  double
  mean_normal_velocity(const FEFaceValuesBase<dim> &      stokes_face,
                       const std::vector<Tensor<1, dim>> &velocity);

  /// Whether the flow enters through a boundary face whose mean u·n is
  /// @p mean_normal_velocity, @p max_speed being the velocity scale: the
  /// transport schemes' inflow faces. A face's mean, not a point's u·n:
  /// along a curved wall that the flow follows, the discrete u·n changes
  /// sign from point to point by the wall's approximation error, whereas
  /// the face's flux nearly vanishes (in 2D it is the difference of the
  /// stream function, constant along the wall, between the face's ends).
  /// (The departure feet test the point where they leave:
  /// DepartureFeet::enters().)
  inline bool
  flow_enters(const double mean_normal_velocity, const double max_speed)
  {
    return mean_normal_velocity < -inflow_threshold * max_speed;
  }

  template <int dim>
  class BoundaryConditions
  {
  public:
    enum class Type
    {
      no_slip,       // u = 0
      velocity,      // u from the expression
      outflow,       // pressure with P = 0 (the thesis' outlet)
      traction_free, // σ·n = 0: all natural
      slip,          // u·n = 0, zero tangential traction
      pressure,      // σn·n = −P, tangential velocity from the expression
      periodic       // identified with Periodic partner by a translation
    };

    struct Boundary
    {
      std::string        name;
      types::boundary_id id   = 0;
      Type               type = Type::no_slip;
      ParsedExpression<dim> velocity{dim};
      double             volume_fraction = 0; // φ where the flow enters
      /// τ where the flow enters (stored components, dimension.h), 0: the
      /// relaxed state.
      ParsedExpression<dim> stress{n_symmetric_components<dim>};
      /// The prescribed normal traction −P n (pressure; outflow: P = 0).
      ParsedExpression<dim> pressure{1};
      /// The id of the boundary a periodic one is identified with.
      types::boundary_id periodic_partner = 0;
      /// The coordinate axis the normal is parallel to; -1: none.
      int normal_axis = -1;
    };

    /// Declare Boundary conditions/<name> for each of @p boundaries.
    static void
    declare_parameters(ParameterHandler &                          prm,
                       const std::vector<typename Geometry<dim>::NamedBoundary> &boundaries);
    void
    parse_parameters(ParameterHandler &                          prm,
                     const std::vector<typename Geometry<dim>::NamedBoundary> &boundaries);

    /// Add the velocity constraints at time @p time to @p constraints for an
    /// element whose first dim components are the velocity (the Stokes
    /// element, or the velocity alone); @p mapping places the boundary nodes
    /// and gives the normals; @p homogeneous: with zero values (a multigrid
    /// level's).
    void
    constrain_velocity(const Mapping<dim> &       mapping,
                       const DoFHandler<dim> &    dof_handler,
                       const double               time,
                       AffineConstraints<double> &constraints,
                       const bool                 homogeneous = false) const;

    /// Whether a pair of boundaries is periodic.
    bool
    has_periodic_pair() const;

    /// Identify the coarse faces of each periodic pair (before refinement).
    void
    add_periodicity(parallel::distributed::Triangulation<dim> &triangulation) const;

    /// Make every component of @p dof_handler's field equal on the two
    /// boundaries of each periodic pair.
    void
    constrain_periodic(const DoFHandler<dim> &    dof_handler,
                       AffineConstraints<double> &constraints) const;

    /// The boundaries with a prescribed normal traction (outflow, pressure,
    /// traction free): where the pressure is data, not a velocity's.
    std::set<types::boundary_id>
    traction_boundary_ids() const;

    /// A boundary with a prescribed normal traction fixes the pressure
    /// level; otherwise the pressure is determined up to a constant (mean
    /// zero).
    bool
    fixes_pressure_level() const;

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
