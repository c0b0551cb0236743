#include <deal.II/base/utilities.h>

#include <deal.II/fe/mapping_q.h>

#include <deal.II/numerics/vector_tools_evaluate.h>

#include <viscofilm/core/input.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/core/version.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/transport/volume_fraction.h>

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace viscofilm
{


  CsvFile::CsvFile(const std::string &                filename,
                   const MPI_Comm                     mpi_communicator,
                   const std::optional<unsigned int> &resume_after_step)
    : is_writer(Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
  {
    // Resuming: the header, and the rows up to the checkpoint's step.
    std::string kept;
    if (resume_after_step && is_writer)
      {
        std::ifstream old(filename);
        std::string   line;
        if (std::getline(old, line))
          {
            header = Utilities::split_string_list(line, ',');
            kept   = line + "\n";
          }
        while (std::getline(old, line))
          if (!line.empty() &&
              std::stoul(line.substr(0, line.find(','))) <= *resume_after_step)
            kept += line + "\n";
      }
    if (is_writer)
      {
        file.open(filename);
        file << kept;
        AssertThrow(file, ExcMessage("cannot open " + filename + " for writing"));
        file << std::setprecision(17);
      }
  }


  void
  CsvFile::set(const std::string &column, const double value)
  {
    for (auto &entry : row)
      if (entry.first == column)
        {
          entry.second = value;
          return;
        }
    row.emplace_back(column, value);
  }


  void
  CsvFile::write_row()
  {
    if (header.empty())
      {
        for (const auto &entry : row)
          header.push_back(entry.first);
        if (is_writer)
          for (unsigned int c = 0; c < header.size(); ++c)
            file << header[c] << (c + 1 < header.size() ? "," : "\n");
      }
    AssertThrow(row.size() == header.size(), ExcInternalError());
    if (is_writer)
      {
        for (unsigned int c = 0; c < row.size(); ++c)
          {
            AssertThrow(row[c].first == header[c], ExcInternalError());
            file << row[c].second << (c + 1 < row.size() ? "," : "\n");
          }
        file.flush();
      }
    row.clear();
  }


  template <int dim>
  void
  Output<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "output",
                      Patterns::Anything(),
                      "Directory for the results (created if missing): "
                      "solution.xdmf with solution-NNNNN.h5, statistics.csv, "
                      "probes.csv and parameters.prm.");
    prm.declare_entry("Interval",
                      "10",
                      Patterns::Integer(0),
                      "Time steps between HDF5 snapshots (the first and last "
                      "step are always written); 0 writes none.");
    prm.declare_entry("Probe points",
                      "",
                      Patterns::Anything(),
                      "Points \"x1, y1; x2, y2; ...\" (3D: \"x1, y1, z1; ...\") "
                      "inside the channel where the velocity components, p, φ "
                      "and the components of τ are written to probes.csv every "
                      "step.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Output<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory = prm.get("Directory");
    interval  = prm.get_integer("Interval");
    probe_points =
      parse_point_list<dim>(prm.get("Probe points"), "Output/Probe points");
    prm.leave_subsection();
    check_input(!directory.empty(), "Output/Directory must not be empty");
  }


  template <int dim>
  Output<dim>::Output(const Parameters &                             parameters,
                 const parallel::distributed::Triangulation<dim> &triangulation,
                 const Mapping<dim> &                             mapping)
    : parameters(parameters)
    , triangulation(triangulation)
    , mapping(mapping)
    , mpi_communicator(triangulation.get_communicator())
  {}


  template <int dim>
  void
  Output<dim>::prepare(const ParameterHandler &      prm,
                  const std::optional<unsigned int> &resume_after_step,
                  const std::vector<XDMFEntry> &     snapshots)
  {
    xdmf_entries = snapshots;
    // Rank 0 creates the directory; every rank learns whether it worked, so
    // that all of them stop together if it did not.
    std::string failure;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::error_code error;
        std::filesystem::create_directories(parameters.directory, error);
        std::ofstream used(parameters.directory + "/parameters.prm");
        if (error || !used)
          failure = "Output/Directory: cannot write into \"" +
                    parameters.directory + "\"" +
                    (error ? ": " + error.message() : std::string());
        else
          {
            used << "# " << run_description(mpi_communicator) << "\n";
            prm.print_parameters(used, ParameterHandler::ShortPRM);
          }
      }
    failure = Utilities::MPI::broadcast(mpi_communicator, failure, 0);
    AssertThrow(failure.empty(), ExcInput(failure));
    statistics_file = std::make_unique<CsvFile>(parameters.directory +
                                                  "/statistics.csv",
                                                mpi_communicator,
                                                resume_after_step);
    if (!parameters.probe_points.empty())
      probes_file = std::make_unique<CsvFile>(parameters.directory + "/probes.csv",
                                              mpi_communicator,
                                              resume_after_step);
  }


  template <int dim>
  void
  Output<dim>::mesh_changed()
  {
    probe_cache_is_current = false;
  }


  template <int dim>
  bool
  Output<dim>::snapshot_due(const unsigned int step, const bool last_step) const
  {
    return parameters.interval > 0 &&
           (step % parameters.interval == 0 || last_step);
  }


  template <int dim>
  void
  Output<dim>::write_snapshot(const unsigned int                        step,
                         const double                                   time,
                         const std::function<void(DataOut<dim> &)> &add_fields)
  {
    DataOut<dim> data_out;
    data_out.attach_triangulation(triangulation);
    add_fields(data_out);
    // On a curved mesh every cell through the problem's mapping, as the
    // fields are computed (the patch points are the cells' own).
    const auto *mapping_q = dynamic_cast<const MappingQ<dim> *>(&mapping);
    data_out.build_patches(mapping,
                           snapshot_subdivisions,
                           mapping_q != nullptr && mapping_q->get_degree() > 1 ?
                             DataOut<dim>::curved_inner_cells :
                             DataOut<dim>::no_curved_cells);

    // Every cell keeps its own copy of its vertices: merging them ("filter
    // duplicates") kept one cell's value of the fields that jump between
    // cells (∇·u, vorticity, u·∇u, the loads, a discontinuous stress).
    DataOutBase::DataOutFilter filter(
      DataOutBase::DataOutFilterFlags(/*filter duplicates*/ false,
                                      /*xdmf hdf5*/ true));
    data_out.write_filtered_data(filter);

    // deal.II 9.4.1's parallel HDF5 writer fails on ranks without cells:
    // write with the ranks that own cells only.
    const bool owns_cells = triangulation.n_locally_owned_active_cells() > 0;
    MPI_Comm   writers;
    MPI_Comm_split(mpi_communicator,
                   owns_cells ? 0 : MPI_UNDEFINED,
                   Utilities::MPI::this_mpi_process(mpi_communicator),
                   &writers);
    std::ostringstream h5_name;
    h5_name << "solution-" << std::setw(5) << std::setfill('0') << step << ".h5";
    const XDMFEntry entry = owns_cells ?
                              data_out.create_xdmf_entry(filter,
                                                         h5_name.str(),
                                                         time,
                                                         writers) :
                              XDMFEntry();
    xdmf_entries.push_back(entry);
    if (owns_cells)
      {
        data_out.write_hdf5_parallel(filter,
                                     parameters.directory + "/" + h5_name.str(),
                                     writers);
        data_out.write_xdmf_file(xdmf_entries,
                                 parameters.directory + "/solution.xdmf",
                                 writers);
        MPI_Comm_free(&writers);
      }
  }


  template <int dim>
  void
  Output<dim>::write_probes(const unsigned int step,
                       const double          time,
                       const StokesFlow<dim> & stokes,
                       const VolumeFraction<dim> &volume_fraction,
                       const ElasticStress<dim> & stress)
  {
    if (!probes_file)
      return;
    const bool is_root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    if (!probe_cache_is_current)
      {
        // Rank 0 asks for every probe; the others only answer.
        probe_cache.reinit(is_root ? parameters.probe_points :
                                     std::vector<Point<dim>>(),
                           triangulation,
                           mapping);
        // Collective, so that no rank waits for one that threw.
        const bool all_found =
          Utilities::MPI::min(probe_cache.all_points_found() ? 1 : 0,
                              mpi_communicator) == 1;
        AssertThrow(all_found,
                    ExcInput("Output/Probe points: a point lies outside the mesh"));
        probe_cache_is_current = true;
      }
    // Each probe's coordinates, velocity components, p, φ and the stored
    // components of τ (2D: x, y, u, v, p, volume_fraction, tau_xx, tau_xy,
    // tau_yy; 3D adds z, w and the xz, yz, zz components).
    const auto up = VectorTools::point_values<dim + 1>(probe_cache,
                                                       stokes.dof_handler(),
                                                       stokes.solution());
    const auto phi = VectorTools::point_values<1>(probe_cache,
                                                  volume_fraction.dof_handler(),
                                                  volume_fraction.solution());
    const auto c = VectorTools::point_values<n_symmetric_components<dim>>(
      probe_cache, stress.dof_handler(), stress.solution());
    for (unsigned int i = 0; i < up.size(); ++i)
      {
        probes_file->set("step", step);
        probes_file->set("time", time);
        for (unsigned int d = 0; d < dim; ++d)
          probes_file->set(std::string(1, "xyz"[d]), parameters.probe_points[i][d]);
        for (unsigned int d = 0; d < dim; ++d)
          probes_file->set(std::string(1, "uvw"[d]), up[i][d]);
        probes_file->set("p", up[i][dim]);
        probes_file->set("volume_fraction", phi[i]);
        const SymmetricTensor<2, dim> tau =
          stress.stress_of(Vector<double>(c[i].begin_raw(), c[i].end_raw()), phi[i]);
        for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
          probes_file->set("tau_" + symmetric_component_name<dim>(k), stored_component(tau, k));
        probes_file->write_row();
      }
  }


  template <int dim>
  const std::vector<XDMFEntry> &
  Output<dim>::snapshots() const
  {
    return xdmf_entries;
  }


  template <int dim>
  CsvFile &
  Output<dim>::statistics()
  {
    return *statistics_file;
  }


  VISCOFILM_INSTANTIATE(Output)
} // namespace viscofilm
