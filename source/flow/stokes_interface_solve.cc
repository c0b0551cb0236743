#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <viscofilm/flow/stokes_interface_solve.h>

#include <algorithm>
#include <tuple>

namespace viscofilm
{
  namespace
  {
    /// The locally owned rows of @p matrix flagged in @p rows (ghosted) that
    /// have an entry in a column where @p columns (ghosted) is zero (@p
    /// outside) or non-zero.
    std::vector<types::global_dof_index>
    rows_coupling_to(const TrilinosWrappers::SparseMatrix &matrix,
                     const TrilinosWrappers::MPI::Vector & rows,
                     const TrilinosWrappers::MPI::Vector & columns,
                     const bool                            outside)
    {
      std::vector<types::global_dof_index> selected;
      for (const types::global_dof_index r : matrix.locally_owned_range_indices())
        if (rows[r] != 0)
          for (auto entry = matrix.begin(r); entry != matrix.end(r); ++entry)
            if ((columns[entry->column()] == 0) == outside)
              {
                selected.push_back(r);
                break;
              }
      return selected;
    }


    /// @p source (owned values) with ghost values at @p columns.
    TrilinosWrappers::MPI::Vector
    ghosted(const TrilinosWrappers::MPI::Vector &source, const IndexSet &columns)
    {
      TrilinosWrappers::MPI::Vector result(source.locally_owned_elements(),
                                           columns,
                                           source.get_mpi_communicator());
      result = source;
      return result;
    }


    /// A ghosted vector (ghosts at @p columns) of @p matrix's layout, @p
    /// values at @p dofs (owned), 0 elsewhere.
    TrilinosWrappers::MPI::Vector
    indicator(const TrilinosWrappers::SparseMatrix &        matrix,
              const IndexSet &                              columns,
              const std::vector<types::global_dof_index> & dofs,
              const std::vector<double> &                   values)
    {
      const IndexSet &              owned = matrix.locally_owned_range_indices();
      TrilinosWrappers::MPI::Vector local(owned, matrix.get_mpi_communicator());
      for (unsigned int k = 0; k < dofs.size(); ++k)
        local.begin()[owned.index_within_set(dofs[k])] = values[k];
      return ghosted(local, columns);
    }
  } // namespace


  void
  InterfaceSolve::reinit(const TrilinosWrappers::SparseMatrix &matrix)
  {
    factorization.reset();
    std::vector<types::global_dof_index> indices;
    for (const types::global_dof_index r : matrix.locally_owned_range_indices())
      for (auto entry = matrix.begin(r); entry != matrix.end(r); ++entry)
        indices.push_back(entry->column());
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    columns = IndexSet(matrix.n());
    columns.add_indices(indices.begin(), indices.end());
    columns.compress();
  }


  void
  InterfaceSolve::build(const TrilinosWrappers::SparseMatrix &matrix,
                        const TrilinosWrappers::MPI::Vector & viscous,
                        const std::string &                   direct_solver)
  {
    factorization.reset();
    // No viscous cell anywhere (a viscosity ratio below the threshold): off.
    if (viscous.linfty_norm() == 0)
      return;
    const MPI_Comm                      comm    = matrix.get_mpi_communicator();
    const IndexSet &                    owned   = matrix.locally_owned_range_indices();
    const TrilinosWrappers::MPI::Vector high    = ghosted(viscous, columns);

    // Two rings of the viscous region's dofs along its edge.
    const std::vector<types::global_dof_index> edge = rows_coupling_to(matrix, high, high, true);
    const TrilinosWrappers::MPI::Vector        on_edge =
      indicator(matrix, columns, edge, std::vector<double>(edge.size(), 1.0));
    std::vector<types::global_dof_index> band = edge;
    for (const types::global_dof_index r : rows_coupling_to(matrix, high, on_edge, false))
      if (on_edge[r] == 0)
        band.push_back(r);
    std::sort(band.begin(), band.end());

    const IndexSet band_owned = Utilities::MPI::create_ascending_partitioning(
      comm, band.size())[Utilities::MPI::this_mpi_process(comm)];
    if (band_owned.size() == 0)
      return;

    // Each band dof's index in the band, plus one (0: not in the band).
    std::vector<double> numbers(band.size());
    for (unsigned int k = 0; k < band.size(); ++k)
      numbers[k] = band_owned.nth_index_in_set(k) + 1;
    const TrilinosWrappers::MPI::Vector band_number = indicator(matrix, columns, band, numbers);

    // The band's entries (band row, band column, value), then its matrix.
    std::vector<std::tuple<types::global_dof_index, types::global_dof_index, double>> entries;
    for (const types::global_dof_index r : band)
      for (auto entry = matrix.begin(r); entry != matrix.end(r); ++entry)
        if (band_number[entry->column()] != 0)
          entries.emplace_back(static_cast<types::global_dof_index>(band_number[r]) - 1,
                               static_cast<types::global_dof_index>(
                                 band_number[entry->column()]) - 1,
                               entry->value());
    TrilinosWrappers::SparsityPattern sparsity(band_owned, comm);
    for (const auto &[row, column, value] : entries)
      sparsity.add(row, column);
    sparsity.compress();
    band_matrix.reinit(sparsity);
    for (const auto &[row, column, value] : entries)
      band_matrix.set(row, column, value);
    band_matrix.compress(VectorOperation::insert);

    band_rhs.reinit(band_owned, comm);
    band_solution.reinit(band_owned, comm);
    band_positions.clear();
    for (const types::global_dof_index r : band)
      band_positions.push_back(owned.index_within_set(r));
    factorization = std::make_unique<TrilinosWrappers::SolverDirect>(
      control, TrilinosWrappers::SolverDirect::AdditionalData(false, direct_solver));
    factorization->initialize(band_matrix);
  }


  void
  InterfaceSolve::add_solve(TrilinosWrappers::MPI::Vector &      dst,
                            const TrilinosWrappers::MPI::Vector &src) const
  {
    for (unsigned int k = 0; k < band_positions.size(); ++k)
      band_rhs.begin()[k] = src.begin()[band_positions[k]];
    factorization->solve(band_solution, band_rhs);
    for (unsigned int k = 0; k < band_positions.size(); ++k)
      dst.begin()[band_positions[k]] += band_solution.begin()[k];
  }
} // namespace viscofilm
