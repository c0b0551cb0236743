// The total stress σ = −p I + 2η(φ) D(u) + φτ of the mixture at the points of
// a cell or face, and its von Mises equivalent: what the loads
// (source/biofilm/loads.cc) and the detachment (source/biofilm/detachment.cc) evaluate.
#ifndef viscofilm_total_stress_h
#define viscofilm_total_stress_h

#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/vector.h>

#include <viscofilm/core/dimension.h>
#include <viscofilm/core/dof_cell.h>
#include <viscofilm/material/model.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/transport/volume_fraction.h>

#include <cmath>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// von Mises equivalent sqrt(3 J2) of σ, J2 = ½ s:s of its deviator s in
  /// dim dimensions: (σ_xx − σ_yy)²/4 + σ_xy² in 2D (the in-plane deviator),
  /// [(σ_xx − σ_yy)² + (σ_yy − σ_zz)² + (σ_zz − σ_xx)²]/6 + σ_xy² + σ_xz² +
  /// σ_yz² in 3D.
  template <int dim>
  inline double
  von_mises(const SymmetricTensor<2, dim> &sigma)
  {
    const SymmetricTensor<2, dim> s = deviator(sigma);
    return std::sqrt(1.5 * scalar_product(s, s));
  }


  /**
   * σ = −p I + 2η(φ) D(u) + φτ, φ and ∇φ at the points of a cell or face:
   * FEValuesType is FEValues<dim> or FEFaceValues<dim>, with one object per
   * field (they live on different DoFHandlers of the same mesh).
   */
  template <class FEValuesType>
  class TotalStress
  {
  public:
    static constexpr int dim = FEValuesType::dimension;

    template <class QuadratureType>
    TotalStress(const QuadratureType &quadrature,
                const Model &         model,
                const StokesFlow<dim> & stokes,
                const VolumeFraction<dim> &volume_fraction,
                const ElasticStress<dim> & stress,
                const UpdateFlags     extra_flags = update_default)
      : model(model)
      , stokes(stokes)
      , volume_fraction(volume_fraction)
      , stress(stress)
      , stokes_values(stokes.mapping(),
                      stokes.dof_handler().get_fe(),
                      quadrature,
                      update_values | update_gradients | update_JxW_values |
                        extra_flags)
      , phi_values(stokes.mapping(),
                   volume_fraction.dof_handler().get_fe(),
                   quadrature,
                   update_values | update_gradients)
      , stress_values(stokes.mapping(),
                      stress.dof_handler().get_fe(),
                      quadrature,
                      update_values)
      , sigma(quadrature.size())
      , phi(quadrature.size())
      , grad_phi(quadrature.size())
      , velocity_gradient(quadrature.size())
      , pressure(quadrature.size())
      , conformation(quadrature.size(), Vector<double>(n_symmetric_components<dim>))
    {}

    /// Evaluate on @p cell (a cell of any of the DoFHandlers), or on its
    /// face @p face.
    template <class CellIterator, typename... Face>
    void
    reinit(const CellIterator &cell, const Face... face)
    {
      stokes_values.reinit(cell_of(stokes.dof_handler(), cell), face...);
      phi_values.reinit(cell_of(volume_fraction.dof_handler(), cell), face...);
      stress_values.reinit(cell_of(stress.dof_handler(), cell), face...);

      const FEValuesExtractors::Vector velocities(0);
      const FEValuesExtractors::Scalar pressure_component(dim);
      stokes_values[velocities].get_function_symmetric_gradients(stokes.solution(),
                                                                 velocity_gradient);
      stokes_values[pressure_component].get_function_values(stokes.solution(),
                                                            pressure);
      phi_values.get_function_values(volume_fraction.solution(), phi);
      phi_values.get_function_gradients(volume_fraction.solution(), grad_phi);
      stress_values.get_function_values(stress.solution(), conformation);
      for (unsigned int q = 0; q < sigma.size(); ++q)
        {
          sigma[q] = -pressure[q] * unit_symmetric_tensor<dim>() +
                     2 * model.viscosity(phi[q]) * velocity_gradient[q];
          if (model.viscoelastic)
            sigma[q] += model.stress_coupling(phi[q]) *
                        stress.stress_of(conformation[q], phi[q]);
        }
    }

    double
    JxW(const unsigned int q) const
    {
      return stokes_values.JxW(q);
    }

    /// The Stokes element's values (shape functions, normals).
    const FEValuesType &
    stokes_fe_values() const
    {
      return stokes_values;
    }

  private:
    const Model &         model;
    const StokesFlow<dim> & stokes;
    const VolumeFraction<dim> &volume_fraction;
    const ElasticStress<dim> & stress;
    FEValuesType          stokes_values;
    FEValuesType          phi_values;
    FEValuesType          stress_values;

  public:
    std::vector<SymmetricTensor<2, dim>> sigma;
    std::vector<double>                phi;
    std::vector<Tensor<1, dim>>        grad_phi;

  private:
    std::vector<SymmetricTensor<2, dim>> velocity_gradient;
    std::vector<double>                pressure;
    std::vector<Vector<double>>        conformation;
  };

} // namespace viscofilm

#endif
