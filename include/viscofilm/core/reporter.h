// What a part of the run adds to the run's records.
#ifndef viscofilm_reporter_h
#define viscofilm_reporter_h

#include <deal.II/numerics/data_out.h>

#include <map>
#include <string>

namespace viscofilm
{
  using namespace dealii;

  class CsvFile;

  /// The checkpoint's scalars, by name (the state file's "name value" lines).
  using CheckpointValues = std::map<std::string, double>;

  /// The value @p name of a checkpoint's @p values; throws ExcInput naming
  /// it if the checkpoint lacks it (written by another version).
  double
  checkpoint_value(const CheckpointValues &values, const std::string &name);

  /**
   * A component's part of the run's records (Problem asks each component in
   * its list, in that order): its columns of statistics.csv after every
   * accepted step, its datasets in the snapshots, and the scalars a
   * checkpoint must keep besides the vectors its fields carry. A new field
   * brings its own by overriding these; nothing is added by default.
   */
  template <int dim>
  class Reporter
  {
  public:
    virtual ~Reporter() = default;

    /// Set this component's columns of the current row, that of @p time.
    virtual void
    add_statistics(CsvFile & /*statistics*/, const double /*time*/) const
    {}

    /// Add this component's datasets to a snapshot; what @p data_out
    /// references must live until the snapshot is written.
    virtual void
    add_output(DataOut<dim> & /*data_out*/)
    {}

    /// Put the scalars a resume needs into @p values, under names no other
    /// component uses.
    virtual void
    save_state(CheckpointValues & /*values*/) const
    {}

    /// Take them back after a resume.
    virtual void
    load_state(const CheckpointValues & /*values*/)
    {}
  };
} // namespace viscofilm

#endif
