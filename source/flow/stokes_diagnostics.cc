// What the Stokes solution tells about the flow: output fields (∇·u, the
// vorticity, |u·∇u|), max |u|, the cell-wise divergence, Kelly's velocity
// indicator and the Picard criterion on u.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/error_estimator.h>

#include <viscofilm/flow/stokes.h>
#include <viscofilm/postprocess/output.h>

#include <cmath>

namespace viscofilm
{
  namespace
  {
    /// ∇·u, the vorticity ∇×u (2D: the scalar ∂v/∂x − ∂u/∂y) and |u·∇u|
    /// from the Stokes solution.
    template <int dim>
    class FlowPostprocessor : public DataPostprocessor<dim>
    {
    public:
      static constexpr unsigned int n_vorticity_components = dim == 2 ? 1 : dim;

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        for (unsigned int q = 0; q < inputs.solution_values.size(); ++q)
          {
            const auto &   grad = inputs.solution_gradients[q];
            Tensor<1, dim> u;
            for (unsigned int d = 0; d < dim; ++d)
              u[d] = inputs.solution_values[q][d];
            Tensor<1, dim> convection;
            double         divergence = 0;
            for (unsigned int i = 0; i < dim; ++i)
              {
                convection[i] = u * grad[i];
                divergence += grad[i][i];
              }
            computed[q][0] = divergence;
            // (∇×u)_i = ∂_j u_k − ∂_k u_j for (i, j, k) cyclic; 2D: i = z.
            for (unsigned int i = 0; i < n_vorticity_components; ++i)
              {
                const unsigned int j = (dim == 2 ? 0 : (i + 1) % 3), k = (j + 1) % dim;
                computed[q][1 + i] = grad[k][j] - grad[j][k];
              }
            computed[q][1 + n_vorticity_components] = convection.norm();
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names = {"divergence"};
        for (unsigned int i = 0; i < n_vorticity_components; ++i)
          names.push_back("vorticity");
        names.push_back("inertia");
        return names;
      }

      /// The vorticity is a vector in 3D (one dataset of three components).
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        std::vector<DataComponentInterpretation::DataComponentInterpretation>
          interpretation(2 + n_vorticity_components,
                         DataComponentInterpretation::component_is_scalar);
        if (dim == 3)
          for (unsigned int i = 0; i < n_vorticity_components; ++i)
            interpretation[1 + i] = DataComponentInterpretation::component_is_part_of_vector;
        return interpretation;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values | update_gradients;
      }
    };
  } // namespace


  template <int dim>
  void
  StokesFlow<dim>::add_output(DataOut<dim> &data_out)
  {
    std::vector<std::string> names(dim, "velocity");
    names.push_back("pressure");
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim, DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);
    data_out.add_data_vector(dofs, current_solution, names, interpretation);
    // DataOut keeps a pointer to the postprocessor until it is done.
    static const FlowPostprocessor<dim> flow_postprocessor;
    data_out.add_data_vector(dofs, current_solution, flow_postprocessor);
  }


  template <int dim>
  void
  StokesFlow<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    statistics.set("stokes_preconditioner_builds", n_preconditioner_builds());
    statistics.set("stokes_viscosity_change", viscosity_change_since_build());
    statistics.set("max_velocity", max_velocity());
    statistics.set("max_cell_divergence", max_cell_divergence());
  }


  template <int dim>
  double
  StokesFlow<dim>::max_velocity() const
  {
    const Quadrature<dim> nodes(fe.base_element(0).get_unit_support_points());
    FEValues<dim>         fe_values(fe, nodes, update_values);
    std::vector<Tensor<1, dim>> velocity(nodes.size());
    const FEValuesExtractors::Vector velocities(0);
    double                    max_speed = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current_solution, velocity);
          for (const Tensor<1, dim> &u : velocity)
            max_speed = std::max(max_speed, u.norm());
        }
    return Utilities::MPI::max(max_speed, mpi_communicator);
  }


  template <int dim>
  double
  StokesFlow<dim>::max_cell_divergence() const
  {
    const QGauss<dim>                  quadrature(fe.degree + 1);
    FEValues<dim>                      fe_values(this->mapping(),
                                               fe,
                                               quadrature,
                                               update_gradients | update_JxW_values);
    std::vector<double>              divergence(quadrature.size());
    const FEValuesExtractors::Vector velocities(0);
    double                           max_divergence = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_divergences(current_solution, divergence);
          double integral = 0, measure = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              integral += divergence[q] * fe_values.JxW(q);
              measure += fe_values.JxW(q);
            }
          max_divergence = std::max(max_divergence, std::abs(integral) / measure);
        }
    return Utilities::MPI::max(max_divergence, mpi_communicator);
  }


  template <int dim>
  Vector<float>
  StokesFlow<dim>::velocity_error_indicator() const
  {
    Vector<float> indicator(triangulation.n_active_cells());
    KellyErrorEstimator<dim>::estimate(this->mapping(),
                                     dofs,
                                     QGauss<dim - 1>(fe.degree + 1),
                                     {},
                                     current_solution,
                                     indicator,
                                     fe.component_mask(FEValuesExtractors::Vector(0)));
    return indicator;
  }


  template <int dim>
  double
  StokesFlow<dim>::velocity_relative_change(
    const TrilinosWrappers::MPI::BlockVector &previous) const
  {
    // ‖u − u_prev‖_L2 / ‖u‖_L2: the velocity alone, as the pressure's size
    // (which grows with the viscosity) says nothing about the flow's change.
    FEValues<dim> fe_values(this->mapping(),
                            fe,
                            quadrature(),
                            update_values | update_JxW_values);
    const FEValuesExtractors::Vector velocities(0);
    std::vector<Tensor<1, dim>>        now(fe_values.n_quadrature_points);
    std::vector<Tensor<1, dim>>        before(fe_values.n_quadrature_points);
    double                           squares[2] = {0, 0}; // change, size
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current_solution, now);
          fe_values[velocities].get_function_values(previous, before);
          for (unsigned int q = 0; q < now.size(); ++q)
            {
              squares[0] += (now[q] - before[q]).norm_square() * fe_values.JxW(q);
              squares[1] += now[q].norm_square() * fe_values.JxW(q);
            }
        }
    Utilities::MPI::sum(squares, mpi_communicator, squares);
    return squares[1] > 0 ? std::sqrt(squares[0] / squares[1]) : std::sqrt(squares[0]);
  }


  // The class is instantiated once, in stokes.cc; each file instantiates the
  // members it defines (an explicit instantiation of the whole class in two
  // files would be ill-formed).
#define INSTANTIATE(dim)                                                          \
  template void StokesFlow<dim>::add_output(DataOut<dim> &);                      \
  template void StokesFlow<dim>::add_statistics(CsvFile &, const double) const;   \
  template double StokesFlow<dim>::max_velocity() const;                          \
  template double StokesFlow<dim>::max_cell_divergence() const;                   \
  template Vector<float> StokesFlow<dim>::velocity_error_indicator() const;       \
  template double StokesFlow<dim>::velocity_relative_change(                      \
    const TrilinosWrappers::MPI::BlockVector &) const;

  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
