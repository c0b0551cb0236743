// viscofilm: command line entry point. The physics lives in the library.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <viscofilm/input.h>
#include <viscofilm/parameters.h>
#include <viscofilm/problem.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  const char *usage =
    "Usage: viscofilm FILE.prm              run the simulation described in FILE.prm\n"
    "       viscofilm --validate FILE.prm   check FILE.prm and exit\n"
    "       viscofilm --print-parameters    print every parameter with its\n"
    "                                       documentation and default\n"
    "       viscofilm --help                print this message\n"
    "Run in parallel with: mpirun -np N viscofilm FILE.prm\n";

  /// The text of @p filename with "include FILE" resolved relative to the
  /// including file's directory (deal.II resolves it relative to the working
  /// directory), so that prm/ variants can include prm/default.prm.
  std::string
  read_with_includes_resolved(const std::string &filename)
  {
    std::ifstream     file(filename);
    std::string       line, text;
    const auto        directory = std::filesystem::path(filename).parent_path();
    const std::string keyword   = "include";
    while (std::getline(file, line))
      {
        const auto start = line.find_first_not_of(" \t");
        if (start != std::string::npos && line.compare(start, keyword.size(), keyword) == 0 &&
            line.size() > start + keyword.size() &&
            std::isspace(line[start + keyword.size()]))
          {
            const std::filesystem::path included(
              dealii::Utilities::trim(line.substr(start + keyword.size())));
            viscofilm::check_input(
              std::filesystem::is_regular_file(directory / included) ||
                std::filesystem::is_regular_file(included),
              "parameter file \"" + filename + "\" includes \"" +
                included.string() + "\", which does not exist");
            line = keyword + " " +
                   (std::filesystem::is_regular_file(directory / included) ?
                      (directory / included).string() :
                      included.string());
          }
        text += line + "\n";
      }
    return text;
  }


  /// Read @p filename into @p prm and @p parameters, or throw with a message
  /// that names the file, the line and the parameter.
  void
  read_parameters(const std::string &     filename,
                  dealii::ParameterHandler &prm,
                  viscofilm::Parameters &  parameters)
  {
    viscofilm::check_input(std::filesystem::is_regular_file(filename),
                           "parameter file \"" + filename + "\" does not exist");
    viscofilm::check_input(filename.size() > 4 &&
                             filename.substr(filename.size() - 4) == ".prm",
                           "parameter file \"" + filename +
                             "\" must have the extension .prm");
    std::istringstream text(read_with_includes_resolved(filename));
    prm.parse_input(text, filename);
    parameters.parse_parameters(prm);
  }
} // namespace


int
main(int argc, char *argv[])
{
  using namespace viscofilm;
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const std::vector<std::string> args(argv + 1, argv + argc);

  const auto fail = [is_root](const std::string &what, const std::string &message) {
    if (is_root)
      std::cerr << "viscofilm: " << what << ": " << message << std::endl;
    return 1;
  };

  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h"))
    {
      if (is_root)
        std::cout << usage;
      return 0;
    }

  ParameterHandler prm;
  Parameters       parameters;
  Parameters::declare_parameters(prm);

  if (args.size() == 1 && args[0] == "--print-parameters")
    {
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

  try
    {
      Problem problem(parameters, prm, MPI_COMM_WORLD);
      problem.run();
    }
  catch (const ExcInput &e)
    {
      return fail("error in the input", error_message(e));
    }
  catch (const std::exception &e)
    {
      return fail("run stopped", error_message(e));
    }
  return 0;
}
