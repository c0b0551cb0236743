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

  struct Parameters
  {
    /// Declare every parameter; Boundary conditions has a subsection for
    /// each of @p boundaries (Geometry::boundaries() of the parsed mesh).
    static void
    declare_parameters(ParameterHandler &                          prm,
                       const std::vector<Geometry::NamedBoundary> &boundaries);

    /// Parse every subsection; throws ExcInput on inconsistent input.
    /// @p directory: that of the parameter file (Geometry/Mesh file).
    void
    parse_parameters(ParameterHandler &prm, const std::string &directory);

    Geometry                 geometry;
    MeshRefinement           mesh_refinement;
    TimeStepping             time_stepping;
    Model                    model;
    BoundaryConditions       boundary_conditions;
    InitialConditions        initial_conditions;
    StokesSolver::Parameters stokes_solver;
    ElasticStress::Parameters stress;
    DepartureFeet::Parameters departure_feet;
    VolumeFraction::Parameters stabilization;
    BiofilmLoads::Parameters  detachment;
    Detachment::Parameters    release;
    Output::Parameters       output;
    Verification             verification;
    Checkpoint::Parameters   checkpointing;
  };
} // namespace viscofilm

#endif
