#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <viscofilm/detachment.h>
#include <viscofilm/output.h>
#include <viscofilm/total_stress.h>

#include <algorithm>
#include <limits>

namespace viscofilm
{
  void
  Detachment::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Detachment");
    prm.declare_entry("Release",
                      "false",
                      Patterns::Bool(),
                      "true: biofilm whose load exceeds Stress threshold for "
                      "Duration is released: φ := 0 at those nodes after the "
                      "step's transport; the released mass is carried away by "
                      "the flow (statistics.csv: detached_mass, "
                      "detached_mass_total, where it came from; "
                      "doc/detachment.md). false: the loads are only reported.");
    prm.declare_entry("Criterion",
                      "von Mises",
                      Patterns::Selection("von Mises|interface traction"),
                      "The load compared with Stress threshold at each node of "
                      "φ in the biofilm (φ >= Interface volume fraction). von "
                      "Mises: σ_vm of the total stress (bulk failure). "
                      "interface traction: |σ n|, n = −∇φ/|∇φ|, at the nodes of "
                      "the cells the outline cuts (erosion from the surface).");
    prm.declare_entry("Duration",
                      "0",
                      Patterns::Double(0),
                      "How long (in the run's time unit) the load at a node must "
                      "stay above Stress threshold before the node is released; "
                      "0: at once.");
    prm.leave_subsection();
  }


  void
  Detachment::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Detachment");
    enabled   = prm.get_bool("Release");
    criterion = (prm.get("Criterion") == "interface traction" ?
                   Criterion::interface_traction :
                   Criterion::von_mises);
    duration  = prm.get_double("Duration");
    prm.leave_subsection();
  }


  Detachment::Detachment(const Parameters &              parameters,
                         const BiofilmLoads::Parameters &loads,
                         const Model &                   model,
                         const StokesSolver &            stokes,
                         VolumeFraction &                volume_fraction,
                         const ElasticStress &           stress)
    : parameters(parameters)
    , loads(loads)
    , model(model)
    , stokes(stokes)
    , volume_fraction(volume_fraction)
    , stress(stress)
  {}


  void
  Detachment::setup_dofs()
  {
    if (!parameters.enabled || parameters.duration == 0)
      return;
    const DoFHandler<dim> &dofs = volume_fraction.dof_handler();
    clock.reinit(dofs.locally_owned_dofs(),
                 DoFTools::extract_locally_relevant_dofs(dofs),
                 dofs.get_communicator());
  }


  TrilinosWrappers::MPI::Vector
  Detachment::nodal_load() const
  {
    const DoFHandler<dim> &dofs  = volume_fraction.dof_handler();
    const IndexSet         owned = dofs.locally_owned_dofs();
    const MPI_Comm         comm  = dofs.get_communicator();
    const double           level = loads.interface_level;
    const bool             traction =
      (parameters.criterion == Parameters::Criterion::interface_traction);

    // Each cell's fields at φ's nodes: ∇u, p and so σ jump between cells,
    // so a node takes the mean over the cells around it that count.
    TrilinosWrappers::MPI::Vector sum;
    sum.reinit(owned, DoFTools::extract_locally_relevant_dofs(dofs), comm, true);
    TrilinosWrappers::MPI::Vector count(sum);
    const Quadrature<dim>       nodes(dofs.get_fe().get_unit_support_points());
    TotalStress<FEValues<dim>>  total_stress(
      nodes, model, stokes, volume_fraction, stress);
    std::vector<types::global_dof_index> local_dofs(nodes.size());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          total_stress.reinit(cell);
          const auto [low, high] =
            std::minmax_element(total_stress.phi.begin(), total_stress.phi.end());
          // Cells cut by the outline: nodal φ on both sides of it.
          if (traction && !(*low < level && *high > level))
            continue;
          cell->get_dof_indices(local_dofs);
          for (unsigned int i = 0; i < nodes.size(); ++i)
            if (total_stress.phi[i] >= level)
              {
                const SymmetricTensor<2, dim> &sigma = total_stress.sigma[i];
                const Tensor<1, dim> &         grad  = total_stress.grad_phi[i];
                if (traction && grad.norm() == 0)
                  continue;
                // n points out of the biofilm: down the gradient of φ.
                sum(local_dofs[i]) += (traction ? (sigma * (-grad / grad.norm())).norm() :
                                                  von_mises(sigma));
                count(local_dofs[i]) += 1;
              }
        }
    sum.compress(VectorOperation::add);
    count.compress(VectorOperation::add);

    TrilinosWrappers::MPI::Vector load(owned, comm);
    for (const types::global_dof_index i : owned)
      load(i) = (count(i) > 0 ? sum(i) / count(i) : 0.0);
    return load;
  }


  void
  Detachment::release(const double time_step)
  {
    step_mass = 0;
    if (!parameters.enabled)
      return;
    const DoFHandler<dim> &              dofs = volume_fraction.dof_handler();
    const IndexSet                       owned = dofs.locally_owned_dofs();
    const TrilinosWrappers::MPI::Vector  load  = nodal_load();
    const TrilinosWrappers::MPI::Vector &phi   = volume_fraction.solution();

    // Which owned nodes go: those whose load has exceeded the strength for
    // Duration (with Duration = 0 the clock is only this step).
    TrilinosWrappers::MPI::Vector clock_now(owned, dofs.get_communicator());
    TrilinosWrappers::MPI::Vector before(owned, dofs.get_communicator());
    for (const types::global_dof_index i : owned)
      {
        clock_now(i) = (parameters.duration > 0 ? clock(i) : 0.0);
        before(i)    = phi(i);
      }
    TrilinosWrappers::MPI::Vector after(before);
    std::vector<bool>             released(owned.n_elements(), false);
    bool                          any = false;
    for (const types::global_dof_index i : owned)
      {
        clock_now(i) = (load(i) > loads.stress_threshold ? clock_now(i) + time_step : 0);
        if (load(i) > loads.stress_threshold &&
            clock_now(i) >= parameters.duration * (1 - 1e-12))
          {
            after(i)                             = 0;
            released[owned.index_within_set(i)] = true;
            any                                  = true;
          }
      }
    clock_now.compress(VectorOperation::insert);
    after.compress(VectorOperation::insert);
    if (parameters.duration > 0)
      clock = clock_now;
    if (!Utilities::MPI::logical_or(any, dofs.get_communicator()))
      {
        record(TrilinosWrappers::MPI::Vector(), {});
        return;
      }

    volume_fraction.set(after);
    // φ's loss: what set() left of the release (hanging nodes follow their
    // masters).
    before -= after;
    TrilinosWrappers::MPI::Vector loss(owned,
                                       DoFTools::extract_locally_relevant_dofs(dofs),
                                       dofs.get_communicator());
    loss = before;

    // Where the released nodes are: their bounding box.
    std::vector<Point<dim>> released_nodes;
    FEValues<dim>           node_values(dofs.get_fe(),
                              Quadrature<dim>(dofs.get_fe().get_unit_support_points()),
                              update_quadrature_points);
    std::vector<types::global_dof_index> local_dofs(node_values.n_quadrature_points);
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(local_dofs);
          bool reinitialized = false;
          for (unsigned int i = 0; i < local_dofs.size(); ++i)
            if (owned.is_element(local_dofs[i]) &&
                released[owned.index_within_set(local_dofs[i])])
              {
                if (!reinitialized)
                  node_values.reinit(cell);
                reinitialized = true;
                released_nodes.push_back(node_values.quadrature_point(i));
              }
        }
    record(loss, released_nodes);
  }


  void
  Detachment::record(const TrilinosWrappers::MPI::Vector &released,
                     const std::vector<Point<dim>> &      released_nodes)
  {
    const DoFHandler<dim> &dofs = volume_fraction.dof_handler();
    const MPI_Comm         comm = dofs.get_communicator();
    // ∫ loss and ∫ x loss (mass and its first moments).
    double moments[dim + 1] = {};
    if (released.size() > 0)
      {
        const QGauss<dim>   quadrature(dofs.get_fe().degree + 1);
        FEValues<dim>       values(dofs.get_fe(),
                             quadrature,
                             update_values | update_quadrature_points |
                               update_JxW_values);
        std::vector<double> loss(quadrature.size());
        for (const auto &cell : dofs.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              values.reinit(cell);
              values.get_function_values(released, loss);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                {
                  moments[dim] += loss[q] * values.JxW(q);
                  for (unsigned int d = 0; d < dim; ++d)
                    moments[d] += values.quadrature_point(q)[d] * loss[q] * values.JxW(q);
                }
            }
      }
    Utilities::MPI::sum(moments, comm, moments);
    double low[dim], high[dim];
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = std::numeric_limits<double>::max();
        high[d] = std::numeric_limits<double>::lowest();
        for (const Point<dim> &p : released_nodes)
          {
            low[d]  = std::min(low[d], p[d]);
            high[d] = std::max(high[d], p[d]);
          }
      }
    Utilities::MPI::min(low, comm, low);
    Utilities::MPI::max(high, comm, high);

    step_mass = moments[dim];
    total += step_mass;
    const bool any = (low[0] <= high[0]);
    for (unsigned int d = 0; d < dim; ++d)
      {
        centroid[d] = (step_mass != 0 ? moments[d] / step_mass : 0);
        lower[d]    = (any ? low[d] : 0);
        upper[d]    = (any ? high[d] : 0);
      }
  }


  void
  Detachment::add_statistics(CsvFile &statistics) const
  {
    if (!parameters.enabled)
      return;
    statistics.set("detached_mass", step_mass);
    statistics.set("detached_mass_total", total);
    for (unsigned int d = 0; d < dim; ++d)
      {
        const std::string x(1, "xyz"[d]);
        statistics.set("detached_centroid_" + x, centroid[d]);
        statistics.set("detached_" + x + "_min", lower[d]);
        statistics.set("detached_" + x + "_max", upper[d]);
      }
  }


  double
  Detachment::total_mass() const
  {
    return total;
  }


  void
  Detachment::set_total_mass(const double mass)
  {
    total = mass;
  }


  void
  Detachment::prepare_for_refinement()
  {
    if (clock.size() > 0)
      carrier.prepare(volume_fraction.dof_handler(), clock);
  }


  void
  Detachment::finish_refinement()
  {
    if (!parameters.enabled || parameters.duration == 0)
      return;
    const DoFHandler<dim> &       dofs = volume_fraction.dof_handler();
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              dofs.get_communicator());
    carrier.finish(dofs, distributed);
    setup_dofs();
    clock = distributed;
  }


  void
  Detachment::prepare_for_checkpoint()
  {
    if (clock.size() > 0)
      carrier.prepare_checkpoint(volume_fraction.dof_handler(), clock);
  }


  void
  Detachment::checkpoint_written()
  {
    carrier.release();
  }
} // namespace viscofilm
