// All run parameters: each component declares and parses its own subsection;
// this collects them and checks what spans several subsections.
#ifndef viscofilm_parameters_h
#define viscofilm_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <viscofilm/boundary_conditions.h>
#include <viscofilm/checkpoint.h>
#include <viscofilm/departure_feet.h>
#include <viscofilm/detachment.h>
#include <viscofilm/geometry.h>
#include <viscofilm/initial_conditions.h>
#include <viscofilm/loads.h>
#include <viscofilm/mesh_refinement.h>
#include <viscofilm/model.h>
#include <viscofilm/output.h>
#include <viscofilm/stokes.h>
#include <viscofilm/stress.h>
#include <viscofilm/time_stepping.h>
#include <viscofilm/verification.h>
#include <viscofilm/volume_fraction.h>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  struct Parameters
  {
    /// Declare every parameter; Boundary conditions has a subsection for
    /// each of @p boundaries (Geometry::boundaries() of the parsed mesh).
    static void
    declare_parameters(ParameterHandler &                          prm,
                       const std::vector<typename Geometry<dim>::NamedBoundary> &boundaries);

    /// Parse every subsection; throws ExcInput on inconsistent input.
    /// @p directory: that of the parameter file (Geometry/Mesh file).
    void
    parse_parameters(ParameterHandler &prm, const std::string &directory);

    Geometry<dim>            geometry;
    MeshRefinement<dim>      mesh_refinement;
    TimeStepping             time_stepping;
    Model                    model;
    BoundaryConditions<dim>  boundary_conditions;
    InitialConditions<dim>   initial_conditions;
    typename StokesSolver<dim>::Parameters stokes_solver;
    typename ElasticStress<dim>::Parameters stress;
    typename DepartureFeet<dim>::Parameters departure_feet;
    typename VolumeFraction<dim>::Parameters stabilization;
    typename BiofilmLoads<dim>::Parameters detachment;
    typename Detachment<dim>::Parameters release;
    typename Output<dim>::Parameters output;
    Verification<dim>        verification;
    typename Checkpoint<dim>::Parameters checkpointing;
  };
} // namespace viscofilm

#endif
