#include <viscofilm/parameters.h>

namespace viscofilm
{
  void
  Parameters::declare_parameters(ParameterHandler &                          prm,
                                 const std::vector<Geometry::NamedBoundary> &boundaries)
  {
    Geometry::declare_parameters(prm);
    MeshRefinement::declare_parameters(prm);
    TimeStepping::declare_parameters(prm);
    Model::declare_parameters(prm);
    BoundaryConditions::declare_parameters(prm, boundaries);
    InitialConditions::declare_parameters(prm);
    StokesSolver::Parameters::declare_parameters(prm);
    ElasticStress::Parameters::declare_parameters(prm);
    DepartureFeet::Parameters::declare_parameters(prm);
    VolumeFraction::Parameters::declare_parameters(prm);
    BiofilmLoads::Parameters::declare_parameters(prm);
    Detachment::Parameters::declare_parameters(prm);
    Output::Parameters::declare_parameters(prm);
    Verification::declare_parameters(prm);
    Checkpoint::Parameters::declare_parameters(prm);
  }


  void
  Parameters::parse_parameters(ParameterHandler &prm, const std::string &directory)
  {
    geometry.parse_parameters(prm, directory);
    mesh_refinement.parse_parameters(prm, geometry.initial_refinement);
    time_stepping.parse_parameters(prm);
    model.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm, geometry.boundaries());
    initial_conditions.parse_parameters(
      prm, directory, BoundingBox<dim>({geometry.lower_left, geometry.upper_right}));
    stokes_solver.parse_parameters(prm);
    stress.parse_parameters(prm);
    departure_feet.parse_parameters(prm);
    stabilization.parse_parameters(prm);
    detachment.parse_parameters(prm, boundary_conditions);
    release.parse_parameters(prm, detachment);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
    checkpointing.parse_parameters(prm);

  }
} // namespace viscofilm
