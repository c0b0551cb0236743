// Stabilization/Volume fraction scheme = thesis: GLS-stabilised Galerkin,
// implicit Euler (thesis eq. 3.47-3.50); softening by Galerkin diffusion.
// Not bounded.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/transport/transport_scheme.h>

#include <cmath>

namespace viscofilm
{
  namespace
  {
    template <int dim>
    class GlsScheme : public TransportScheme<dim>
    {
    public:
      GlsScheme(const typename VolumeFraction<dim>::Parameters &parameters,
                VolumeFraction<dim> &                          phi)
        : TransportScheme<dim>(phi)
        , parameters(parameters)
      {}

      bool
      bounded() const override
      {
        return false;
      }

      /// φ transported with u^{n+1}, as the thesis does (either order).
      unsigned int
      advance(const StokesFlow<dim> &stokes,
              DepartureFeet<dim> &,
              const double diffusion,
              const double time_step,
              const unsigned int,
              const bool) override
      {
        this->phi.add_exchange(this->phi.boundary_flux(stokes.dof_handler(), stokes.solution()),
                               time_step);
        return step(&stokes, diffusion, time_step);
      }

      void
      diffuse(const double diffusion, const double time_step) override
      {
        step(nullptr, diffusion, time_step);
      }

    private:
      /// The thesis' step, implicit; without @p stokes: pure φ-scaled
      /// diffusion.
      unsigned int
      step(const StokesFlow<dim> *stokes, const double diffusion, const double time_step);

      const typename VolumeFraction<dim>::Parameters &parameters;
    };


    template <int dim>
    unsigned int
    GlsScheme<dim>::step(const StokesFlow<dim> *stokes,
                         const double           diffusion,
                         const double           time_step)
    {
      this->phi.make_constraints(stokes);
      TrilinosWrappers::SparseMatrix &system_matrix = this->system_matrix();
      TrilinosWrappers::MPI::Vector & system_rhs    = this->system_rhs();
      system_matrix                                 = 0;
      system_rhs                                    = 0;

      const FE_Q<dim> & fe = this->fe();
      const QGauss<dim> quadrature(fe.degree + 1);
      FEValues<dim>     fe_values(this->phi.mapping(),
                              fe,
                              quadrature,
                              update_values | update_gradients | update_JxW_values);
      std::unique_ptr<FEValues<dim>> stokes_values;
      if (stokes != nullptr)
        stokes_values = std::make_unique<FEValues<dim>>(this->phi.mapping(),
                                                        stokes->dof_handler().get_fe(),
                                                        quadrature,
                                                        update_values);
      const FEValuesExtractors::Vector velocities(0);

      const unsigned int                   n_dofs = fe.n_dofs_per_cell();
      const unsigned int                   n_q    = quadrature.size();
      FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
      Vector<double>                       cell_rhs(n_dofs);
      std::vector<types::global_dof_index> local_dofs(n_dofs);
      std::vector<double>                  phi_old(n_q);
      std::vector<Tensor<1, dim>>          velocity(n_q);
      std::vector<double>                  streamline(n_dofs); // ψ_i/k + u·∇ψ_i
      const double                         k = time_step;

      for (const auto &cell : this->dofs().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values.get_function_values(this->solution(), phi_old);
            if (stokes != nullptr)
              {
                stokes_values->reinit(cell_of(stokes->dof_handler(), cell));
                (*stokes_values)[velocities].get_function_values(stokes->solution(), velocity);
              }
            // The edge of a square/cube cell.
            const double h = cell->diameter() / std::sqrt(double(dim));

            cell_matrix = 0;
            cell_rhs    = 0;
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const Tensor<1, dim> u = (stokes != nullptr ? velocity[q] : Tensor<1, dim>());
                double               tau = 0;
                if (stokes != nullptr)
                  tau = parameters.standard_tau ?
                          parameters.gls_parameter /
                            std::sqrt(4 / (k * k) + std::pow(2 * u.norm() / h, 2)) :
                          parameters.gls_parameter;
                // φ-scaled diffusion D φ^n (eq. 3.45), φ^n clipped at 0.
                const double kappa = k * diffusion * std::max(phi_old[q], 0.0);
                const double JxW   = fe_values.JxW(q);
                for (unsigned int i = 0; i < n_dofs; ++i)
                  streamline[i] =
                    fe_values.shape_value(i, q) / k + u * fe_values.shape_grad(i, q);
                // eq. 3.49/3.50
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    const double          psi_i      = fe_values.shape_value(i, q);
                    const Tensor<1, dim> &grad_psi_i = fe_values.shape_grad(i, q);
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      cell_matrix(i, j) += (psi_i * fe_values.shape_value(j, q) +
                                            kappa * (grad_psi_i * fe_values.shape_grad(j, q)) +
                                            k * psi_i * (u * fe_values.shape_grad(j, q)) +
                                            tau * k * streamline[i] * streamline[j]) *
                                           JxW;
                    cell_rhs(i) += (phi_old[q] * psi_i + tau * phi_old[q] * streamline[i]) * JxW;
                  }
              }
            cell->get_dof_indices(local_dofs);
            this->constraints().distribute_local_to_global(
              cell_matrix, cell_rhs, local_dofs, system_matrix, system_rhs);
          }
      system_matrix.compress(VectorOperation::add);
      system_rhs.compress(VectorOperation::add);
      return this->phi.solve();
    }
  } // namespace


  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  make_gls_scheme(const typename VolumeFraction<dim>::Parameters &parameters,
                  VolumeFraction<dim> &                          phi)
  {
    return std::make_unique<GlsScheme<dim>>(parameters, phi);
  }


#define INSTANTIATE(dim)                                                                       \
  template std::unique_ptr<TransportScheme<dim>> make_gls_scheme<dim>(                           \
    const typename VolumeFraction<dim>::Parameters &, VolumeFraction<dim> &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
