#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/vector_tools.h>

#include <viscofilm/volume_fraction.h>

#include <limits>

namespace viscofilm
{
  VolumeFraction::VolumeFraction(
    const parallel::distributed::Triangulation<2> &triangulation)
    : mpi_communicator(triangulation.get_communicator())
    , fe(2)
    , dofs(triangulation)
  {}


  void
  VolumeFraction::setup_dofs()
  {
    dofs.distribute_dofs(fe);
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    constraints.close();
    current_solution.reinit(dofs.locally_owned_dofs(),
                            locally_relevant_dofs,
                            mpi_communicator);
  }


  void
  VolumeFraction::interpolate(const Function<2> &initial)
  {
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              mpi_communicator);
    VectorTools::interpolate(dofs, initial, distributed);
    constraints.distribute(distributed);
    current_solution = distributed;
  }


  const DoFHandler<2> &
  VolumeFraction::dof_handler() const
  {
    return dofs;
  }


  const TrilinosWrappers::MPI::Vector &
  VolumeFraction::solution() const
  {
    return current_solution;
  }


  double
  VolumeFraction::integral() const
  {
    const QGauss<2>     quadrature(fe.degree + 1);
    FEValues<2>         fe_values(fe, quadrature, update_values | update_JxW_values);
    std::vector<double> values(quadrature.size());
    double              sum = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(current_solution, values);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            sum += values[q] * fe_values.JxW(q);
        }
    return Utilities::MPI::sum(sum, mpi_communicator);
  }


  std::pair<double, double>
  VolumeFraction::range() const
  {
    double low  = std::numeric_limits<double>::max();
    double high = std::numeric_limits<double>::lowest();
    for (const auto i : dofs.locally_owned_dofs())
      {
        low  = std::min(low, current_solution[i]);
        high = std::max(high, current_solution[i]);
      }
    return {Utilities::MPI::min(low, mpi_communicator),
            Utilities::MPI::max(high, mpi_communicator)};
  }
} // namespace viscofilm
