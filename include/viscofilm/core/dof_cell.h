// The fields live on separate DoFHandlers of one mesh: the same mesh cell seen
// through another DoFHandler.
#ifndef viscofilm_dof_cell_h
#define viscofilm_dof_cell_h

#include <deal.II/dofs/dof_handler.h>

#include <viscofilm/core/dimension.h>

namespace viscofilm
{
  using namespace dealii;

  /// The active cell of @p dofs that is @p cell (an iterator of the
  /// triangulation or of any DoFHandler on it).
  template <int dim, class CellIterator>
  typename DoFHandler<dim>::active_cell_iterator
  cell_of(const DoFHandler<dim> &dofs, const CellIterator &cell)
  {
    return typename DoFHandler<dim>::active_cell_iterator(&dofs.get_triangulation(),
                                                          cell->level(),
                                                          cell->index(),
                                                          &dofs);
  }
} // namespace viscofilm

#endif
