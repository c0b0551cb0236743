#include <viscofilm/parameters.h>

namespace viscofilm
{
  void
  Parameters::declare_parameters(ParameterHandler &prm)
  {
    Geometry::declare_parameters(prm);
    MeshRefinement::declare_parameters(prm);
    TimeStepping::declare_parameters(prm);
    Model::declare_parameters(prm);
    BoundaryConditions::declare_parameters(prm);
    InitialConditions::declare_parameters(prm);
    StokesSolver::Parameters::declare_parameters(prm);
    ElasticStress::Parameters::declare_parameters(prm);
    DepartureFeet::Parameters::declare_parameters(prm);
    VolumeFraction::Parameters::declare_parameters(prm);
    BiofilmLoads::Parameters::declare_parameters(prm);
    Output::Parameters::declare_parameters(prm);
    Verification::declare_parameters(prm);
    Checkpoint::Parameters::declare_parameters(prm);
  }


  void
  Parameters::parse_parameters(ParameterHandler &prm)
  {
    geometry.parse_parameters(prm);
    mesh_refinement.parse_parameters(prm, geometry.initial_refinement);
    time_stepping.parse_parameters(prm);
    model.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm);
    initial_conditions.parse_parameters(prm);
    stokes_solver.parse_parameters(prm);
    stress.parse_parameters(prm);
    departure_feet.parse_parameters(prm);
    stabilization.parse_parameters(prm);
    detachment.parse_parameters(prm, boundary_conditions);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
    checkpointing.parse_parameters(prm);

    for (const Point<2> &p : output.probe_points)
      check_input(geometry.contains(p),
                  "Output/Probe points: the point (" + to_text(p[0]) +
                    ", " + to_text(p[1]) +
                    ") lies outside the channel given by Geometry/Lower left "
                    "corner and Geometry/Upper right corner");
  }
} // namespace viscofilm
