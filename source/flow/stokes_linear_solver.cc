#include <viscofilm/flow/stokes_linear_solver.h>

namespace viscofilm
{
  template <int dim>
  std::unique_ptr<StokesLinearSolver<dim>>
  StokesLinearSolver<dim>::create(const typename StokesFlow<dim>::Method      method,
                                  const typename StokesFlow<dim>::Parameters &parameters,
                                  const double                                  reference_viscosity,
                                  const BoundaryConditions<dim> &               boundary_conditions)
  {
    switch (method)
      {
        case StokesFlow<dim>::Method::direct:
          return make_direct_solver<dim>(parameters);
        case StokesFlow<dim>::Method::thesis:
          return make_thesis_solver<dim>(parameters);
        case StokesFlow<dim>::Method::block_preconditioned:
          return make_block_preconditioned_solver<dim>(parameters,
                                                       reference_viscosity,
                                                       boundary_conditions);
        default:
          Assert(false, ExcInternalError()); // auto: StokesFlow chooses
          return nullptr;
      }
  }


  template <int dim>
  unsigned int
  StokesLinearSolver<dim>::n_preconditioner_builds() const
  {
    return 0;
  }


  template <int dim>
  std::string
  StokesLinearSolver<dim>::velocity_preconditioner() const
  {
    return "";
  }


  template <int dim>
  double
  StokesLinearSolver<dim>::viscosity_change_since_build() const
  {
    return 0;
  }


  VISCOFILM_INSTANTIATE(StokesLinearSolver)
} // namespace viscofilm
