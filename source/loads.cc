#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <viscofilm/geometry.h>
#include <viscofilm/input.h>
#include <viscofilm/loads.h>
#include <viscofilm/output.h>
#include <viscofilm/stokes.h>
#include <viscofilm/stress.h>
#include <viscofilm/volume_fraction.h>

#include <cmath>

namespace viscofilm
{
  namespace
  {
    /// von Mises equivalent sqrt(3 J2) of the in-plane deviator of σ.
    double
    von_mises(const SymmetricTensor<2, 2> &sigma)
    {
      const double half_difference = 0.5 * (sigma[0][0] - sigma[1][1]);
      return std::sqrt(3 * (half_difference * half_difference +
                            sigma[0][1] * sigma[0][1]));
    }


    /**
     * σ = −p I + 2η(φ) D(u) + φτ, φ and ∇φ at the points of a cell or face:
     * FEValuesType is FEValues<2> or FEFaceValues<2>, with one object per
     * field (they live on different DoFHandlers of the same mesh).
     */
    template <class FEValuesType>
    class TotalStress
    {
    public:
      template <class QuadratureType>
      TotalStress(const QuadratureType &quadrature,
                  const Model &         model,
                  const StokesSolver &  stokes,
                  const VolumeFraction &volume_fraction,
                  const ElasticStress & stress)
        : model(model)
        , stokes(stokes)
        , volume_fraction(volume_fraction)
        , stress(stress)
        , stokes_values(stokes.dof_handler().get_fe(),
                        quadrature,
                        update_values | update_gradients | update_JxW_values)
        , phi_values(volume_fraction.dof_handler().get_fe(),
                     quadrature,
                     update_values | update_gradients)
        , stress_values(stress.dof_handler().get_fe(), quadrature, update_values)
        , sigma(quadrature.size())
        , phi(quadrature.size())
        , grad_phi(quadrature.size())
        , velocity_gradient(quadrature.size())
        , pressure(quadrature.size())
        , conformation(quadrature.size(), Vector<double>(3))
      {}

      /// Evaluate on @p cell (a cell of any of the DoFHandlers), or on its
      /// face @p face.
      template <class CellIterator, typename... Face>
      void
      reinit(const CellIterator &cell, const Face... face)
      {
        const auto on = [&](const DoFHandler<2> &dofs) {
          return DoFHandler<2>::active_cell_iterator(&dofs.get_triangulation(),
                                                     cell->level(),
                                                     cell->index(),
                                                     &dofs);
        };
        stokes_values.reinit(on(stokes.dof_handler()), face...);
        phi_values.reinit(on(volume_fraction.dof_handler()), face...);
        stress_values.reinit(on(stress.dof_handler()), face...);

        const FEValuesExtractors::Vector velocities(0);
        const FEValuesExtractors::Scalar pressure_component(2);
        stokes_values[velocities].get_function_symmetric_gradients(stokes.solution(),
                                                                   velocity_gradient);
        stokes_values[pressure_component].get_function_values(stokes.solution(),
                                                              pressure);
        phi_values.get_function_values(volume_fraction.solution(), phi);
        phi_values.get_function_gradients(volume_fraction.solution(), grad_phi);
        stress_values.get_function_values(stress.solution(), conformation);
        for (unsigned int q = 0; q < sigma.size(); ++q)
          {
            sigma[q] = -pressure[q] * unit_symmetric_tensor<2>() +
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

    private:
      const Model &         model;
      const StokesSolver &  stokes;
      const VolumeFraction &volume_fraction;
      const ElasticStress & stress;
      FEValuesType          stokes_values;
      FEValuesType          phi_values;
      FEValuesType          stress_values;

    public:
      std::vector<SymmetricTensor<2, 2>> sigma;
      std::vector<double>                phi;
      std::vector<Tensor<1, 2>>          grad_phi;

    private:
      std::vector<SymmetricTensor<2, 2>> velocity_gradient;
      std::vector<double>                pressure;
      std::vector<Vector<double>>        conformation;
    };


    /// σ_xy and σ_vm at the points DataOut evaluates (2 subdivisions).
    class LoadsPostprocessor : public DataPostprocessor<2>
    {
    public:
      LoadsPostprocessor(const Model &         model,
                         const StokesSolver &  stokes,
                         const VolumeFraction &volume_fraction,
                         const ElasticStress & stress)
        : points(QTrapezoid<1>(), 2)
        , model(model)
        , stokes(stokes)
        , volume_fraction(volume_fraction)
        , stress(stress)
      {}

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<2> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        AssertThrow(inputs.solution_values.size() == points.size(),
                    ExcInternalError());
        // One per call: DataOut calls this from several threads.
        TotalStress<FEValues<2>> total_stress(
          points, model, stokes, volume_fraction, stress);
        total_stress.reinit(inputs.template get_cell<2>());
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            computed[q][0] = total_stress.sigma[q][0][1];
            computed[q][1] = von_mises(total_stress.sigma[q]);
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        return {"shear_stress", "von_mises"};
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values;
      }

    private:
      // DataOut's points for build_patches(2), in its order.
      const QIterated<2>    points;
      const Model &         model;
      const StokesSolver &  stokes;
      const VolumeFraction &volume_fraction;
      const ElasticStress & stress;
    };
  } // namespace


