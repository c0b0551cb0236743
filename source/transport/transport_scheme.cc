#include <viscofilm/postprocess/output.h>
#include <viscofilm/transport/transport_scheme.h>

namespace viscofilm
{
  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  TransportScheme<dim>::create(const typename VolumeFraction<dim>::Parameters &parameters,
                               VolumeFraction<dim> &                          phi)
  {
    using Scheme = typename VolumeFraction<dim>::Parameters::Scheme;
    switch (parameters.scheme)
      {
        case Scheme::semi_lagrangian:
          return make_semi_lagrangian_scheme(phi);
        case Scheme::flux_corrected:
          return make_flux_corrected_scheme(phi);
        case Scheme::thesis:
          return make_gls_scheme(parameters, phi);
      }
    Assert(false, ExcInternalError());
    return nullptr;
  }


  template <int dim>
  TransportScheme<dim>::TransportScheme(VolumeFraction<dim> &phi)
    : phi(phi)
  {}


  template <int dim>
  double
  TransportScheme<dim>::error_estimate() const
  {
    return 0;
  }


  template <int dim>
  void
  TransportScheme<dim>::add_statistics(CsvFile &) const
  {}


  template <int dim>
  bool
  BoundedTransportScheme<dim>::bounded() const
  {
    return true;
  }


  template <int dim>
  double
  BoundedTransportScheme<dim>::error_estimate() const
  {
    return last_error_estimate;
  }


  template <int dim>
  void
  BoundedTransportScheme<dim>::diffuse(const double diffusion, const double time_step)
  {
    VolumeFraction<dim> &phi      = this->phi;
    const double mass             = phi.integral();
    const auto [phi_min, phi_max] = phi.range();
    phi.bounded_diffusion_step(diffusion, time_step);
    phi.restore_mass(mass, phi_min, phi_max);
  }


  template <int dim>
  void
  TransportScheme<dim>::record_mass_defect(const double defect)
  {
    phi.mass_defect = defect;
  }


  template <int dim>
  const DoFHandler<dim> &
  TransportScheme<dim>::dofs() const
  {
    return phi.dofs;
  }


  template <int dim>
  const FE_Q<dim> &
  TransportScheme<dim>::fe() const
  {
    return phi.fe;
  }


  template <int dim>
  const AffineConstraints<double> &
  TransportScheme<dim>::constraints() const
  {
    return phi.constraints;
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector &
  TransportScheme<dim>::solution()
  {
    return phi.current_solution;
  }


  template <int dim>
  TrilinosWrappers::SparseMatrix &
  TransportScheme<dim>::system_matrix()
  {
    return phi.system_matrix;
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector &
  TransportScheme<dim>::system_rhs()
  {
    return phi.system_rhs;
  }


  template <int dim>
  const IndexSet &
  TransportScheme<dim>::matrix_columns() const
  {
    return phi.matrix_columns;
  }


  template <int dim>
  const BoundaryConditions<dim> &
  TransportScheme<dim>::boundary_conditions() const
  {
    return phi.boundary_conditions;
  }


  template <int dim>
  MPI_Comm
  TransportScheme<dim>::mpi_communicator() const
  {
    return phi.mpi_communicator;
  }


  VISCOFILM_INSTANTIATE(TransportScheme)
  VISCOFILM_INSTANTIATE(BoundedTransportScheme)
} // namespace viscofilm
