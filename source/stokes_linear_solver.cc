#include <viscofilm/stokes_linear_solver.h>

namespace viscofilm
{
  std::unique_ptr<StokesLinearSolver>
  StokesLinearSolver::create(const StokesSolver::Parameters &parameters, const Model &model)
  {
    switch (parameters.method)
      {
        case StokesSolver::Method::direct:
          return make_direct_solver(parameters);
        case StokesSolver::Method::thesis:
          return make_thesis_solver(parameters);
        default:
          return make_block_preconditioned_solver(parameters, model);
      }
  }


  unsigned int
  StokesLinearSolver::n_preconditioner_builds() const
  {
    return 0;
  }


  double
  StokesLinearSolver::viscosity_change_since_build() const
  {
    return 0;
  }
} // namespace viscofilm
