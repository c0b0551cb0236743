// Detachment (doc/detachment.md): biofilm whose load exceeds its strength,
// for a given duration, is released from the attached biofilm φ and counted
// as detached mass, which the flow carries away.
#ifndef viscofilm_detachment_h
#define viscofilm_detachment_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <viscofilm/dimension.h>
#include <viscofilm/loads.h>
#include <viscofilm/mesh_refinement.h>
#include <viscofilm/model.h>

namespace viscofilm
{
  using namespace dealii;

  class StokesSolver;
  class VolumeFraction;
  class ElasticStress;
  class CsvFile;

  class Detachment
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
      void
      parse_parameters(ParameterHandler &prm);

      bool      enabled   = false;
      Criterion criterion = Criterion::von_mises;
      /// How long the load must exceed the strength before release.
      double duration = 0;
    };

    /// The strength and the biofilm's outline are @p loads' Stress threshold
    /// and Interface volume fraction.
    Detachment(const Parameters &              parameters,
               const BiofilmLoads::Parameters &loads,
               const Model &                   model,
               const StokesSolver &            stokes,
               VolumeFraction &                volume_fraction,
               const ElasticStress &           stress);

    /// After VolumeFraction::setup_dofs(): the clocks of the duration.
    void
    setup_dofs();

    /// After the transport of a step of length @p time_step: φ := 0 at the
    /// nodes of the biofilm (φ >= the outline's value) whose load has
    /// exceeded the strength for the duration. Collective.
    void
    release(const double time_step);

    /// Columns detached_mass (this step), detached_mass_total and where this
    /// step's release came from: detached_centroid_<x>, detached_<x>_min,
    /// detached_<x>_max per coordinate (0 when nothing was released). Only
    /// with Detachment/Release = true, so that other runs' files keep their
    /// columns.
    void
    add_statistics(CsvFile &statistics) const;

    /// The total released so far, kept by a checkpoint.
    double
    total_mass() const;
    void
    set_total_mass(const double mass);

    /// Keep the clocks across a mesh change and a checkpoint (as
    /// VolumeFraction; nothing to keep with Duration = 0).
    void
    prepare_for_refinement();
    void
    finish_refinement();
    void
    prepare_for_checkpoint();
    void
    checkpoint_written();

  private:
    /// The criterion's load at each owned node of φ in the biofilm (mean
    /// over the cells around the node of the value each cell's fields give
    /// there); 0 where the criterion does not apply.
    TrilinosWrappers::MPI::Vector
    nodal_load() const;

    /// Mass, centroid and bounding box of the release @p released (φ's
    /// loss, ghosted).
    void
    record(const TrilinosWrappers::MPI::Vector &released,
           const std::vector<Point<dim>> &      released_nodes);

    const Parameters &              parameters;
    const BiofilmLoads::Parameters &loads;
    const Model &                   model;
    const StokesSolver &            stokes;
    VolumeFraction &                volume_fraction;
    const ElasticStress &           stress;

    /// Per node of φ: how long the load has exceeded the strength (ghosted;
    /// only with Duration > 0).
    TrilinosWrappers::MPI::Vector                  clock;
    SolutionCarrier<TrilinosWrappers::MPI::Vector> carrier;

    double     step_mass  = 0;
    double     total      = 0;
    Point<dim> centroid;
    Point<dim> lower, upper; // the released nodes' bounding box
  };
} // namespace viscofilm

#endif
