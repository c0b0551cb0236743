// How φ is carried by the flow: one class per Stabilization/Volume fraction
// scheme (doc/numerics-transport.md), chosen once, as StokesLinearSolver is
// for the Stokes methods. A scheme works on its VolumeFraction's vectors and
// uses the field's toolbox (constraints, boundary exchange, bounded
// diffusion, mass restoration) for what the schemes share.
#ifndef viscofilm_transport_scheme_h
#define viscofilm_transport_scheme_h

#include <viscofilm/transport/volume_fraction.h>

#include <memory>

namespace viscofilm
{
  using namespace dealii;

  class CsvFile;

  template <int dim>
  class TransportScheme
  {
  public:
    /// The scheme of @p parameters for @p phi (which owns it).
    static std::unique_ptr<TransportScheme<dim>>
    create(const typename VolumeFraction<dim>::Parameters &parameters,
           VolumeFraction<dim> &                          phi);

    virtual ~TransportScheme() = default;

    /// Whether φ stays in the range of its initial and inflow values: then
    /// its hanging nodes are kept in that range, and a mesh change clips φ
    /// to it and restores the mass.
    virtual bool
    bounded() const = 0;

    /// φ^{n+1} from φ^n (VolumeFraction::advance()): advection by the
    /// velocity of @p stokes (feet traced by @p feet where the scheme uses
    /// them), the φ-scaled diffusion @p diffusion, the boundary exchange
    /// added to the field's totals. @p order: of the velocity's time
    /// interpolation; @p estimate_error: also compute error_estimate().
    /// Returns the linear solver's iterations.
    virtual unsigned int
    advance(const StokesFlow<dim> &stokes,
            DepartureFeet<dim> &   feet,
            const double           diffusion,
            const double           time_step,
            const unsigned int     order,
            const bool             estimate_error) = 0;

    /// One step of the softening (eq. 2.50), φ's constraints set without
    /// inflow: ∂φ/∂t = ∇·(D φ ∇φ) by implicit Euler.
    virtual void
    diffuse(const double diffusion, const double time_step) = 0;

    /// After advance() with estimate_error: the max over the nodes of φ's
    /// change from a first-order to the scheme's step (dimensionless, φ is
    /// a fraction); 0 otherwise.
    virtual double
    error_estimate() const;

    /// The scheme's own statistics.csv columns (none by default).
    virtual void
    add_statistics(CsvFile &statistics) const;

  protected:
    explicit TransportScheme(VolumeFraction<dim> &phi);

    /// What the step's mass fixer could not restore: φ's last_mass_defect().
    void
    record_mass_defect(const double defect);

    /// φ's vectors, constraints and matrix (VolumeFraction's friend).
    const DoFHandler<dim> &
    dofs() const;
    const FE_Q<dim> &
    fe() const;
    const AffineConstraints<double> &
    constraints() const;
    /// φ at t_{n+1}, ghosted.
    TrilinosWrappers::MPI::Vector &
    solution();
    TrilinosWrappers::SparseMatrix &
    system_matrix();
    TrilinosWrappers::MPI::Vector &
    system_rhs();
    /// The locally relevant dofs and every column of the matrix's owned rows.
    const IndexSet &
    matrix_columns() const;
    const BoundaryConditions<dim> &
    boundary_conditions() const;
    MPI_Comm
    mpi_communicator() const;

    VolumeFraction<dim> &phi;
  };


  /// What the bounded schemes (semi-Lagrangian, FCT) share.
  template <int dim>
  class BoundedTransportScheme : public TransportScheme<dim>
  {
  public:
    bool
    bounded() const override;

    /// The bounded diffusion step, then ∫φ restored within the range of
    /// φ^n (the step keeps the sub-cells' lumped mass, not ∫φ).
    void
    diffuse(const double diffusion, const double time_step) override;

    double
    error_estimate() const override;

  protected:
    using TransportScheme<dim>::TransportScheme;

    /// Set by advance(): 0, or the estimate it was asked for.
    double last_error_estimate = 0;
  };


  /// The schemes (semi_lagrangian_scheme.cc, flux_corrected_scheme.cc,
  /// gls_scheme.cc).
  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  make_semi_lagrangian_scheme(VolumeFraction<dim> &phi);
  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  make_flux_corrected_scheme(VolumeFraction<dim> &phi);
  template <int dim>
  std::unique_ptr<TransportScheme<dim>>
  make_gls_scheme(const typename VolumeFraction<dim>::Parameters &parameters,
                  VolumeFraction<dim> &                          phi);
} // namespace viscofilm

#endif
