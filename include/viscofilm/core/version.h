// What built this program: printed at the start of every run, recorded in
// parameters.prm and printed by viscofilm --version (doc/output.md).
#ifndef viscofilm_version_h
#define viscofilm_version_h

#include <deal.II/base/mpi.h>

#include <string>

namespace viscofilm
{
  /// git describe of the source tree at build time ("-dirty": with
  /// uncommitted changes) and CMAKE_BUILD_TYPE; defined in the file that
  /// cmake/version.cmake generates.
  extern const char *const source_revision;
  extern const char *const build_type;

  /// "viscofilm REVISION (TYPE build), deal.II X, Trilinos Y".
  std::string
  build_description();

  /// build_description() with the MPI ranks of @p comm and the threads per
  /// rank.
  std::string
  run_description(const MPI_Comm comm);
} // namespace viscofilm

#endif
