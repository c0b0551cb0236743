#include <deal.II/base/multithread_info.h>
#include <deal.II/base/mpi.h>

#include <Trilinos_version.h>
#include <viscofilm/core/version.h>

namespace viscofilm
{
  std::string
  build_description()
  {
    return std::string("viscofilm ") + source_revision + " (" + build_type +
           " build), deal.II " + DEAL_II_PACKAGE_VERSION + ", Trilinos " +
           TRILINOS_VERSION_STRING;
  }


  std::string
  run_description(const MPI_Comm comm)
  {
    return build_description() + "; " +
           std::to_string(dealii::Utilities::MPI::n_mpi_processes(comm)) + " MPI rank(s) × " +
           std::to_string(dealii::MultithreadInfo::n_threads()) + " thread(s)";
  }
} // namespace viscofilm
