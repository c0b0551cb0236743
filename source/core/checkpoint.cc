#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <boost/archive/text_iarchive.hpp>
#include <boost/archive/text_oarchive.hpp>
#include <boost/serialization/vector.hpp>

#include <viscofilm/core/checkpoint.h>
#include <viscofilm/core/input.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace viscofilm
{
  namespace
  {
    /// Run @p files (file system work) on rank 0 only; if it throws, every
    /// rank throws the same message, so that none waits in a collective
    /// call for a rank that has given up.
    void
    on_rank_zero(const MPI_Comm comm, const std::function<void()> &files)
    {
      std::string error;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        try
          {
            files();
          }
        catch (const std::exception &e)
          {
            error = std::string("checkpoint: ") + e.what();
          }
      error = Utilities::MPI::broadcast(comm, error, 0);
      AssertThrow(error.empty(), ExcMessage(error));
    }

    /// The entries that may differ when a run is resumed: where, what and
    /// how often it writes, how far it goes, and caps whose reaching stops
    /// the run instead of changing its solution. Every other declared entry
    /// shapes the solution and must be as the checkpoint recorded it, so
    /// that a newly declared parameter is checked by default.
    const std::vector<std::string> free_on_resume = {
      "Output/Directory",
      "Output/Interval",
      "Output/Probe points",
      "Checkpointing/Interval",
      "Checkpointing/Resume",
      "Time stepping/Number of steps",
      "Stokes solver/Maximum iterations",
      "Departure feet/Maximum Newton iterations"};


    /// Every declared entry that shapes the solution, "Subsection/Name",
    /// with its value, found by walking the tree of @p prm.
    std::vector<std::pair<std::string, std::string>>
    critical_entries(const ParameterHandler &prm)
    {
      std::ostringstream listing;
      prm.print_parameters(listing, ParameterHandler::ShortPRM);
      std::istringstream                               lines(listing.str());
      std::vector<std::string>                         subsections;
      std::vector<std::pair<std::string, std::string>> entries;
      unsigned int                                     n_free = 0;
      for (std::string line; std::getline(lines, line);)
        {
          line = Utilities::trim(line);
          if (line.rfind("subsection ", 0) == 0)
            subsections.push_back(line.substr(11));
          else if (line == "end")
            subsections.pop_back();
          else if (line.rfind("set ", 0) == 0)
            {
              const std::string name =
                Utilities::trim(line.substr(4, line.find('=') - 4));
              std::string path;
              for (const std::string &subsection : subsections)
                path += subsection + "/";
              path += name;
              if (std::find(free_on_resume.begin(), free_on_resume.end(), path) ==
                  free_on_resume.end())
                entries.emplace_back(path, prm.get(subsections, name));
              else
                ++n_free;
            }
        }
      AssertThrow(n_free == free_on_resume.size(),
                  ExcMessage("free_on_resume names an entry that is not declared"));
      return entries;
    }
  } // namespace


  namespace
  {
    /// The layout of the saved vectors: 2 since each field's vectors are
    /// stored together (one SolutionTransfer per field).
    constexpr double format = 2;
  } // namespace


  double
  checkpoint_value(const CheckpointValues &values, const std::string &name)
  {
    const auto value = values.find(name);
    check_input(value != values.end(),
                "Checkpointing/Resume: the checkpoint does not record " + name +
                  " (written by another version of viscofilm)");
    return value->second;
  }


  template <int dim>
  void
  Checkpoint<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpointing");
    prm.declare_entry("Interval",
                      "0",
                      Patterns::Integer(0),
                      "Time steps between checkpoints (0: none), written to "
                      "OUTPUT/checkpoint; the last step always writes one when "
                      "this is > 0.");
    std::string free;
    for (const std::string &path : free_on_resume)
      free += (free.empty() ? "" : ", ") + path;
    prm.declare_entry("Resume",
                      "false",
                      Patterns::Bool(),
                      "Continue from OUTPUT/checkpoint (or from "
                      "OUTPUT/checkpoint.old, where a run stopped while "
                      "replacing one by the next), appending to the run's "
                      "files. Refused if any parameter differs from the "
                      "checkpoint's except " + free + ".");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Checkpoint<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpointing");
    interval = prm.get_integer("Interval");
    resume   = prm.get_bool("Resume");
    prm.leave_subsection();
  }


  template <int dim>
  Checkpoint<dim>::Checkpoint(const Parameters & parameters,
                         const std::string &output_directory,
                         MPI_Comm           comm)
    : parameters(parameters)
    , directory(output_directory + "/checkpoint")
    , mpi_communicator(comm)
  {}


  template <int dim>
  bool
  Checkpoint<dim>::due(const unsigned int step) const
  {
    return parameters.interval > 0 && step % parameters.interval == 0;
  }


  template <int dim>
  std::string
  Checkpoint<dim>::mesh_file() const
  {
    return directory + "/mesh";
  }


  template <int dim>
  std::string
  Checkpoint<dim>::begin() const
  {
    const std::string staging = directory + ".new";
    on_rank_zero(mpi_communicator, [&]() {
      std::filesystem::remove_all(staging);
      std::filesystem::create_directories(staging);
    });
    return staging + "/mesh";
  }


  template <int dim>
  void
  Checkpoint<dim>::commit(const State &state, const ParameterHandler &prm) const
  {
    on_rank_zero(mpi_communicator, [&]() {
      const std::string staging = directory + ".new";
      {
        std::ofstream out(staging + "/state");
        out << std::setprecision(17) << "step " << state.step << "\ntime "
            << state.time << "\nformat " << format << "\nnext_time_step "
            << state.next_time_step << "\n";
        for (const auto &[name, value] : state.values)
          out << name << " " << value << "\n";
        for (const auto &[path, value] : critical_entries(prm))
          out << "parameter " << path << " = " << value << "\n";
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
    });
  }


  template <int dim>
  typename Checkpoint<dim>::State
  Checkpoint<dim>::read(const ParameterHandler &prm) const
  {
    // Rank 0 reads; every rank gets the text (and so the same verdict).
    std::string text;
    on_rank_zero(mpi_communicator, [&]() {
      // Stopped between the two renames of commit(): the last checkpoint
      // is whole under its old name. Restore it, so that the next commit
      // does not delete it.
      const std::string previous = directory + ".old";
      if (!std::filesystem::exists(directory) &&
          std::filesystem::exists(previous + "/state"))
        {
          std::filesystem::rename(previous, directory);
          std::cout << "The last checkpoint's commit was interrupted: resuming "
                       "from the one before it, "
                    << previous << std::endl;
        }
      std::ifstream in(directory + "/state");
      std::ostringstream contents;
      contents << in.rdbuf();
      text = in ? contents.str() : "";
    });
    text = Utilities::MPI::broadcast(mpi_communicator, text, 0);
    check_input(!text.empty(),
                "Checkpointing/Resume: there is no checkpoint in \"" + directory +
                  "\" (Output/Directory must name the run to continue)");

    State              state;
    std::istringstream in(text);
    std::string        word, line;
    in >> word >> state.step >> word >> state.time;
    std::getline(in, line);
    // "name value" lines of the state, then "parameter path = value" lines.
    std::map<std::string, std::string> saved;
    while (std::getline(in, line) && line != "snapshots")
      {
        const std::string name = line.substr(0, line.find(' '));
        if (name == "parameter")
          saved[line.substr(10, line.find(" = ") - 10)] =
            line.substr(line.find(" = ") + 3);
        else
          state.values[name] = std::stod(line.substr(name.size() + 1));
      }
    check_input(state.values.count("format") == 1 && state.values.at("format") == format,
                "Checkpointing/Resume: the checkpoint in \"" + directory +
                  "\" was written by an older viscofilm, which stored the "
                  "fields' vectors differently; start the run anew (Resume = false)");
    state.next_time_step = checkpoint_value(state.values, "next_time_step");
    state.values.erase("format");
    state.values.erase("next_time_step");
    for (const auto &[path, value] : critical_entries(prm))
      {
        const auto entry = saved.find(path);
        check_input(entry != saved.end(),
                    "Checkpointing/Resume: the checkpoint does not record " +
                      path + " (written by another version of viscofilm)");
        check_input(entry->second == value,
                    "Checkpointing/Resume: " + path + " is \"" + value +
                      "\" but the checkpoint was written with \"" +
                      entry->second +
                      "\"; resuming would continue a different run");
      }
    boost::archive::text_iarchive archive(in);
    archive >> state.snapshots;
    return state;
  }


  VISCOFILM_INSTANTIATE(Checkpoint)
} // namespace viscofilm
