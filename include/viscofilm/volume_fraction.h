// The biofilm volume fraction φ on its own FE_Q(2) DoFHandler (MODEL.md §2).
#ifndef viscofilm_volume_fraction_h
#define viscofilm_volume_fraction_h

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/data_out.h>

#include <viscofilm/boundary_conditions.h>
#include <viscofilm/mesh_refinement.h>

namespace viscofilm
{
  using namespace dealii;

  class StokesSolver;

  class VolumeFraction
  {
  public:
    /// GLS stabilisation of the transport (thesis eq. 3.47-3.50).
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// constant: τ = GLS parameter (the thesis: 1). standard: τ = GLS
      /// parameter × (4/k² + (2|u|/h)²)^(-1/2).
      bool   standard_tau  = false;
      double gls_parameter = 1.0;
    };

    VolumeFraction(const parallel::distributed::Triangulation<2> &triangulation,
                   const Parameters &                             parameters,
                   const BoundaryConditions &                     boundary_conditions);

    void
    setup_dofs();

    /// φ := the interpolant of @p initial at the Q2 nodes.
    void
    interpolate(const Function<2> &initial);

    /// MODEL.md §3 step 3: φ^{n+1} from φ^n with the velocity of @p stokes,
    /// GLS-stabilised Galerkin with the φ-scaled diffusion D φ^n ∇φ; φ takes
    /// each boundary's Volume fraction where the flow enters. Returns the
    /// GMRES iteration count.
    unsigned int
    advance(const StokesSolver &stokes, const double diffusion, const double time_step);

    /// Eq. 2.50: @p n_steps implicit Euler steps of ∂φ/∂t = ∇·(D φ ∇φ).
    void
    soften(const double diffusion, const unsigned int n_steps, const double time_step);

    const DoFHandler<2> &
    dof_handler() const;

    /// Add volume_fraction to @p data_out.
    void
    add_output(DataOut<2> &data_out) const;

    /// φ with ghost values.
    const TrilinosWrappers::MPI::Vector &
    solution() const;

    /// Keep φ across a mesh change (see StokesSolver).
    void
    prepare_for_refinement();
    void
    finish_refinement();
    /// Keep the fields through a checkpoint: prepare before the mesh is
    /// saved, written after; finish_refinement() after it is loaded.
    void
    prepare_for_checkpoint();
    void
    checkpoint_written();


    /// ∫_Ω φ dx.
    double
    integral() const;

    /// Smallest and largest nodal value.
    std::pair<double, double>
    range() const;

  private:
    /// One implicit step; without @p stokes: pure φ-scaled diffusion.
    unsigned int
    step(const StokesSolver *stokes, const double diffusion, const double time_step);

    /// Hanging nodes, and φ = boundary value on faces where u·n < 0.
    void
    make_constraints(const StokesSolver *stokes);

    const Parameters &        parameters;
    const BoundaryConditions &boundary_conditions;
    const MPI_Comm            mpi_communicator;
    const FE_Q<2>             fe;
    DoFHandler<2>             dofs;
    AffineConstraints<double> constraints;
    IndexSet                  locally_relevant_dofs;

    TrilinosWrappers::SparseMatrix system_matrix;
    TrilinosWrappers::MPI::Vector  system_rhs;
    TrilinosWrappers::MPI::Vector current_solution; // ghosted
    SolutionCarrier<TrilinosWrappers::MPI::Vector> carrier;
  };
} // namespace viscofilm

#endif