  void
  BiofilmLoads::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Detachment");
    prm.declare_entry("Stress threshold",
                      "1",
                      Patterns::Double(0),
                      "von Mises stress of the total stress above which the "
                      "biofilm counts as prone to detach (statistics.csv: "
                      "detachment_area), in units of ηs U0/L0 (≈ 0.0167 Pa with "
                      "Table 4.1).");
    prm.declare_entry("Interface volume fraction",
                      "0.05",
                      Patterns::Double(0, 1),
                      "φ of the biofilm outline: the biofilm is φ >= this, its "
                      "interface the contour φ = this. In (0, 1).");
    prm.leave_subsection();
  }


  void
  BiofilmLoads::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Detachment");
    stress_threshold = prm.get_double("Stress threshold");
    interface_level  = prm.get_double("Interface volume fraction");
    prm.leave_subsection();
    check_input(interface_level > 0 && interface_level < 1,
                "Detachment/Interface volume fraction must be in (0, 1), got " +
                  to_text(interface_level));
  }


  BiofilmLoads::BiofilmLoads(const Parameters &    parameters,
                             const Model &         model,
                             const StokesSolver &  stokes,
                             const VolumeFraction &volume_fraction,
                             const ElasticStress & stress)
    : parameters(parameters)
    , model(model)
    , stokes(stokes)
    , volume_fraction(volume_fraction)
    , stress(stress)
    , postprocessor(
        std::make_unique<LoadsPostprocessor>(model, stokes, volume_fraction, stress))
  {}


  void
  BiofilmLoads::add_statistics(CsvFile &statistics) const
  {
    const QGauss<2> quadrature(3);
    const QGauss<1> face_quadrature(3);
    TotalStress<FEValues<2>>     cell_stress(quadrature, model, stokes, volume_fraction, stress);
    TotalStress<FEFaceValues<2>> wall_stress(
      face_quadrature, model, stokes, volume_fraction, stress);
    const double level = parameters.interface_level;

    // sums: wall ∫σ_xy, wall length, interface ∫|σn|, interface measure,
    // detachment area; maxima: |σ_xy| on the wall, |σn|, σ_vm
    double sums[5]   = {0, 0, 0, 0, 0};
    double maxima[3] = {0, 0, 0};
    for (const auto &cell : stokes.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == BoundaryId::bottom)
              {
                wall_stress.reinit(cell, f);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    sums[0] += wall_stress.sigma[q][0][1] * wall_stress.JxW(q);
                    sums[1] += wall_stress.JxW(q);
                    maxima[0] = std::max(maxima[0], std::abs(wall_stress.sigma[q][0][1]));
                  }
              }

          cell_stress.reinit(cell);
          const auto [low, high] =
            std::minmax_element(cell_stress.phi.begin(), cell_stress.phi.end());
          const bool cut = (*low < level && *high > level);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const SymmetricTensor<2, 2> &sigma = cell_stress.sigma[q];
              if (cut && cell_stress.grad_phi[q].norm() > 0)
                {
                  // n points out of the biofilm: down the gradient of φ.
                  const Tensor<1, 2> n =
                    -cell_stress.grad_phi[q] / cell_stress.grad_phi[q].norm();
                  const double traction = (sigma * n).norm();
                  sums[2] += traction * cell_stress.JxW(q);
                  sums[3] += cell_stress.JxW(q);
                  maxima[1] = std::max(maxima[1], traction);
                }
              if (cell_stress.phi[q] >= level)
                {
                  const double equivalent = von_mises(sigma);
                  maxima[2] = std::max(maxima[2], equivalent);
                  if (equivalent > parameters.stress_threshold)
                    sums[4] += cell_stress.JxW(q);
                }
            }
        }
    const MPI_Comm comm = stokes.dof_handler().get_communicator();
    Utilities::MPI::sum(sums, comm, sums);
    Utilities::MPI::max(maxima, comm, maxima);

    statistics.set("wall_shear_stress_mean", sums[1] > 0 ? sums[0] / sums[1] : 0);
    statistics.set("wall_shear_stress_max", maxima[0]);
    statistics.set("interface_traction_mean", sums[3] > 0 ? sums[2] / sums[3] : 0);
    statistics.set("interface_traction_max", maxima[1]);
    statistics.set("von_mises_max", maxima[2]);
    statistics.set("detachment_area", sums[4]);
  }


  void
  BiofilmLoads::add_output(DataOut<2> &data_out)
  {
    data_out.add_data_vector(stokes.dof_handler(), stokes.solution(), *postprocessor);
  }
} // namespace viscofilm
