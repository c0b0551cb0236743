// Checkpoint and restart: the mesh and every field through p4est's
// serialization, the time loop's state and the parameters that must not
// change on resume.
#ifndef viscofilm_checkpoint_h
#define viscofilm_checkpoint_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>

#include <viscofilm/core/reporter.h>

#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class Checkpoint
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      unsigned int interval = 0;     // steps between checkpoints; 0: none
      bool         resume   = false; // start from the last checkpoint
    };

    /// Where the time loop was.
    struct State
    {
      unsigned int           step      = 0;
      double                 time      = 0;
      /// The error controller's next step (0: none, TimeStepping).
      double                 next_time_step = 0;
      std::vector<XDMFEntry> snapshots;
      /// The components' scalars (Reporter::save_state).
      CheckpointValues       values;
    };

    Checkpoint(const Parameters &parameters,
               const std::string &output_directory,
               MPI_Comm           comm);

    /// A checkpoint due after @p step?
    bool
    due(const unsigned int step) const;

    /// An empty staging directory; returns the file name to save the mesh
    /// (and the fields attached to it) to. Collective.
    std::string
    begin() const;

    /// Write the state next to the saved mesh, then let the staging
    /// directory replace the last checkpoint (a crash before that leaves the
    /// last one intact). Collective.
    void
    commit(const State &state, const ParameterHandler &prm) const;

    /// The saved state, after checking that the parameters that shape the
    /// solution (every declared one but a short list) are those of the
    /// checkpoint. If a commit was stopped between its two renames, the
    /// previous checkpoint is restored first. Collective; throws ExcInput.
    State
    read(const ParameterHandler &prm) const;

    /// The file name the mesh was saved to.
    std::string
    mesh_file() const;

  private:
    const Parameters &parameters;
    const std::string directory; // OUTPUT/checkpoint
    const MPI_Comm    mpi_communicator;
  };
} // namespace viscofilm

#endif
