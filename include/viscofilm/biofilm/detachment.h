// Detachment (doc/detachment.md): biofilm whose load exceeds its strength,
// for a given duration, and biofilm cut off from the walls, is released from
// the attached biofilm φ into the detached fraction φ_d, which the flow
// carries (a passive tracer) and which leaves through outflow boundaries.
#ifndef viscofilm_detachment_h
#define viscofilm_detachment_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/biofilm/loads.h>
#include <viscofilm/material/model.h>
#include <viscofilm/transport/volume_fraction.h>

#include <optional>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class ElasticStress;
  class CsvFile;
  template <int dim>
  class DepartureFeet;

  template <int dim>
  class Detachment : public Reporter<dim>
  {
  public:
    struct Parameters
    {
      /// The load compared with the strength (Detachment/Stress threshold).
      enum class Criterion
      {
        von_mises,         // σ_vm of the total stress, in the biofilm
        interface_traction // |σ n| on the biofilm's outline
      };

      static void
      declare_parameters(ParameterHandler &prm);
      /// Walls' names are resolved with @p boundary_conditions.
      void
      parse_parameters(ParameterHandler &prm, const BoundaryConditions<dim> &boundary_conditions);

      /// The outline, the strength and the walls, which the loads read too.
      Biofilm<dim> biofilm;
      bool      enabled   = false;
      Criterion criterion = Criterion::von_mises;
      /// How long the load must exceed the strength before release.
      double duration = 0;
      /// Release the biofilm connected to none of Detachment/Walls too.
      bool release_unattached = true;
    };

    /// What has been released and what has left, kept by a checkpoint.
    struct Totals
    {
      double released = 0; // ∫ of every release since t = 0
      double outflow  = 0; // φ_d carried out through the boundary since t = 0
    };

    /// φ_d lives on @p triangulation with φ's element and transport scheme
    /// (@p transport).
    Detachment(const Parameters &                             parameters,
               const Model &                                  model,
               const parallel::distributed::Triangulation<dim> &triangulation,
               const typename VolumeFraction<dim>::Parameters & transport,
               const BoundaryConditions<dim> &                boundary_conditions,
               const StokesFlow<dim> &                      stokes,
               VolumeFraction<dim> &                          volume_fraction,
               const ElasticStress<dim> &                     stress);

    /// After VolumeFraction::setup_dofs(): the clocks of the duration (0).
    /// φ_d is a field of its own (detached_fraction()); φ carries the clocks
    /// through mesh changes and checkpoints.
    void
    setup_dofs();

    /// After any change of the mesh: the connectivity is built anew.
    void
    mesh_changed();

    /// After the transport of an accepted step of length @p time_step: φ_d
    /// carried by the step's flow as φ was (@p feet, @p order), then φ := 0
    /// at the nodes of the biofilm (φ >= the outline's value) whose load
    /// has exceeded the strength for the duration and, with Release
    /// unattached, at those connected to no wall; φ_d gains what φ lost.
    /// Collective.
    void
    release(DepartureFeet<dim> &feet, const double time_step, const unsigned int order);

    /// Columns detached_mass (this step), detached_by_connectivity (the part
    /// of it cut off from the walls), detached_mass_total,
    /// detached_mass_in_flow (∫φ_d), detached_mass_outflow and where this
    /// step's release came from: detached_centroid_<x>, detached_<x>_min,
    /// detached_<x>_max per coordinate (0 when nothing was released). Only
    /// with Detachment/Release = true, so that other runs' files keep their
    /// columns.
    void
    add_statistics(CsvFile &statistics, const double time) const override;

    /// phi_detached in the snapshots (with Release = true).
    void
    add_output(DataOut<dim> &data_out) override;

    /// φ_d, for the refinement indicator and Problem's list of fields; null
    /// with Release = false.
    const VolumeFraction<dim> *
    detached_fraction() const;
    VolumeFraction<dim> *
    detached_fraction();

    /// The Totals (detached, detached_outflow).
    void
    save_state(CheckpointValues &values) const override;
    void
    load_state(const CheckpointValues &values) override;

  private:
    /// The criterion's load at each owned node of φ in the biofilm (mean
    /// over the cells around the node of the value each cell's fields give
    /// there); 0 where the criterion does not apply.
    TrilinosWrappers::MPI::Vector
    nodal_load() const;

    /// Strength: φ := 0 in @p phi (owned values) at the owned nodes whose
    /// load has exceeded the strength for the duration, flagged in
    /// @p released (by owned index); advances the clocks.
    void
    release_by_strength(const double                   time_step,
                        TrilinosWrappers::MPI::Vector &phi,
                        std::vector<bool> &            released);

    /// Connectivity: φ := 0 in @p phi at the owned biofilm nodes that no
    /// path of biofilm nodes (through the cells, and the constraints'
    /// periodic and hanging-node links) joins to a node on a wall.
    /// @p ghosted_phi: φ with ghosts.
    void
    release_unattached(const TrilinosWrappers::MPI::Vector &ghosted_phi,
                       TrilinosWrappers::MPI::Vector &      phi,
                       std::vector<bool> &                  released);

    /// The mesh's part of the release by connectivity, which depends on
    /// no field: the nodes of each cell (owned or ghost) and each
    /// constraint's (node, master) pairs, by index within the locally
    /// relevant nodes, the nodes on a wall, the flood's ghost vectors.
    struct Connectivity
    {
      IndexSet                               relevant;
      std::vector<std::vector<unsigned int>> cells;
      std::vector<std::vector<unsigned int>> cells_of; // per node
      std::vector<unsigned int>              wall_nodes;
      TrilinosWrappers::MPI::Vector          shared; // writable ghosts
      TrilinosWrappers::MPI::Vector          seen;   // ghosted
      TrilinosWrappers::MPI::Vector          sum;    // owned
    };

    /// Build connectivity for the current mesh.
    void
    build_connectivity();

    /// Mass, centroid and bounding box of the release @p released (φ's
    /// loss, ghosted).
    void
    record(const TrilinosWrappers::MPI::Vector &released,
           const std::vector<Point<dim>> &      released_nodes);

    const Parameters &              parameters;
    const Model &                   model;
    const StokesFlow<dim> &       stokes;
    VolumeFraction<dim> &           volume_fraction;
    const ElasticStress<dim> &      stress;
    const BoundaryConditions<dim> & boundary_conditions;

    /// φ_d: the detached biofilm, a passive tracer (doc/detachment.md).
    VolumeFraction<dim> detached;

    /// Per node of φ: how long the load has exceeded the strength (ghosted;
    /// only with Duration > 0).
    TrilinosWrappers::MPI::Vector                  clock;

    /// Built at the first release on a mesh (doc/detachment.md).
    std::optional<Connectivity> connectivity;

    double     step_mass         = 0;
    double     connectivity_mass = 0; // the part of step_mass cut off
    Totals     total;
    Point<dim> centroid;
    Point<dim> lower, upper; // the released nodes' bounding box
  };
} // namespace viscofilm

#endif
