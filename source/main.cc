// viscofilm: command line entry point. The physics lives in the library.
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <viscofilm/core/input.h>
#include <viscofilm/core/parameters.h>
#include <viscofilm/core/problem.h>
#include <viscofilm/core/version.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <chrono>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
  const char *usage =
    "Usage: viscofilm FILE.prm              run the simulation described in FILE.prm\n"
    "       viscofilm --validate FILE.prm   check FILE.prm and exit\n"
    "       viscofilm --print-parameters    print every parameter with its\n"
    "                                       documentation and default\n"
    "       viscofilm --version             print the source revision, build type\n"
    "                                       and the deal.II and Trilinos versions\n"
    "       viscofilm --help                print this message\n"
    "Run in parallel with: mpirun -np N viscofilm FILE.prm\n"
    "Threads per MPI rank (assembly): viscofilm --threads T FILE.prm; default\n"
    "1, or DEAL_II_NUM_THREADS if set, which also caps T.\n";

  /// The number of threads @p text asks for (a whole number >= 1), or throw
  /// with a message naming @p name.
  unsigned int
  thread_count(const std::string &text, const std::string &name)
  {
    std::size_t end   = 0;
    long        count = 0;
    try
      {
        count = std::stol(text, &end);
      }
    catch (...)
      {
        end = 0;
      }
    viscofilm::check_input(end > 0 && end == text.size() && count >= 1 &&
                             count <= 1024,
                           name + " must be a whole number of threads per MPI "
                                  "rank from 1 to 1024, got \"" + text + "\"");
    return count;
  }

  /// Parse @p filename into @p prm. "include FILE" (outside subsections)
  /// reads FILE first, relative to the including file's directory (deal.II
  /// would resolve it relative to the working directory), so that the cases
  /// in prm/ can include prm/default.prm and be included in turn. The include
  /// line becomes a comment, so messages keep the file's line numbers.
  ///
  /// With @p skip_undefined (the first pass, which declares Geometry alone)
  /// undeclared entries are skipped, and the names of the subsections of
  /// Boundary conditions are collected in @p boundary_names with their line.
  void
  parse_with_includes(dealii::ParameterHandler &prm,
                      const std::string &       filename,
                      const bool                skip_undefined = false,
                      std::vector<std::pair<std::string, std::string>>
                        *                boundary_names = nullptr,
                      const unsigned int depth          = 0)
  {
    using viscofilm::check_input;
    check_input(depth < 16,
                "parameter file \"" + filename +
                  "\": includes nested more than 16 deep (a cycle?)");
    check_input(std::filesystem::is_regular_file(filename),
                "parameter file \"" + filename + "\" does not exist");
    std::ifstream            file(filename);
    std::string              line, text;
    std::vector<std::string> includes;
    std::vector<std::string> subsections;
    for (unsigned int number = 1; std::getline(file, line); ++number)
      {
        const std::string code =
          dealii::Utilities::trim(line.substr(0, line.find('#')));
        const int level = subsections.size();
        if (code.rfind("subsection ", 0) == 0)
          {
            const std::string name = dealii::Utilities::trim(code.substr(11));
            if (boundary_names != nullptr && level == 1 &&
                subsections[0] == "Boundary conditions")
              boundary_names->emplace_back(name,
                                           "line " + std::to_string(number) +
                                             " of \"" + filename + "\"");
            subsections.push_back(name);
          }
        else if (code == "end" && level > 0)
          subsections.pop_back();
        else if (code.rfind("include ", 0) == 0 || code.rfind("INCLUDE ", 0) == 0)
          {
            check_input(level == 0,
                        "line " + std::to_string(number) + " of \"" + filename +
                          "\": include must stand outside subsections");
            const std::filesystem::path included(dealii::Utilities::trim(code.substr(8)));
            includes.push_back(
              (std::filesystem::path(filename).parent_path() / included).string());
            line = "# " + line;
          }
        text += line + "\n";
      }
    for (const std::string &included : includes)
      {
        check_input(std::filesystem::is_regular_file(included),
                    "parameter file \"" + filename + "\" includes \"" + included +
                      "\", which does not exist");
        parse_with_includes(prm, included, skip_undefined, boundary_names, depth + 1);
      }
    std::istringstream stream(text);
    prm.parse_input(stream, filename, "", skip_undefined);
  }


  /// Declare every parameter in @p prm for the mesh that @p geometry_input
  /// (Geometry's entries) describes: Boundary conditions has a subsection for
  /// each of its boundaries.
  template <int dim>
  void
  declare_for_mesh(dealii::ParameterHandler &prm,
                   dealii::ParameterHandler &geometry_input,
                   viscofilm::Geometry<dim> &geometry,
                   const std::string &       directory)
  {
    geometry.parse_parameters(geometry_input, directory);
    viscofilm::Parameters<dim>::declare_parameters(prm, geometry.boundaries());
  }


  /// Read @p filename into @p prm and @p parameters, or throw with a message
  /// that names the file, the line and the parameter. Two passes: the first
  /// reads Geometry alone and learns the mesh's boundaries, which declares
  /// Boundary conditions/<name>; the second reads everything strictly.
  template <int dim>
  void
  read_parameters(const std::string &         filename,
                  dealii::ParameterHandler &  prm,
                  viscofilm::Parameters<dim> &parameters)
  {
    viscofilm::check_input(std::filesystem::is_regular_file(filename),
                           "parameter file \"" + filename + "\" does not exist");
    viscofilm::check_input(filename.size() > 4 &&
                             filename.substr(filename.size() - 4) == ".prm",
                           "parameter file \"" + filename +
                             "\" must have the extension .prm");
    const std::string directory = std::filesystem::path(filename).parent_path().string();
    dealii::ParameterHandler geometry_input;
    viscofilm::Geometry<dim>::declare_parameters(geometry_input);
    std::vector<std::pair<std::string, std::string>> boundary_names;
    parse_with_includes(geometry_input, filename, true, &boundary_names);
    declare_for_mesh(prm, geometry_input, parameters.geometry, directory);

    std::string known;
    for (const auto &boundary : parameters.geometry.boundaries())
      known += (known.empty() ? "" : ", ") + boundary.name;
    for (const auto &[name, where] : boundary_names)
      {
        bool found = false;
        for (const auto &boundary : parameters.geometry.boundaries())
          found = found || boundary.name == name;
        viscofilm::check_input(found,
                               where + ": Boundary conditions/" + name +
                                 ": the mesh has no boundary named \"" + name +
                                 "\"; its boundaries are " + known);
      }

    parse_with_includes(prm, filename);
    parameters.parse_parameters(prm, directory);
  }


  /// Geometry/Dimension of @p filename (Geometry's entries alone, whose
  /// declarations are the same in 2D and 3D but for defaults), or 2 where it
  /// cannot be read: the 2D run's read of the file then says why.
  int
  requested_dimension(const std::string &filename)
  {
    try
      {
        dealii::ParameterHandler geometry_input;
        viscofilm::Geometry<2>::declare_parameters(geometry_input);
        parse_with_includes(geometry_input, filename, true);
        geometry_input.enter_subsection("Geometry");
        return geometry_input.get_integer("Dimension");
      }
    catch (...)
      {
        return 2;
      }
  }


  /// A communicator of its own for stop_run(), so that its barrier cannot
  /// match a collective call of the run.
  struct StopCommunicator
  {
    StopCommunicator()
      : comm(dealii::Utilities::MPI::duplicate_communicator(MPI_COMM_WORLD))
    {}
    StopCommunicator(const StopCommunicator &) = delete;
    StopCommunicator &
    operator=(const StopCommunicator &) = delete;
    ~StopCommunicator()
    {
      dealii::Utilities::MPI::free_communicator(comm);
    }
    MPI_Comm comm;
  };


  /// Whether every rank of @p stop_comm (a communicator used for nothing
  /// else) reaches this call within @p patience: a non-blocking barrier,
  /// so that ranks still waiting in a collective call of the run do not
  /// hang it.
  bool
  all_ranks_stopped(const MPI_Comm stop_comm, const std::chrono::seconds patience)
  {
    MPI_Request request;
    MPI_Ibarrier(stop_comm, &request);
    const auto deadline = std::chrono::steady_clock::now() + patience;
    int        done     = 0;
    while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done == 0 &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return done != 0;
  }


  /// A run that stopped (Problem and its files closed): exit code 1. When
  /// every rank failed alike (a solver, a NaN, a time step), rank 0 prints
  /// and all return normally. When the failure is this rank's alone, the
  /// others wait for it in a collective call: it prints with its rank and
  /// stops them all (MPI_Abort). Aborting only then keeps Open MPI's
  /// abort report, whose messages race with the job's end, out of
  /// ordinary failures.
  int
  stop_run(const std::string &message, const MPI_Comm stop_comm)
  {
    const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const bool alike = n_ranks == 1 || all_ranks_stopped(stop_comm, std::chrono::seconds(10));
    if (rank == 0 || !alike)
      std::cerr << "viscofilm: run stopped"
                << (alike ? std::string() : " (on MPI rank " + std::to_string(rank) + ")")
                << ": " << message << std::endl;
    if (!alike)
      MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }


  /// Read @p filename and, unless @p validate_only, run it in dim
  /// dimensions; the exit code.
  template <int dim>
  int
  run(const std::string &filename, const bool validate_only)
  {
    using namespace viscofilm;
    const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    const auto fail    = [is_root](const std::string &what, const std::string &message) {
      if (is_root)
        std::cerr << "viscofilm: " << what << ": " << message << std::endl;
      return 1;
    };

    ParameterHandler prm;
    Parameters<dim>  parameters;
    try
      {
        read_parameters(filename, prm, parameters);
      }
    catch (const std::exception &e)
      {
        return fail("error in the input", error_message(e));
      }

    if (validate_only)
      {
        if (is_root)
          std::cout << filename << ": valid" << std::endl;
        return 0;
      }

    const StopCommunicator stop;
    try
      {
        Problem<dim> problem(parameters, prm, MPI_COMM_WORLD);
        problem.run();
      }
    catch (const ExcInput &e)
      {
        return fail("error in the input", error_message(e));
      }
    catch (const std::exception &e)
      {
        return stop_run(error_message(e), stop.comm);
      }
    return 0;
  }
} // namespace


