#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>

#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/biofilm/detachment.h>
#include <viscofilm/core/input.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/material/total_stress.h>

#include <algorithm>
#include <limits>

namespace viscofilm
{
  template <int dim>
  void
  Detachment<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Detachment");
    Biofilm<dim>::declare_entries(prm);
    prm.declare_entry("Release",
                      "false",
                      Patterns::Bool(),
                      "true: biofilm whose load exceeds Stress threshold for "
                      "Duration is released: φ := 0 at those nodes after the "
                      "step's transport, and the released mass goes into the "
                      "detached fraction φ_d, which the flow carries and which "
                      "leaves through outflow boundaries (statistics.csv: "
                      "detached_mass, detached_mass_total, "
                      "detached_mass_in_flow, detached_mass_outflow, where it "
                      "came from; the snapshots' phi_detached; "
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
    prm.declare_entry("Release unattached",
                      "true",
                      Patterns::Bool(),
                      "With Release = true: after the release by strength, "
                      "biofilm (φ >= Interface volume fraction) that no path "
                      "of biofilm joins to one of Walls is released too: a "
                      "piece cut off from the wall, or an island that never "
                      "touched it (statistics.csv: detached_by_connectivity). "
                      "Needs at least one boundary in Walls. false: only the "
                      "strength releases.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Detachment<dim>::Parameters::parse_parameters(ParameterHandler &             prm,
                                                const BoundaryConditions<dim> &boundary_conditions)
  {
    prm.enter_subsection("Detachment");
    biofilm.parse_entries(prm, boundary_conditions);
    enabled   = prm.get_bool("Release");
    criterion = (prm.get("Criterion") == "interface traction" ?
                   Criterion::interface_traction :
                   Criterion::von_mises);
    duration  = prm.get_double("Duration");
    release_unattached = prm.get_bool("Release unattached");
    prm.leave_subsection();
    check_input(!enabled || !release_unattached || !biofilm.walls.empty(),
                "Detachment/Release unattached = true needs the walls the biofilm "
                "is attached to in Detachment/Walls, which names no boundary of "
                "this mesh (set Walls, or Release unattached = false)");
  }


  template <int dim>
  Detachment<dim>::Detachment(const Parameters &                             parameters,
                         const Model &                                  model,
                         const parallel::distributed::Triangulation<dim> &triangulation,
                         const typename VolumeFraction<dim>::Parameters & transport,
                         const BoundaryConditions<dim> &                boundary_conditions,
                         const StokesFlow<dim> &                      stokes,
                         VolumeFraction<dim> &                          volume_fraction,
                         const ElasticStress<dim> &                     stress)
    : parameters(parameters)
    , model(model)
    , stokes(stokes)
    , volume_fraction(volume_fraction)
    , stress(stress)
    , boundary_conditions(boundary_conditions)
    , detached(triangulation, volume_fraction.mapping(), transport, boundary_conditions, "phi_detached", false)
  {
    if (parameters.enabled && parameters.duration > 0)
      volume_fraction.carry(clock);
  }


  template <int dim>
  void
  Detachment<dim>::setup_dofs()
  {
    if (!parameters.enabled || parameters.duration == 0)
      return;
    const DoFHandler<dim> &dofs = volume_fraction.dof_handler();
    clock.reinit(dofs.locally_owned_dofs(),
                 DoFTools::extract_locally_relevant_dofs(dofs),
                 dofs.get_communicator());
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector
  Detachment<dim>::nodal_load() const
  {
    const DoFHandler<dim> &dofs  = volume_fraction.dof_handler();
    const IndexSet         owned = dofs.locally_owned_dofs();
    const MPI_Comm         comm  = dofs.get_communicator();
    const double           level = parameters.biofilm.interface_level;
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


  template <int dim>
  void
  Detachment<dim>::release(DepartureFeet<dim> &feet, const double time_step, const unsigned int order)
  {
    step_mass         = 0;
    connectivity_mass = 0;
    if (!parameters.enabled)
      return;
    // What was released before is carried by the step's flow as φ was
    // (nothing to carry, nothing to compute: φ_d >= 0). No boundary brings
    // φ_d in, so what the step takes from ∫φ_d has left through the
    // outflow boundaries: the scheme's k∫φ_d u·n ds wherever its mass fixer
    // reaches it (doc/detachment.md).
    if (detached.range().second > 0)
      {
        const double mass = detached.integral();
        detached.advance(stokes, feet, model.diffusion, time_step, order);
        total.outflow += mass - detached.integral();
      }

    const DoFHandler<dim> &dofs  = volume_fraction.dof_handler();
    const IndexSet         owned = dofs.locally_owned_dofs();
    const MPI_Comm         comm  = dofs.get_communicator();
    TrilinosWrappers::MPI::Vector before(owned, comm);
    before = volume_fraction.solution();
    TrilinosWrappers::MPI::Vector after(before);
    std::vector<bool>             released(owned.n_elements(), false);

    const auto released_anywhere = [&]() {
      return Utilities::MPI::logical_or(std::find(released.begin(), released.end(), true) !=
                                          released.end(),
                                        comm);
    };
    release_by_strength(time_step, after, released);
    const bool by_strength = released_anywhere();
    if (by_strength)
      volume_fraction.set(after);
    if (parameters.release_unattached)
      {
        const double mass = volume_fraction.integral();
        const auto   n_by_strength = std::count(released.begin(), released.end(), true);
        release_unattached(volume_fraction.solution(), after, released);
        if (Utilities::MPI::logical_or(std::count(released.begin(), released.end(), true) >
                                         n_by_strength,
                                       comm))
          {
            volume_fraction.set(after);
            connectivity_mass = mass - volume_fraction.integral();
          }
      }
    if (!released_anywhere())
      {
        record(TrilinosWrappers::MPI::Vector(), {});
        return;
      }

    // φ's loss (what set() left of the release: hanging nodes follow their
    // masters) goes into φ_d, node by node: φ_d's DoFHandler has φ's mesh and
    // element, so deal.II numbers its dofs as φ's.
    before -= after;
    TrilinosWrappers::MPI::Vector gained(owned, comm);
    gained = detached.solution();
    gained += before;
    detached.set(gained);
    TrilinosWrappers::MPI::Vector loss(owned,
                                       DoFTools::extract_locally_relevant_dofs(dofs),
                                       comm);
    loss = before;

    // Where the released nodes are: their bounding box.
    std::vector<Point<dim>> released_nodes;
    FEValues<dim>           node_values(volume_fraction.mapping(),
                              dofs.get_fe(),
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


  template <int dim>
  void
  Detachment<dim>::release_by_strength(const double              time_step,
                                  TrilinosWrappers::MPI::Vector &phi,
                                  std::vector<bool> &            released)
  {
    const DoFHandler<dim> &             dofs  = volume_fraction.dof_handler();
    const IndexSet                      owned = dofs.locally_owned_dofs();
    const TrilinosWrappers::MPI::Vector load  = nodal_load();
    // Which owned nodes go: those whose load has exceeded the strength for
    // Duration (with Duration = 0 the clock is only this step).
    TrilinosWrappers::MPI::Vector clock_now(owned, dofs.get_communicator());
    for (const types::global_dof_index i : owned)
      {
        const double previous = (parameters.duration > 0 ? clock(i) : 0.0);
        clock_now(i) = (load(i) > parameters.biofilm.stress_threshold ? previous + time_step : 0);
        if (load(i) > parameters.biofilm.stress_threshold &&
            clock_now(i) >= parameters.duration * (1 - 1e-12))
          {
            phi(i)                              = 0;
            released[owned.index_within_set(i)] = true;
          }
      }
    clock_now.compress(VectorOperation::insert);
    phi.compress(VectorOperation::insert);
    if (parameters.duration > 0)
      clock = clock_now;
  }


  template <int dim>
  void
  Detachment<dim>::build_connectivity()
  {
    const DoFHandler<dim> &dofs = volume_fraction.dof_handler();
    const IndexSet         owned = dofs.locally_owned_dofs();
    const MPI_Comm         comm  = dofs.get_communicator();
    Connectivity &         graph = connectivity.emplace();
    graph.relevant               = DoFTools::extract_locally_relevant_dofs(dofs);
    const IndexSet &relevant     = graph.relevant;
    // Nodes of one cell (owned or ghost) are joined, and so are a
    // constrained node and its masters (periodic images, hanging nodes).
    std::vector<types::global_dof_index> local_dofs(dofs.get_fe().n_dofs_per_cell());
    std::vector<types::global_dof_index> face_dofs(dofs.get_fe().n_dofs_per_face());
    std::vector<bool>                    on_wall(relevant.n_elements(), false);
    for (const auto &cell : dofs.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(local_dofs);
          std::vector<unsigned int> nodes;
          for (const auto dof : local_dofs)
            nodes.push_back(relevant.index_within_set(dof));
          graph.cells.push_back(nodes);
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) && parameters.biofilm.is_wall(cell->face(f)->boundary_id()))
              {
                cell->face(f)->get_dof_indices(face_dofs);
                for (const auto dof : face_dofs)
                  on_wall[relevant.index_within_set(dof)] = true;
              }
        }
    AffineConstraints<double> constraints(relevant);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    boundary_conditions.constrain_periodic(dofs, constraints);
    constraints.close();
    for (const auto &line : constraints.get_lines())
      if (relevant.is_element(line.index))
        for (const auto &[master, weight] : line.entries)
          if (relevant.is_element(master))
            graph.cells.push_back(
              {relevant.index_within_set(line.index), relevant.index_within_set(master)});
    graph.cells_of.resize(relevant.n_elements());
    for (unsigned int c = 0; c < graph.cells.size(); ++c)
      for (const unsigned int k : graph.cells[c])
        graph.cells_of[k].push_back(c);
    for (unsigned int k = 0; k < relevant.n_elements(); ++k)
      if (on_wall[k])
        graph.wall_nodes.push_back(k);
    graph.shared.reinit(owned, relevant, comm, true);
    graph.seen.reinit(owned, relevant, comm);
    graph.sum.reinit(owned, comm);
  }


  template <int dim>
  void
  Detachment<dim>::release_unattached(const TrilinosWrappers::MPI::Vector &ghosted_phi,
                                 TrilinosWrappers::MPI::Vector &      phi,
                                 std::vector<bool> &                  released)
  {
    // The graph and the ghost vectors depend on the mesh only: built once
    // per mesh (cleared by mesh_changed()).
    if (!connectivity)
      build_connectivity();
    Connectivity &         graph    = *connectivity;
    const IndexSet &       relevant = graph.relevant;
    const IndexSet         owned    = volume_fraction.dof_handler().locally_owned_dofs();
    const MPI_Comm         comm     = volume_fraction.dof_handler().get_communicator();
    const unsigned int     n        = relevant.n_elements();

    // The walk goes through biofilm nodes only; the seeds: biofilm on a
    // wall.
    std::vector<bool> biofilm(n);
    for (unsigned int k = 0; k < n; ++k)
      biofilm[k] = (ghosted_phi(relevant.nth_index_in_set(k)) >= parameters.biofilm.interface_level);
    std::vector<bool> attached(n, false);
    for (const unsigned int k : graph.wall_nodes)
      attached[k] = biofilm[k];

    // Flood from the walls on this rank, share with the ranks that see the
    // same nodes, again until no rank attaches a node more.
    std::vector<bool> cell_done(graph.cells.size(), false);
    for (types::global_dof_index n_attached = 0;;)
      {
        std::vector<unsigned int> front;
        for (unsigned int k = 0; k < n; ++k)
          if (attached[k])
            front.push_back(k);
        while (!front.empty())
          {
            const unsigned int k = front.back();
            front.pop_back();
            for (const unsigned int c : graph.cells_of[k])
              if (!cell_done[c])
                {
                  cell_done[c] = true;
                  for (const unsigned int other : graph.cells[c])
                    if (biofilm[other] && !attached[other])
                      {
                        attached[other] = true;
                        front.push_back(other);
                      }
                }
          }
        graph.shared = 0;
        for (unsigned int k = 0; k < n; ++k)
          if (attached[k])
            graph.shared(relevant.nth_index_in_set(k)) += 1;
        graph.shared.compress(VectorOperation::add);
        for (const types::global_dof_index i : owned)
          graph.sum(i) = graph.shared(i);
        graph.seen = graph.sum;
        types::global_dof_index owned_attached = 0;
        for (unsigned int k = 0; k < n; ++k)
          {
            const types::global_dof_index dof = relevant.nth_index_in_set(k);
            attached[k] = attached[k] || graph.seen(dof) > 0;
            owned_attached += (attached[k] && owned.is_element(dof));
          }
        owned_attached = Utilities::MPI::sum(owned_attached, comm);
        if (owned_attached == n_attached)
          break;
        n_attached = owned_attached;
      }

    for (const types::global_dof_index i : owned)
      {
        const unsigned int k = relevant.index_within_set(i);
        if (biofilm[k] && !attached[k])
          {
            phi(i)                              = 0;
            released[owned.index_within_set(i)] = true;
          }
      }
    phi.compress(VectorOperation::insert);
  }


  template <int dim>
  void
  Detachment<dim>::record(const TrilinosWrappers::MPI::Vector &released,
                     const std::vector<Point<dim>> &      released_nodes)
  {
    const DoFHandler<dim> &dofs = volume_fraction.dof_handler();
    const MPI_Comm         comm = dofs.get_communicator();
    // ∫ loss and ∫ x loss (mass and its first moments).
    double moments[dim + 1] = {};
    if (released.size() > 0)
      {
        const QGauss<dim>   quadrature(dofs.get_fe().degree + 1);
        FEValues<dim>       values(volume_fraction.mapping(),
                             dofs.get_fe(),
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
    total.released += step_mass;
    const bool any = (low[0] <= high[0]);
    for (unsigned int d = 0; d < dim; ++d)
      {
        centroid[d] = (step_mass != 0 ? moments[d] / step_mass : 0);
        lower[d]    = (any ? low[d] : 0);
        upper[d]    = (any ? high[d] : 0);
      }
  }


  template <int dim>
  void
  Detachment<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    if (!parameters.enabled)
      return;
    statistics.set("detached_mass", step_mass);
    statistics.set("detached_by_connectivity", connectivity_mass);
    statistics.set("detached_mass_total", total.released);
    statistics.set("detached_mass_in_flow", detached.integral());
    statistics.set("detached_mass_outflow", total.outflow);
    for (unsigned int d = 0; d < dim; ++d)
      {
        const std::string x(1, "xyz"[d]);
        statistics.set("detached_centroid_" + x, centroid[d]);
        statistics.set("detached_" + x + "_min", lower[d]);
        statistics.set("detached_" + x + "_max", upper[d]);
      }
  }


  template <int dim>
  void
  Detachment<dim>::add_output(DataOut<dim> &data_out)
  {
    if (parameters.enabled)
      detached.add_output(data_out);
  }


  template <int dim>
  const VolumeFraction<dim> *
  Detachment<dim>::detached_fraction() const
  {
    return parameters.enabled ? &detached : nullptr;
  }


  template <int dim>
  VolumeFraction<dim> *
  Detachment<dim>::detached_fraction()
  {
    return parameters.enabled ? &detached : nullptr;
  }


  template <int dim>
  void
  Detachment<dim>::mesh_changed()
  {
    connectivity.reset();
  }


  template <int dim>
  void
  Detachment<dim>::save_state(CheckpointValues &values) const
  {
    values["detached"]         = total.released;
    values["detached_outflow"] = total.outflow;
  }


  template <int dim>
  void
  Detachment<dim>::load_state(const CheckpointValues &values)
  {
    total.released = checkpoint_value(values, "detached");
    total.outflow  = checkpoint_value(values, "detached_outflow");
  }


  VISCOFILM_INSTANTIATE(Detachment)
} // namespace viscofilm
