#include <viscofilm/core/parameters.h>
#include <viscofilm/core/input.h>

namespace viscofilm
{
  template <int dim>
  void
  Parameters<dim>::declare_parameters(ParameterHandler &                     prm,
                                 const std::vector<typename Geometry<dim>::NamedBoundary> &boundaries)
  {
    Geometry<dim>::declare_parameters(prm);
    MeshRefinement<dim>::Parameters::declare_parameters(prm);
    TimeStepping::declare_parameters(prm);
    Model::declare_parameters(prm);
    BoundaryConditions<dim>::declare_parameters(prm, boundaries);
    InitialConditions<dim>::declare_parameters(prm);
    StokesFlow<dim>::Parameters::declare_parameters(prm);
    ElasticStress<dim>::Parameters::declare_parameters(prm);
    DepartureFeet<dim>::Parameters::declare_parameters(prm);
    VolumeFraction<dim>::Parameters::declare_parameters(prm);
    Substrate<dim>::Parameters::declare_parameters(prm);
    Growth<dim>::Parameters::declare_parameters(prm);
    BiofilmLoads<dim>::Parameters::declare_parameters(prm);
    Detachment<dim>::Parameters::declare_parameters(prm);
    Output<dim>::Parameters::declare_parameters(prm);
    Verification<dim>::Parameters::declare_parameters(prm);
    Checkpoint<dim>::Parameters::declare_parameters(prm);
  }


  template <int dim>
  void
  Parameters<dim>::parse_parameters(ParameterHandler &prm, const std::string &directory)
  {
    geometry.parse_parameters(prm, directory);
    mesh_refinement.parse_parameters(prm, geometry.initial_refinement);
    time_stepping.parse_parameters(prm);
    model.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm, geometry.boundaries());
    initial_conditions.parse_parameters(
      prm, directory, BoundingBox<dim>({geometry.lower_left, geometry.upper_right}));
    stokes_solver.parse_parameters(prm);
    check_input(stokes_solver.velocity_preconditioner !=
                    StokesFlow<dim>::VelocityPreconditioner::gmg ||
                  !boundary_conditions.has_periodic_pair(),
                "Stokes solver/Preconditioner/Velocity preconditioner = GMG does not "
                "support periodic boundaries (its levels have no periodic "
                "constraints); use Velocity preconditioner = AMG or auto");
    stress.parse_parameters(prm);
    // log c needs c positive definite, which it is only for a > 0 (a < 0
    // shifts c by the negative ηp/(a Wi)).
    check_input(!stress.logarithm_at_feet ||
                  (model.slip_parameter > 0 && model.relaxed_conformation() > 0),
                "Stress/Foot interpolation = logarithm needs a positive definite "
                "conformation c: Model/Slip parameter > 0 (given " +
                  to_text(model.slip_parameter) +
                  ") and a polymer viscosity > 0; use Foot interpolation = conformation");
    departure_feet.parse_parameters(prm);
    volume_fraction.parse_parameters(prm);
    substrate.parse_parameters(prm, boundary_conditions);
    growth.parse_parameters(prm, substrate.enabled, boundary_conditions);
    loads.parse_parameters(prm, boundary_conditions);
    detachment.parse_parameters(prm, boundary_conditions);
    // The growth places its biomass where φ is biofilm (at least the
    // interface level): it needs room between that and φmax.
    check_input(!growth.enabled ||
                  growth.maximum_volume_fraction > detachment.biofilm.interface_level,
                "Growth/Maximum volume fraction (" + to_text(growth.maximum_volume_fraction) +
                  ") must exceed Detachment/Interface volume fraction (" +
                  to_text(detachment.biofilm.interface_level) + ")");
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
    checkpointing.parse_parameters(prm);
  }


  VISCOFILM_INSTANTIATE(Parameters)
} // namespace viscofilm