int
main(int argc, char *argv[])
{
  using namespace viscofilm;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  std::vector<std::string> args(argv + 1, argv + argc);

  // Threads within each rank: --threads, else DEAL_II_NUM_THREADS, else 1
  // (MPI_InitFinalize above); deal.II caps the count at DEAL_II_NUM_THREADS.
  try
    {
      const char *environment = std::getenv("DEAL_II_NUM_THREADS");
      if (!args.empty() && args[0] == "--threads")
        {
          check_input(args.size() > 1,
                      "--threads must be followed by the number of threads per MPI rank");
          MultithreadInfo::set_thread_limit(thread_count(args[1], "--threads"));
          args.erase(args.begin(), args.begin() + 2);
        }
      else if (environment != nullptr)
        MultithreadInfo::set_thread_limit(
          thread_count(environment, "the environment variable DEAL_II_NUM_THREADS"));
    }
  catch (const std::exception &e)
    {
      if (is_root)
        std::cerr << "viscofilm: error on the command line: " << error_message(e)
                  << std::endl;
      return 2;
    }

  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h"))
    {
      if (is_root)
        std::cout << usage;
      return 0;
    }

  if (args.size() == 1 && args[0] == "--version")
    {
      if (is_root)
        std::cout << build_description() << std::endl;
      return 0;
    }

  if (args.size() == 1 && args[0] == "--print-parameters")
    {
      // The 2D defaults, and the default mesh's (the channel's) boundaries.
      ParameterHandler prm;
      ParameterHandler geometry_input;
      Geometry<2>      geometry;
      Geometry<2>::declare_parameters(geometry_input);
      declare_for_mesh(prm, geometry_input, geometry, "");
      if (is_root)
        prm.print_parameters(std::cout, ParameterHandler::PRM);
      return 0;
    }

  const bool validate_only = (args.size() == 2 && args[0] == "--validate");
  if (!(validate_only || (args.size() == 1 && args[0].rfind("-", 0) != 0)))
    {
      if (is_root)
        std::cerr << "viscofilm: unknown command line; see below.\n" << usage;
      return 2;
    }
  const std::string filename = args.back();
  return requested_dimension(filename) == 3 ? run<3>(filename, validate_only) :
                                              run<2>(filename, validate_only);
}
