// Everything a run writes: HDF5/XDMF snapshots, statistics.csv, probes.csv
// and the parameters it used.
#ifndef viscofilm_output_h
#define viscofilm_output_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/numerics/data_out.h>

#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class ElasticStress;
  template <int dim>
  class VolumeFraction;

  /// A snapshot's subdivisions of each cell, one per polynomial degree: the
  /// Q2 nodes are among its points.
  constexpr unsigned int snapshot_subdivisions = 2;

  /// The unit points at which a snapshot evaluates the fields of each cell,
  /// in DataOut's order: a postprocessor that needs other fields than its
  /// own evaluates them there.
  template <int dim>
  QIterated<dim>
  snapshot_points()
  {
    return QIterated<dim>(QTrapezoid<1>(), snapshot_subdivisions);
  }

  /**
   * A CSV file written by rank 0, one row at a time with named columns in a
   * fixed order. Values carry 17 significant digits, and every row is
   * flushed so that a run stopped by an error leaves a valid file.
   */
  class CsvFile
  {
  public:
    /// With @p resume_after_step, continue the existing file: keep its rows
    /// up to that step and append.
    CsvFile(const std::string &                filename,
            const MPI_Comm                     mpi_communicator,
            const std::optional<unsigned int> &resume_after_step = {});

    /// Set a column of the current row; the first row fixes the columns.
    void
    set(const std::string &column, const double value);

    /// Write the current row and start a new one.
    void
    write_row();

  private:
    const bool                                    is_writer;
    std::ofstream                                 file;
    std::vector<std::pair<std::string, double>>   row;
    std::vector<std::string>                      header;
  };


  template <int dim>
  class Output
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      std::string           directory = "output";
      unsigned int          interval  = 10;
      std::vector<Point<dim>> probe_points;
    };

    /// @p mapping: the problem's, which places the snapshots' points and
    /// the probes.
    Output(const Parameters &                             parameters,
           const parallel::distributed::Triangulation<dim> &triangulation,
           const Mapping<dim> &                             mapping);

    /// Create the output directory and write the parameters used into it;
    /// when resuming after @p resume_after_step, continue the run's files
    /// and its list of @p snapshots instead.
    void
    prepare(const ParameterHandler &           prm,
            const std::optional<unsigned int> &resume_after_step = {},
            const std::vector<XDMFEntry> &     snapshots         = {});

    /// The snapshots written so far (for a checkpoint).
    const std::vector<XDMFEntry> &
    snapshots() const;

    /// The mesh changed: probe locations must be searched again.
    void
    mesh_changed();

    /// Snapshot due at this step? (The first and last steps always are.)
    bool
    snapshot_due(const unsigned int step, const bool last_step) const;

    /// Write solution-NNNNN.h5 with the fields @p add_fields adds (each on
    /// Q2 patches: two subdivisions per cell, every cell with its own copy
    /// of its vertices so that fields discontinuous between cells keep each
    /// cell's value) and rewrite solution.xdmf.
    void
    write_snapshot(const unsigned int                             step,
                   const double                                   time,
                   const std::function<void(DataOut<dim> &)> &add_fields);

    /// Append one row per probe point to probes.csv.
    void
    write_probes(const unsigned int    step,
                 const double          time,
                 const StokesFlow<dim> & stokes,
                 const VolumeFraction<dim> &volume_fraction,
                 const ElasticStress<dim> & stress);

    CsvFile &
    statistics();

  private:
    const Parameters &                             parameters;
    const parallel::distributed::Triangulation<dim> &triangulation;
    const Mapping<dim> &                             mapping;
    const MPI_Comm                                 mpi_communicator;

    std::vector<XDMFEntry>                  xdmf_entries;
    std::unique_ptr<CsvFile>                statistics_file;
    std::unique_ptr<CsvFile>                probes_file;
    Utilities::MPI::RemotePointEvaluation<dim> probe_cache;
    bool                                    probe_cache_is_current = false;
  };
} // namespace viscofilm

#endif
