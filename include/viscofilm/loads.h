// Loads on the biofilm (the thesis' future work, doc/loads.md): the total
// stress σ = −p I + 2η(φ) D(u) + φτ evaluated as wall shear stress, traction
// on the biofilm interface and a von Mises detachment indicator.
#ifndef viscofilm_loads_h
#define viscofilm_loads_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <viscofilm/model.h>

#include <memory>

namespace viscofilm
{
  using namespace dealii;

  class StokesSolver;
  class VolumeFraction;
  class ElasticStress;
  class CsvFile;

  class BiofilmLoads
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// σ_vm above which the biofilm counts as prone to detach.
      double stress_threshold = 1.0;
      /// The biofilm is φ >= this; its interface the contour φ = this.
      double interface_level = 0.05;
    };

    BiofilmLoads(const Parameters &    parameters,
                 const Model &         model,
                 const StokesSolver &  stokes,
                 const VolumeFraction &volume_fraction,
                 const ElasticStress & stress);

    /// Columns wall_shear_stress_mean/max, interface_traction_mean/max,
    /// von_mises_max, detachment_area (collective).
    void
    add_statistics(CsvFile &statistics) const;

    /// Fields shear_stress (σ_xy) and von_mises (σ_vm) in the snapshots.
    void
    add_output(DataOut<2> &data_out);

  private:
    const Parameters &    parameters;
    const Model &         model;
    const StokesSolver &  stokes;
    const VolumeFraction &volume_fraction;
    const ElasticStress & stress;

    std::unique_ptr<DataPostprocessor<2>> postprocessor;
  };
} // namespace viscofilm

#endif
