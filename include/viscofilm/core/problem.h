// The simulator: owns the mesh and the fields and runs the coupled time loop
// of MODEL.md §3 in the thesis' order.
#ifndef viscofilm_problem_h
#define viscofilm_problem_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/fe/mapping_q_cache.h>

#include <viscofilm/core/checkpoint.h>
#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/biofilm/detachment.h>
#include <viscofilm/biofilm/growth.h>
#include <viscofilm/biofilm/loads.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/core/parameters.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/transport/volume_fraction.h>

#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class Problem
  {
  public:
    /// @p prm is kept to write the parameters used next to the results.
    Problem(const Parameters<dim> &parameters, const ParameterHandler &prm, MPI_Comm comm);

    /// Run all time steps; throws with the step and time on failure.
    void
    run();

  private:
    void
    run_time_loop();
    /// What one time step did, for statistics.csv and the screen.
    struct StepReport
    {
      std::string  stokes_iterations; // per Picard iteration, "12+8+3"
      unsigned int total_stokes_iterations = 0;
      unsigned int picard_iterations       = 0;
      bool         picard_converged        = true;
      // Relative L2 changes of u and τ in the last Picard iteration.
      double       picard_velocity_change  = 0;
      double       picard_stress_change    = 0;
      unsigned int transport_iterations    = 0;
      // Error control: the largest of the fields' estimates, and how many
      // tries of this step were rejected before it.
      double       error_estimate          = 0;
      unsigned int rejected_steps          = 0;
    };

    /// The coarse mesh with its periodic pairs, refined globally; checks
    /// that every probe point lies in the mesh.
    void
    make_grid();
    /// The coarse mesh with its periodic pairs (also what a checkpoint's
    /// mesh is loaded into).
    void
    make_coarse_grid();
    void
    check_probe_points() const;
    void
    setup_dofs();
    /// Adapt the mesh (MeshRefinement), carrying u, p, c and φ over; false
    /// if no cell was flagged. Without @p coarsen cells are only refined;
    /// @p input: the initial φ the mesh must resolve between φ's nodes too.
    bool
    refine_mesh(const bool                            coarsen = true,
                const typename MeshRefinement<dim>::InitialInput *input = nullptr);
    /// Right after the triangulation changed (made, refined, loaded), before
    /// anything maps a cell: the curved mapping's support points. deal.II
    /// drops them at every change, and mapping a cell without them fails.
    void
    cache_mapping();
    /// After any change of the mesh: caches that depend on it.
    void
    mesh_changed();
    /// Save mesh, fields and the loop's state to OUTPUT/checkpoint.
    void
    write_checkpoint(const unsigned int step, const double time);
    /// Load them; returns the state to continue from.
    typename Checkpoint<dim>::State
    resume_from_checkpoint();
    void
    set_initial_conditions();
    /// The step from t_n = @p time: its length (time_step) from Time
    /// stepping, and with error control tried and redone shorter until its
    /// estimate is within the tolerance.
    StepReport
    take_step(const double time);
    /// One step t_n -> t_{n+1} = @p time of length time_step: feet, Picard
    /// loop, transport (Order 1: after the loop; Order 2: inside it).
    StepReport
    do_time_step(const double time);
    /// φ^{n+1} from φ^n with the current Stokes solution (VolumeFraction::
    /// advance); returns the linear solver's iterations.
    unsigned int
    advance_volume_fraction(const double k);
    /// Assemble and solve (a @p predictor: StokesFlow::solve).
    unsigned int
    solve_stokes(const double time, const bool predictor = false);
    void
    output_results(const unsigned int step, const double time, const bool last_step);
    void
    write_statistics(const unsigned int step, const double time, const StepReport &report);

    const Parameters<dim> &parameters;
    double                  time_step     = 0; // of the current step
    double                  step_cfl      = 0; // its max|u^n| k / Δx
    double                  min_cell_size = 0; // smallest cell edge
    double                  proposed_time_step = 0; // the controller's; 0: none
    const ParameterHandler &prm;
    MPI_Comm                mpi_communicator;
    ConditionalOStream      pcout;
    // A pointer, so that a failed run can drop it before its message: its
    // destructor warns about the exception in flight otherwise.
    std::unique_ptr<TimerOutput> computing_timer;

    parallel::distributed::Triangulation<dim> triangulation;
    /// On a curved mesh (Geometry::mapping_degree() 2) MappingQ(2)'s support
    /// points computed once per mesh: MappingQ would ask the manifolds (the
    /// transfinite one is costly) at every reinit of a cell. Null otherwise.
    std::unique_ptr<MappingQCache<dim>> curved_mapping;
    /// The map from the reference cell every field and position uses.
    const Mapping<dim> &                 mapping;
    StokesFlow<dim>                       stokes;
    VolumeFraction<dim>                     volume_fraction;
    ElasticStress<dim>                      stress;
    DepartureFeet<dim>                      departure_feet;
    MeshRefinement<dim>                     mesh_refinement;
    Verification<dim>                       verification;
    BiofilmLoads<dim>                       loads;
    Detachment<dim>                         detachment;
    /// With Substrate/Enable only.
    std::unique_ptr<Substrate<dim>>         substrate;
    std::unique_ptr<Growth<dim>>            growth; // with the substrate
    Output<dim>                             output;
    Checkpoint<dim>                         checkpoint;
    /// Every field, for the life cycle (FieldBase): u and p, c, φ, φ_d, S.
    std::vector<FieldBase<dim> *>           fields;
    /// Every component that reports (Reporter): statistics.csv's columns,
    /// the snapshots' datasets and the checkpoint's scalars, in this order
    /// (φ_d reports through the detachment).
    std::vector<Reporter<dim> *>            reporters;
  };
} // namespace viscofilm

#endif
