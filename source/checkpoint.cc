#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <boost/archive/text_iarchive.hpp>
#include <boost/archive/text_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <viscofilm/checkpoint.h>
#include <viscofilm/input.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace viscofilm
{
  namespace
  {
    /// Entries that shape the solution: resuming with other values would
    /// continue a different run. (Output, solver and step-count settings may
    /// change.)
    std::vector<std::vector<std::string>>
    critical_entries()
    {
      std::vector<std::vector<std::string>> entries = {
        {"Geometry", "Lower left corner"},
        {"Geometry", "Upper right corner"},
        {"Geometry", "Initial global refinement"},
        {"Time stepping", "Time step"},
        {"Time stepping", "CFL number"},
        {"Model", "Reynolds number"},
        {"Model", "Viscosity ratio"},
        {"Model", "Weissenberg number"},
        {"Model", "Slip parameter"},
        {"Model", "Diffusion coefficient"},
        {"Model", "Viscoelastic"},
        {"Stress", "Element"},
        {"Stress", "Deformation gradient"},
        {"Stabilization", "GLS tau"},
        {"Stabilization", "GLS parameter"},
        {"Mesh refinement", "Adaptive"},
        {"Mesh refinement", "Interval"},
        {"Mesh refinement", "Minimum level"},
        {"Mesh refinement", "Maximum level"},
        {"Mesh refinement", "Refinement threshold"}};
      for (const char *boundary : {"Inlet", "Outlet", "Bottom", "Top"})
        for (const char *entry :
             {"Type", "Velocity", "Function constants", "Volume fraction"})
          entries.push_back({"Boundary conditions", boundary, entry});
      return entries;
    }

    std::string
    path_of(const std::vector<std::string> &entry)
    {
      std::string path;
      for (const std::string &part : entry)
        path += (path.empty() ? "" : "/") + part;
      return path;
    }

    std::string
    value_of(const ParameterHandler &prm, const std::vector<std::string> &entry)
    {
      return prm.get(std::vector<std::string>(entry.begin(), entry.end() - 1),
                     entry.back());
    }
  } // namespace


  void
  Checkpoint::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpointing");
    prm.declare_entry("Interval",
                      "0",
                      Patterns::Integer(0),
                      "Time steps between checkpoints (0: none), written to "
                      "OUTPUT/checkpoint; the last step always writes one when "
                      "this is > 0.");
    prm.declare_entry("Resume",
                      "false",
                      Patterns::Bool(),
                      "Continue from OUTPUT/checkpoint, appending to the run's "
                      "files. Refused if a parameter that shapes the solution "
                      "changed; Time stepping/Number of steps may grow.");
    prm.leave_subsection();
  }


  void
  Checkpoint::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpointing");
    interval = prm.get_integer("Interval");
    resume   = prm.get_bool("Resume");
    prm.leave_subsection();
  }


  Checkpoint::Checkpoint(const Parameters & parameters,
                         const std::string &output_directory,
                         MPI_Comm           comm)
    : parameters(parameters)
    , directory(output_directory + "/checkpoint")
    , mpi_communicator(comm)
  {}


  bool
  Checkpoint::due(const unsigned int step) const
  {
    return parameters.interval > 0 && step % parameters.interval == 0;
  }


  std::string
  Checkpoint::mesh_file() const
  {
    return directory + "/mesh";
  }


  std::string
  Checkpoint::begin() const
  {
    const std::string staging = directory + ".new";
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::filesystem::remove_all(staging);
        std::filesystem::create_directories(staging);
      }
    MPI_Barrier(mpi_communicator);
    return staging + "/mesh";
  }


  void
  Checkpoint::commit(const State &state, const ParameterHandler &prm) const
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        const std::string staging = directory + ".new";
        {
          std::ofstream out(staging + "/state");
          out << std::setprecision(17) << "step " << state.step << "\ntime "
              << state.time << "\n";
          for (const auto &entry : critical_entries())
            out << "parameter " << path_of(entry) << " = " << value_of(prm, entry)
                << "\n";
          out << "snapshots\n";
          boost::archive::text_oarchive archive(out);
          archive << state.snapshots;
        }
        // Swap in the new checkpoint; until the first rename the old one is
        // whole, after it the new one is.
        const std::string previous = directory + ".old";
        std::filesystem::remove_all(previous);
        if (std::filesystem::exists(directory))
          std::filesystem::rename(directory, previous);
        std::filesystem::rename(staging, directory);
        std::filesystem::remove_all(previous);
      }
    MPI_Barrier(mpi_communicator);
  }


  Checkpoint::State
  Checkpoint::read(const ParameterHandler &prm) const
  {
    // Rank 0 reads; every rank gets the text (and so the same verdict).
    std::string text;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ifstream in(directory + "/state");
        std::ostringstream contents;
        contents << in.rdbuf();
        text = in ? contents.str() : "";
      }
    text = Utilities::MPI::broadcast(mpi_communicator, text, 0);
    check_input(!text.empty(),
                "Checkpointing/Resume: there is no checkpoint in \"" + directory +
                  "\" (Output/Directory must name the run to continue)");

    State              state;
    std::istringstream in(text);
    std::string        word, line;
    in >> word >> state.step >> word >> state.time;
    std::getline(in, line);
    while (std::getline(in, line) && line != "snapshots")
      {
        const std::string path  = line.substr(10, line.find(" = ") - 10);
        const std::string saved = line.substr(line.find(" = ") + 3);
        for (const auto &entry : critical_entries())
          if (path_of(entry) == path)
            check_input(value_of(prm, entry) == saved,
                        "Checkpointing/Resume: " + path + " is \"" +
                          value_of(prm, entry) + "\" but the checkpoint was "
                          "written with \"" + saved +
                          "\"; resuming would continue a different run");
      }
    boost::archive::text_iarchive archive(in);
    archive >> state.snapshots;
    return state;
  }
} // namespace viscofilm
