// All run parameters: each component declares and parses its own subsection;
// this collects them and checks what spans several subsections.
#ifndef viscofilm_parameters_h
#define viscofilm_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/core/checkpoint.h>
#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/biofilm/detachment.h>
#include <viscofilm/geometry/geometry.h>
#include <viscofilm/biofilm/initial_conditions.h>
#include <viscofilm/biofilm/loads.h>
#include <viscofilm/geometry/mesh_refinement.h>
#include <viscofilm/material/model.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/core/time_stepping.h>
#include <viscofilm/postprocess/verification.h>
#include <viscofilm/transport/substrate.h>
#include <viscofilm/biofilm/growth.h>
#include <viscofilm/transport/volume_fraction.h>

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
    typename MeshRefinement<dim>::Parameters mesh_refinement;
    TimeStepping             time_stepping;
    Model                    model;
    BoundaryConditions<dim>  boundary_conditions;
    InitialConditions<dim>   initial_conditions;
    // Named after what they hold; the prm subsection, where it differs, in
    // the comment.
    typename StokesFlow<dim>::Parameters     stokes_solver;
    typename ElasticStress<dim>::Parameters  stress;
    typename DepartureFeet<dim>::Parameters  departure_feet;
    typename VolumeFraction<dim>::Parameters volume_fraction; // Stabilization
    typename Substrate<dim>::Parameters      substrate;
    typename Growth<dim>::Parameters         growth;
    typename BiofilmLoads<dim>::Parameters   loads; // Forces
    typename Detachment<dim>::Parameters     detachment;
    typename Output<dim>::Parameters output;
    typename Verification<dim>::Parameters verification;
    typename Checkpoint<dim>::Parameters checkpointing;
  };
} // namespace viscofilm

#endif
