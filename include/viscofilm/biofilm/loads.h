// Loads on the biofilm (the thesis' future work, doc/loads.md): the total
// stress σ = −p I + 2η(φ) D(u) + φτ evaluated as wall shear stress, traction
// on the biofilm interface, a von Mises detachment indicator and the force on
// named boundaries.
#ifndef viscofilm_loads_h
#define viscofilm_loads_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <viscofilm/biofilm/biofilm.h>
#include <viscofilm/core/dimension.h>
#include <viscofilm/core/reporter.h>
#include <viscofilm/material/model.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class VolumeFraction;
  template <int dim>
  class ElasticStress;
  class CsvFile;
  template <int dim>
  class BoundaryConditions;

  template <int dim>
  class BiofilmLoads : public Reporter<dim>
  {
  public:
    struct Parameters
    {
      /// How the force on a boundary is computed.
      enum class ForceMethod
      {
        consistent,      // −R(v): the residual of the discrete momentum equation
        surface_integral // −∫_Γ σ n ds with the face values of the fields
      };

      static void
      declare_parameters(ParameterHandler &prm);
      /// Boundary names are resolved with @p boundary_conditions.
      void
      parse_parameters(ParameterHandler &        prm,
                       const BoundaryConditions<dim> &boundary_conditions);

      /// The boundaries whose force goes into statistics.csv.
      std::vector<NamedBoundaryId> force_boundaries;
      ForceMethod                force_method = ForceMethod::consistent;
    };

    /// @p biofilm: the outline, the strength and the walls (Detachment).
    BiofilmLoads(const Parameters &    parameters,
                 const Biofilm<dim> &  biofilm,
                 const Model &         model,
                 const StokesFlow<dim> & stokes,
                 const VolumeFraction<dim> &volume_fraction,
                 const ElasticStress<dim> & stress);

    /// Columns wall_shear_stress_mean/max, interface_traction_mean/max,
    /// von_mises_max, detachment_area and force_x_<name>, force_y_<name>
    /// (and force_z_<name> in 3D) per force boundary: per unit depth in 2D,
    /// totals in 3D (collective).
    void
    add_statistics(CsvFile &statistics, const double time) const override;

    /// Fields shear_stress (σ_xy) and von_mises (σ_vm) in the snapshots.
    void
    add_output(DataOut<dim> &data_out) override;

  private:
    /// The force the fluid exerts on each force boundary (collective).
    std::vector<Tensor<1, dim>>
    boundary_forces() const;
    /// This rank's part of the forces by Forces/Method.
    std::vector<Tensor<1, dim>>
    surface_integral_forces() const;
    std::vector<Tensor<1, dim>>
    consistent_forces() const;

    const Parameters &    parameters;
    const Biofilm<dim> &  biofilm;
    const Model &         model;
    const StokesFlow<dim> & stokes;
    const VolumeFraction<dim> &volume_fraction;
    const ElasticStress<dim> & stress;

    std::unique_ptr<DataPostprocessor<dim>> postprocessor;
  };
} // namespace viscofilm

#endif
