#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q_iso_q1.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/numerics/vector_tools.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/core/input.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/transport/transport_scheme.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace viscofilm
{
  template <int dim>
  void
  VolumeFraction<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stabilization");
    prm.declare_entry("Volume fraction scheme",
                      "semi-Lagrangian",
                      Patterns::Selection("semi-Lagrangian|thesis|FCT"),
                      "semi-Lagrangian: φ at the departure feet of its nodes, "
                      "clipped to the nodal range of the cell there, mass "
                      "restored at the fronts; diffusion and softening with an "
                      "M-matrix: φ stays in the range of its initial and "
                      "inflow values (doc/numerics.md). thesis: GLS-stabilised "
                      "Galerkin (eq. 3.47-3.50), softening by Galerkin "
                      "diffusion; not bounded. FCT: Eulerian flux-corrected "
                      "transport (Galerkin limited towards discrete upwinding "
                      "by monolithic convex limiting), SSP-RK3 in time with the "
                      "velocity interpolated between u^n and u^{n+1}, "
                      "sub-stepped to its positivity limit; bounded like "
                      "semi-Lagrangian, conservative, on uniform and "
                      "adapted meshes.");
    prm.declare_entry("GLS tau",
                      "constant",
                      Patterns::Selection("constant|standard"),
                      "Used by Volume fraction scheme = thesis. constant: "
                      "τ_GLS = GLS parameter (the thesis, eq. 3.49). standard: "
                      "τ_GLS = GLS parameter × (4/k² + (2|u|/h)²)^(-1/2).");
    prm.declare_entry("GLS parameter",
                      "1.0",
                      Patterns::Double(0),
                      "Used by Volume fraction scheme = thesis. τ_GLS "
                      "(constant) or its factor (standard), >= 0. The thesis "
                      "used 1.0 and tried 0.3.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  VolumeFraction<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stabilization");
    const std::string name = prm.get("Volume fraction scheme");
    scheme = (name == "semi-Lagrangian" ? Scheme::semi_lagrangian :
              name == "FCT"             ? Scheme::flux_corrected :
                                          Scheme::thesis);
    standard_tau  = (prm.get("GLS tau") == "standard");
    gls_parameter = prm.get_double("GLS parameter");
    prm.leave_subsection();
  }


  template <int dim>
  VolumeFraction<dim>::VolumeFraction(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const Mapping<dim> &                           mapping,
    const Parameters &                             parameters,
    const BoundaryConditions<dim> &                boundary_conditions,
    const std::string &                            name,
    const bool                                     inflow_from_boundaries)
    : FieldType(triangulation, mapping)
    , boundary_conditions(boundary_conditions)
    , mpi_communicator(triangulation.get_communicator())
    , name(name)
    , inflow_from_boundaries(inflow_from_boundaries)
    , fe(2)
    , scheme(TransportScheme<dim>::create(parameters, *this))
  {}


  template <int dim>
  VolumeFraction<dim>::~VolumeFraction() = default;


  template <int dim>
  void
  VolumeFraction<dim>::setup_dofs()
  {
    dofs.distribute_dofs(fe);
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    boundary_conditions.constrain_periodic(dofs, constraints);
    constraints.close();
    this->setup_vectors(dofs.locally_owned_dofs(), locally_relevant_dofs);
    system_rhs.reinit(dofs.locally_owned_dofs(), mpi_communicator);

    // Inflow faces change with the flow: keep constrained dofs in the pattern
    // so that any of them can be constrained later.
    TrilinosWrappers::SparsityPattern sparsity(dofs.locally_owned_dofs(),
                                               dofs.locally_owned_dofs(),
                                               locally_relevant_dofs,
                                               mpi_communicator);
    DoFTools::make_sparsity_pattern(dofs,
                                    sparsity,
                                    constraints,
                                    /*keep constrained dofs*/ true,
                                    Utilities::MPI::this_mpi_process(
                                      mpi_communicator));
    sparsity.compress();
    system_matrix.reinit(sparsity);
    matrix_columns                = locally_relevant_dofs;
    const Epetra_Map &column_map = system_matrix.trilinos_matrix().ColMap();
    std::vector<types::global_dof_index> columns;
    for (int c = 0; c < column_map.NumMyElements(); ++c)
      columns.push_back(column_map.GID64(c));
    std::sort(columns.begin(), columns.end());
    matrix_columns.add_indices(columns.begin(), columns.end());
    matrix_columns.compress();
  }


  template <int dim>
  double
  VolumeFraction<dim>::inflow_value(const types::boundary_id id) const
  {
    return inflow_from_boundaries ? boundary_conditions.boundary(id).volume_fraction : 0.0;
  }


  template <int dim>
  void
  VolumeFraction<dim>::make_constraints(const StokesFlow<dim> *stokes)
  {
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    boundary_conditions.constrain_periodic(dofs, constraints);
    if (stokes != nullptr)
      {
        const double          max_speed = stokes->max_velocity();
        const QGauss<dim - 1> face_quadrature(3);
        FEFaceValues<dim>     stokes_face(this->mapping(),
                                      stokes->dof_handler().get_fe(),
                                    face_quadrature,
                                    update_values | update_normal_vectors | update_JxW_values);
        const FEValuesExtractors::Vector     velocities(0);
        std::vector<Tensor<1, dim>>            velocity(face_quadrature.size());
        std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
        // Ghost cells too, so that every rank constrains the same dofs.
        for (const auto &cell : dofs.active_cell_iterators())
          if (!cell->is_artificial() && cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  boundary_conditions.boundary(cell->face(f)->boundary_id()).type !=
                    BoundaryConditions<dim>::Type::periodic)
                {
                  stokes_face.reinit(cell_of(stokes->dof_handler(), cell), f);
                  stokes_face[velocities].get_function_values(stokes->solution(),
                                                              velocity);
                  if (!flow_enters(mean_normal_velocity(stokes_face, velocity), max_speed))
                    continue;
                  const double value = inflow_value(cell->face(f)->boundary_id());
                  cell->face(f)->get_dof_indices(face_dofs);
                  for (const auto dof : face_dofs)
                    if (!constraints.is_constrained(dof))
                      {
                        constraints.add_line(dof);
                        constraints.set_inhomogeneity(dof, value);
                      }
                }
      }
    constraints.close();
  }


  template <int dim>
  unsigned int
  VolumeFraction<dim>::advance(const StokesFlow<dim> &stokes,
                               DepartureFeet<dim> &   feet,
                               const double           diffusion,
                               const double           time_step,
                               const unsigned int     order,
                               const bool             estimate_error)
  {
    return scheme->advance(stokes, feet, diffusion, time_step, order, estimate_error);
  }


  template <int dim>
  double
  VolumeFraction<dim>::error_estimate() const
  {
    return scheme->error_estimate();
  }


  template <int dim>
  void
  VolumeFraction<dim>::add_exchange(const Exchange &rates, const double time_step)
  {
    exchange.net += time_step * rates.net;
    exchange.outflow += time_step * rates.outflow;
    exchange.inflow += time_step * rates.inflow;
  }


  template <int dim>
  void
  VolumeFraction<dim>::restore_old()
  {
    FieldType::restore_old();
    exchange = old_exchange;
  }


  template <int dim>
  void
  VolumeFraction<dim>::advance_time()
  {
    FieldType::advance_time();
    old_exchange = exchange;
  }


  template <int dim>
  void
  VolumeFraction<dim>::soften(const double       diffusion,
                              const unsigned int n_steps,
                              const double       time_step)
  {
    make_constraints(nullptr);
    for (unsigned int s = 0; s < n_steps; ++s)
      scheme->diffuse(diffusion, time_step);
  }


  template <int dim>
  unsigned int
  VolumeFraction<dim>::solve()
  {
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              mpi_communicator);
    distributed = current_solution;
    // ILU, cheap, serves the transport and mild diffusion; where diffusion
    // dominates (k D/Δx² of 1e4 and more: a dimensionless D on a mesh in
    // µm) it stalls, and AMG goes on from where it got, and serves every
    // later solve.
    const double  target = 1e-12 * system_rhs.l2_norm();
    unsigned int  iterations = 0;
    if (!diffusion_dominated)
      {
        SolverControl                              control(1000, target);
        SolverGMRES<TrilinosWrappers::MPI::Vector> solver(control);
        TrilinosWrappers::PreconditionILU          preconditioner;
        preconditioner.initialize(system_matrix);
        try
          {
            solver.solve(system_matrix, distributed, system_rhs, preconditioner);
            iterations = control.last_step();
          }
        catch (const SolverControl::NoConvergence &e)
          {
            iterations          = e.last_step;
            diffusion_dominated = true;
            // A diverged ILU leaves no useful start.
            if (!std::isfinite(distributed.l2_norm()))
              distributed = current_solution;
          }
      }
    if (diffusion_dominated)
      {
        SolverControl                              control(1000, target);
        SolverGMRES<TrilinosWrappers::MPI::Vector> solver(control);
        TrilinosWrappers::PreconditionAMG          preconditioner;
        preconditioner.initialize(system_matrix);
        try
          {
            solver.solve(system_matrix, distributed, system_rhs, preconditioner);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            throw ExcMessage("the volume fraction solver (GMRES with AMG) did not converge in " +
                             std::to_string(e.last_step) + " iterations: residual " +
                             to_text(e.last_residual) + ", target " + to_text(target));
          }
        iterations += control.last_step();
      }
    constraints.distribute(distributed);
    AssertThrow(std::isfinite(distributed.l2_norm()),
                ExcMessage("the volume fraction is not finite (NaN or inf)"));
    current_solution = distributed;
    return iterations;
  }


  template <int dim>
  unsigned int
  VolumeFraction<dim>::bounded_diffusion_step(const double diffusion, const double time_step)
  {
    system_matrix = 0;
    system_rhs    = 0;
    // FE_Q_iso_Q1(2) is Q1 on the 2^dim sub-cells of the Q2 nodes, numbered
    // like FE_Q(2); its lumped mass is positive and its sub-cell stiffness
    // nearly an M-matrix (exactly on squares and cubes with constant κ).
    const FE_Q_iso_Q1<dim> sub_cells(2);
    const QIterated<dim>   quadrature(QGauss<1>(2), 2);
    FEValues<dim>          values(this->mapping(),
                         sub_cells,
                       quadrature,
                       update_values | update_gradients | update_JxW_values);
    const unsigned int   n_dofs = fe.n_dofs_per_cell();
    FullMatrix<double>   cell_matrix(n_dofs, n_dofs);
    Vector<double>       cell_rhs(n_dofs);
    std::vector<double>  phi_old(n_dofs);
    std::vector<types::global_dof_index> local_dofs(n_dofs);
    // A quadrature point lies in one sub-cell: the 2^dim shape functions of
    // its nodes are the only ones not zero there (value and gradient).
    std::vector<std::vector<unsigned int>> support(quadrature.size());
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (sub_cells.shape_value(i, quadrature.point(q)) != 0 ||
            sub_cells.shape_grad(i, quadrature.point(q)).norm() != 0)
          support[q].push_back(i);
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          values.reinit(static_cast<typename Triangulation<dim>::cell_iterator>(cell));
          cell->get_dof_values(current_solution, phi_old.begin(), phi_old.end());
          cell_matrix = 0;
          cell_rhs    = 0;
          for (const unsigned int q : values.quadrature_point_indices())
            {
              // D φ^n (eq. 3.45) from the sub-cells' interpolant: >= 0 where
              // the nodal values are.
              double phi = 0;
              for (const unsigned int i : support[q])
                phi += phi_old[i] * values.shape_value(i, q);
              const double kappa = time_step * diffusion * std::max(phi, 0.0);
              for (const unsigned int i : support[q])
                {
                  const double lumped_mass = values.shape_value(i, q) * values.JxW(q);
                  cell_matrix(i, i) += lumped_mass;
                  cell_rhs(i) += lumped_mass * phi_old[i];
                  for (const unsigned int j : support[q])
                    cell_matrix(i, j) += kappa *
                                         (values.shape_grad(i, q) * values.shape_grad(j, q)) *
                                         values.JxW(q);
                }
            }
          // Discrete upwinding (Kuzmin): remove positive off-diagonal
          // entries, keeping row and column sums: an M-matrix whatever the
          // cell's shape and κ.
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = i + 1; j < n_dofs; ++j)
              {
                const double d = std::max({0.0, cell_matrix(i, j), cell_matrix(j, i)});
                cell_matrix(i, j) -= d;
                cell_matrix(j, i) -= d;
                cell_matrix(i, i) += d;
                cell_matrix(j, j) += d;
              }
          cell->get_dof_indices(local_dofs);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, local_dofs, system_matrix, system_rhs);
        }
    system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    return solve();
  }


  template <int dim>
  void
  VolumeFraction<dim>::bound_hanging_nodes(TrilinosWrappers::MPI::Vector & distributed,
                                      const TrilinosWrappers::MPI::Vector &lower,
                                      const TrilinosWrappers::MPI::Vector &upper) const
  {
    // The range: the smallest lower and largest upper bound of the free nodes.
    double low  = std::numeric_limits<double>::max();
    double high = std::numeric_limits<double>::lowest();
    for (const auto i : dofs.locally_owned_dofs())
      if (!constraints.is_constrained(i))
        {
          low  = std::min(low, static_cast<double>(lower[i]));
          high = std::max(high, static_cast<double>(upper[i]));
        }
    low  = Utilities::MPI::min(low, mpi_communicator);
    high = Utilities::MPI::max(high, mpi_communicator);

    TrilinosWrappers::MPI::Vector ghosted(dofs.locally_owned_dofs(),
                                          locally_relevant_dofs,
                                          mpi_communicator);
    ghosted = distributed;
    // The owner of a master sees every hanging node that depends on it (they
    // lie on cells next to its own), so each rank shifts the masters it owns.
    std::map<types::global_dof_index, double> shifts;
    for (const auto &line : constraints.get_lines())
      {
        if (line.entries.empty() ||
            !std::all_of(line.entries.begin(), line.entries.end(), [&](const auto &entry) {
              return locally_relevant_dofs.is_element(entry.first);
            }))
          continue;
        double value = line.inhomogeneity;
        for (const auto &[dof, weight] : line.entries)
          value += weight * ghosted[dof];
        if (value >= low && value <= high)
          continue;
        const auto &[master, weight] =
          *std::max_element(line.entries.begin(),
                            line.entries.end(),
                            [](const auto &a, const auto &b) { return a.second < b.second; });
        if (weight <= 0 || !dofs.locally_owned_dofs().is_element(master))
          continue;
        const double needed = ((value < low ? low : high) - value) / weight;
        // One master may be asked to rise by one hanging node and to fall
        // by another (a front along the edge both ways): the larger need wins.
        auto [shift, inserted] = shifts.emplace(master, needed);
        if (!inserted && std::abs(needed) > std::abs(shift->second))
          shift->second = needed;
      }
    for (const auto &[master, shift] : shifts)
      distributed[master] = std::clamp(distributed[master] + shift, low, high);
    constraints.distribute(distributed);
  }


  template <int dim>
  double
  VolumeFraction<dim>::restore_mass(const double                    mass,
                               const TrilinosWrappers::MPI::Vector &lower,
                               const TrilinosWrappers::MPI::Vector &upper)
  {
    // ∫φ = Σ_i w_i φ_i with w_i = ∫ψ_i over all nodes; a change of the free
    // nodes changes it by W·δ, W = w condensed onto them.
    const IndexSet &              owned = dofs.locally_owned_dofs();
    TrilinosWrappers::MPI::Vector w(owned, mpi_communicator), weights(w);
    const QGauss<dim>               quadrature(fe.degree + 1);
    FEValues<dim>    fe_values(this->mapping(), fe, quadrature, update_values | update_JxW_values);
    Vector<double> cell_w(fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> local_dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_w = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < cell_w.size(); ++i)
              cell_w(i) += fe_values.shape_value(i, q) * fe_values.JxW(q);
          cell->get_dof_indices(local_dofs);
          w.add(local_dofs, cell_w);
          constraints.distribute_local_to_global(cell_w, local_dofs, weights);
        }
    w.compress(VectorOperation::add);
    weights.compress(VectorOperation::add);

    TrilinosWrappers::MPI::Vector distributed(owned, mpi_communicator);
    distributed = current_solution;
    bound_hanging_nodes(distributed, lower, upper);
    TrilinosWrappers::MPI::Vector room(owned, mpi_communicator);
    for (const auto i : owned)
      if (!constraints.is_constrained(i) && upper[i] > lower[i])
        room[i] = std::max(0.0,
                           (distributed[i] - lower[i]) * (upper[i] - distributed[i]) /
                             (upper[i] - lower[i]));
    // Not at the masters of hanging nodes: moving them would take the hanging
    // nodes out of range again (−1/8 weights; a sharp disc crossing the
    // refinement went to −1.2e-4 and 0.10115 of [0, 0.1] in one step).
    for (const auto &line : constraints.get_lines())
      if (line.entries.size() > 1)
        for (const auto &[master, weight] : line.entries)
          if (owned.is_element(master))
            room[master] = 0;
    room.compress(VectorOperation::insert);
    const double missing   = mass - (w * distributed);
    const double available = weights * room;
    const double lambda =
      available > 0 ? std::clamp(missing / available, -1.0, 1.0) : 0.0;
    distributed.add(lambda, room);
    constraints.distribute(distributed);
    current_solution = distributed;
    return missing - lambda * available;
  }


  template <int dim>
  double
  VolumeFraction<dim>::restore_mass(const double mass, const double low, const double high)
  {
    TrilinosWrappers::MPI::Vector lower(dofs.locally_owned_dofs(), mpi_communicator);
    TrilinosWrappers::MPI::Vector upper(lower);
    lower = low;
    upper = high;
    return restore_mass(mass, lower, upper);
  }


  template <int dim>
  double
  VolumeFraction<dim>::max_difference(const TrilinosWrappers::MPI::Vector &a,
                                      const TrilinosWrappers::MPI::Vector &b) const
  {
    double difference = 0;
    for (const auto i : dofs.locally_owned_dofs())
      difference = std::max(difference, std::abs(a[i] - b[i]));
    return Utilities::MPI::max(difference, mpi_communicator);
  }


  template <int dim>
  typename VolumeFraction<dim>::Exchange
  VolumeFraction<dim>::boundary_flux(const DoFHandler<dim> &                stokes_dofs,
                                const TrilinosWrappers::MPI::BlockVector &velocity_field) const
  {
    const QGauss<dim - 1> quadrature(fe.degree + 1);
    FEFaceValues<dim> phi_face(this->mapping(), fe, quadrature, update_values | update_JxW_values);
    FEFaceValues<dim> stokes_face(this->mapping(),
                                  stokes_dofs.get_fe(),
                                quadrature,
                                update_values | update_normal_vectors);
    const FEValuesExtractors::Vector velocities(0);
    std::vector<double>              phi(quadrature.size());
    std::vector<Tensor<1, dim>>        velocity(quadrature.size());
    // [net, out, in]: the periodic faces' fluxes cancel in the net flux;
    // out and in count the other faces only.
    double flux[3] = {};
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary())
        for (const unsigned int f : cell->face_indices())
          if (cell->at_boundary(f))
            {
              phi_face.reinit(cell, f);
              stokes_face.reinit(cell_of(stokes_dofs, cell), f);
              phi_face.get_function_values(current_solution, phi);
              stokes_face[velocities].get_function_values(velocity_field, velocity);
              const bool periodic =
                boundary_conditions.boundary(cell->face(f)->boundary_id()).type ==
                BoundaryConditions<dim>::Type::periodic;
              for (const unsigned int q : phi_face.quadrature_point_indices())
                {
                  const double normal_velocity = velocity[q] * stokes_face.normal_vector(q);
                  const double through = phi[q] * normal_velocity * phi_face.JxW(q);
                  flux[0] += through;
                  // By the flow's direction (φ between the nodes may be
                  // slightly negative).
                  if (!periodic)
                    flux[normal_velocity > 0 ? 1 : 2] += (normal_velocity > 0 ? through : -through);
                }
            }
    Utilities::MPI::sum(flux, mpi_communicator, flux);
    return {flux[0], flux[1], flux[2]};
  }


  template <int dim>
  void
  VolumeFraction<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    statistics.set("volume_fraction_integral", integral());
    statistics.set("volume_fraction_outflow", exchange.outflow);
    statistics.set("volume_fraction_inflow", exchange.inflow);
    const auto [phi_min, phi_max] = range();
    statistics.set("volume_fraction_min", phi_min);
    statistics.set("volume_fraction_max", phi_max);
    statistics.set("volume_fraction_mass_defect", mass_defect);
    scheme->add_statistics(statistics);
  }


  template <int dim>
  void
  VolumeFraction<dim>::save_state(CheckpointValues &values) const
  {
    values["volume_fraction_net"]     = exchange.net;
    values["volume_fraction_outflow"] = exchange.outflow;
    values["volume_fraction_inflow"]  = exchange.inflow;
  }


  template <int dim>
  void
  VolumeFraction<dim>::load_state(const CheckpointValues &values)
  {
    exchange.net     = checkpoint_value(values, "volume_fraction_net");
    exchange.outflow = checkpoint_value(values, "volume_fraction_outflow");
    exchange.inflow  = checkpoint_value(values, "volume_fraction_inflow");
    old_exchange     = exchange;
  }


  template <int dim>
  void
  VolumeFraction<dim>::interpolate(const Function<dim> &initial)
  {
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              mpi_communicator);
    VectorTools::interpolate(this->mapping(), dofs, initial, distributed);
    set(distributed);
  }


  template <int dim>
  void
  VolumeFraction<dim>::set(TrilinosWrappers::MPI::Vector &distributed)
  {
    constraints.distribute(distributed);
    if (scheme->bounded())
      bound_hanging_nodes(distributed, distributed, distributed);
    current_solution = distributed;
  }


  template <int dim>
  void
  VolumeFraction<dim>::add_output(DataOut<dim> &data_out)
  {
    data_out.add_data_vector(dofs, current_solution, name);
  }


  template <int dim>
  void
  VolumeFraction<dim>::prepare_for_refinement()
  {
    if (scheme->bounded())
      {
        const auto [phi_min, phi_max] = range();
        before_transfer = std::array<double, 3>{{phi_min, phi_max, integral()}};
      }
    FieldType::prepare_for_refinement();
  }


  template <int dim>
  void
  VolumeFraction<dim>::transferred(TrilinosWrappers::MPI::Vector &distributed)
  {
    if (!before_transfer)
      return;
    const auto [phi_min, phi_max, mass] = *before_transfer;
    before_transfer.reset();
    for (const auto i : dofs.locally_owned_dofs())
      distributed[i] = std::clamp(static_cast<double>(distributed[i]), phi_min, phi_max);
    constraints.distribute(distributed);
    current_solution = distributed;
    restore_mass(mass, phi_min, phi_max);
    distributed = current_solution;
  }


  template <int dim>
  double
  VolumeFraction<dim>::integral() const
  {
    return integral_of(current_solution);
  }


  template <int dim>
  double
  VolumeFraction<dim>::integral_of(const TrilinosWrappers::MPI::Vector &values_on_dofs,
                                   const TrilinosWrappers::MPI::Vector *weight) const
  {
    const QGauss<dim>     quadrature(fe.degree + 1);
    FEValues<dim> fe_values(this->mapping(), fe, quadrature, update_values | update_JxW_values);
    std::vector<double> values(quadrature.size()), weights(quadrature.size(), 1.0);
    double              sum = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(values_on_dofs, values);
          if (weight)
            fe_values.get_function_values(*weight, weights);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            sum += values[q] * weights[q] * fe_values.JxW(q);
        }
    return Utilities::MPI::sum(sum, mpi_communicator);
  }


  template <int dim>
  void
  VolumeFraction<dim>::set_expansion(const TrilinosWrappers::MPI::Vector *rate)
  {
    expansion = rate ? integral_of(current_solution, rate) : 0.0;
  }


  template <int dim>
  double
  VolumeFraction<dim>::expansion_integral() const
  {
    return expansion;
  }


  template <int dim>
  double
  VolumeFraction<dim>::last_mass_defect() const
  {
    return mass_defect;
  }


  template <int dim>
  std::pair<double, double>
  VolumeFraction<dim>::range(const bool free_nodes) const
  {
    double low  = std::numeric_limits<double>::max();
    double high = std::numeric_limits<double>::lowest();
    for (const auto i : dofs.locally_owned_dofs())
      if (!free_nodes || !constraints.is_constrained(i))
      {
        low  = std::min(low, current_solution[i]);
        high = std::max(high, current_solution[i]);
      }
    return {Utilities::MPI::min(low, mpi_communicator),
            Utilities::MPI::max(high, mpi_communicator)};
  }


  VISCOFILM_INSTANTIATE(VolumeFraction)
} // namespace viscofilm
