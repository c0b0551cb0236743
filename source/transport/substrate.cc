#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <deal.II/numerics/vector_tools.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/core/input.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/transport/substrate.h>
#include <viscofilm/transport/volume_fraction.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace viscofilm
{
  template <int dim>
  void
  Substrate<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Substrate");
    prm.declare_entry("Enable",
                      "false",
                      Patterns::Bool(),
                      "A dissolved substrate S carried by the flow, diffusing "
                      "and consumed by the biofilm (Monod kinetics; "
                      "doc/model.md, \"Substrate\"). The defaults are the IWA "
                      "benchmark's standard case (Wanner et al. 2006) in SI: "
                      "kg/m³, m²/s, 1/s.");
    prm.declare_entry("Diffusivity",
                      "1.1574e-9",
                      Patterns::Double(0),
                      "D_w, S's diffusivity in water (1e-4 m²/d).");
    prm.declare_entry("Biofilm diffusivity ratio",
                      "0.8",
                      Patterns::Double(0),
                      "D_b/D_w; D(φ) = D_w (1 − φ) + D_b φ.");
    prm.declare_entry("Maximum growth rate",
                      "6.9444e-5",
                      Patterns::Double(0),
                      "μmax, the biomass' growth rate at S ≫ K_S (6 per day).");
    prm.declare_entry("Half saturation",
                      "0.004",
                      Patterns::Double(0),
                      "K_S, the Monod half-saturation concentration "
                      "(4 g/m³), > 0.");
    prm.declare_entry("Yield", "0.63", Patterns::Double(0), "Y, biomass made per substrate consumed, > 0.");
    prm.declare_entry("Biomass density",
                      "10",
                      Patterns::Double(0),
                      "ρX, the biomass per volume of biofilm at φ = 1 "
                      "(1e4 g/m³); S is consumed at (μmax/Y) ρX φ S/(K_S + S).");
    prm.declare_entry("Initial value", "0", Patterns::Double(0), "S at t = 0.");
    prm.declare_entry("Fixed values",
                      "",
                      Patterns::Anything(),
                      "S on boundaries, as \"Name: value, Name: value\" (names "
                      "of Boundary conditions, not periodic ones), e.g. the "
                      "inlet's concentration or a bulk value above a biofilm. "
                      "Through every other boundary no diffusive flux: where "
                      "the flow leaves, S leaves with it; where it enters, "
                      "it brings none (list such a boundary here to give its "
                      "inflow a concentration).");
    prm.declare_entry("Quasi-steady",
                      "false",
                      Patterns::Bool(),
                      "true: each step solves for S in balance with the "
                      "step's flow and biomass (diffusion across a biofilm "
                      "takes minutes, growth hours); false: implicit Euler "
                      "in time.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Substrate<dim>::Parameters::parse_parameters(ParameterHandler &             prm,
                                               const BoundaryConditions<dim> &boundary_conditions)
  {
    prm.enter_subsection("Substrate");
    enabled                   = prm.get_bool("Enable");
    diffusivity               = prm.get_double("Diffusivity");
    biofilm_diffusivity_ratio = prm.get_double("Biofilm diffusivity ratio");
    maximum_growth_rate       = prm.get_double("Maximum growth rate");
    half_saturation           = prm.get_double("Half saturation");
    yield                     = prm.get_double("Yield");
    biomass_density           = prm.get_double("Biomass density");
    initial_value             = prm.get_double("Initial value");
    quasi_steady              = prm.get_bool("Quasi-steady");
    const std::string values  = prm.get("Fixed values");
    prm.leave_subsection();
    check_input(half_saturation > 0,
                "Substrate/Half saturation must be > 0, got " + to_text(half_saturation));
    check_input(yield > 0, "Substrate/Yield must be > 0, got " + to_text(yield));
    fixed_values.clear();
    for (const std::string &entry : Utilities::split_string_list(values))
      {
        const std::vector<std::string> parts = Utilities::split_string_list(entry, ':');
        check_input(parts.size() == 2,
                    "Substrate/Fixed values: \"" + entry +
                      "\" is not of the form \"Name: value\"");
        const types::boundary_id id = boundary_conditions.id(parts[0], "Substrate/Fixed values");
        check_input(fixed_values.count(id) == 0,
                    "Substrate/Fixed values: \"" + parts[0] + "\" is listed twice");
        check_input(boundary_conditions.boundary(id).type !=
                      BoundaryConditions<dim>::Type::periodic,
                    "Substrate/Fixed values: \"" + parts[0] +
                      "\" is periodic; name boundaries that are not");
        double value = 0;
        try
          {
            value = Utilities::string_to_double(parts[1]);
          }
        catch (...)
          {
            check_input(false,
                        "Substrate/Fixed values: the value of \"" + parts[0] + "\", \"" +
                          parts[1] + "\", is not a number");
          }
        check_input(value >= 0,
                    "Substrate/Fixed values: the value of \"" + parts[0] +
                      "\" must be >= 0, got " + parts[1]);
        fixed_values[id] = value;
      }
  }


  template <int dim>
  double
  Substrate<dim>::Parameters::diffusivity_at(const double phi) const
  {
    const double clipped = std::clamp(phi, 0.0, 1.0);
    return diffusivity * (1 - clipped + biofilm_diffusivity_ratio * clipped);
  }


  template <int dim>
  double
  Substrate<dim>::Parameters::uptake_rate() const
  {
    return maximum_growth_rate / yield * biomass_density;
  }


  template <int dim>
  Substrate<dim>::Substrate(const parallel::distributed::Triangulation<dim> &triangulation,
                            const Mapping<dim> &                             mapping,
                            const Parameters &                               parameters,
                            const BoundaryConditions<dim> &boundary_conditions,
                            const VolumeFraction<dim> &    volume_fraction)
    : FieldType(triangulation, mapping)
    , parameters(parameters)
    , boundary_conditions(boundary_conditions)
    , volume_fraction(volume_fraction)
    , mpi_communicator(triangulation.get_communicator())
    , fe(1)
  {}


  template <int dim>
  void
  Substrate<dim>::setup_dofs()
  {
    dofs.distribute_dofs(fe);
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    hanging_node_constraints.clear();
    hanging_node_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, hanging_node_constraints);
    boundary_conditions.constrain_periodic(dofs, hanging_node_constraints);
    hanging_node_constraints.close();
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    constraints.merge(hanging_node_constraints);
    for (const auto &[id, value] : parameters.fixed_values)
      VectorTools::interpolate_boundary_values(
        this->mapping(), dofs, id, Functions::ConstantFunction<dim>(value), constraints);
    constraints.close();
    this->setup_vectors(dofs.locally_owned_dofs(), locally_relevant_dofs);
    system_rhs.reinit(dofs.locally_owned_dofs(), mpi_communicator);

    TrilinosWrappers::SparsityPattern sparsity(dofs.locally_owned_dofs(),
                                               dofs.locally_owned_dofs(),
                                               locally_relevant_dofs,
                                               mpi_communicator);
    DoFTools::make_sparsity_pattern(
      dofs, sparsity, constraints, false, Utilities::MPI::this_mpi_process(mpi_communicator));
    sparsity.compress();
    system_matrix.reinit(sparsity);
    compute_lumped_mass();
  }


  template <int dim>
  void
  Substrate<dim>::set_initial_values()
  {
    // The mesh changes before t = 0 carried no substrate.
    totals     = Totals();
    old_totals = totals;
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(), mpi_communicator);
    distributed = parameters.initial_value;
    constraints.distribute(distributed);
    current_solution = distributed;
    old_solution     = distributed;
  }


  template <int dim>
  void
  Substrate<dim>::assemble(const StokesFlow<dim> &              stokes,
                           const double                         time_step,
                           const TrilinosWrappers::MPI::Vector &iterate,
                           Rates *                              rates)
  {
    // Discrete upwinding of diffusion and convection, and the lumped mass
    // and Monod term on the diagonal: an M-matrix, so S >= 0; the shape
    // functions sum to one, so the convection's columns sum to the outflow:
    // S is conserved; its rows sum to ∫ψ_i ∇·u = 0 (exact with the Stokes
    // assembly's quadrature): S stays within its data.
    const QGauss<dim>        quadrature(3);
    const QGauss<dim - 1>    face_quadrature(3);
    FEValues<dim>            values(this->mapping(),
                         fe,
                         quadrature,
                         update_values | update_gradients | update_JxW_values);
    FEValues<dim>     stokes_values(this->mapping(),
                                stokes.dof_handler().get_fe(),
                                quadrature,
                                update_values);
    FEValues<dim>     phi_values(this->mapping(),
                             volume_fraction.dof_handler().get_fe(),
                             quadrature,
                             update_values);
    FEFaceValues<dim> face_values(this->mapping(),
                                  fe,
                                  face_quadrature,
                                  update_values | update_normal_vectors | update_JxW_values);
    FEFaceValues<dim> stokes_face(this->mapping(),
                                  stokes.dof_handler().get_fe(),
                                  face_quadrature,
                                  update_values);
    const FEValuesExtractors::Vector     velocities(0);
    const unsigned int                   n_dofs = fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs), outflow(n_dofs, n_dofs);
    Vector<double>                       cell_rhs(n_dofs), residual(n_dofs);
    std::vector<double> phi_q(quadrature.size()), s(n_dofs);
    // The biomass each node consumes with, b_i = ∫ψ_i φ, clipped to [0,
    // m_i] (Σ_i b_i = ∫φ where no clip acts, so the consumption is that of
    // the biomass there is on any mesh; φ clipped at the quadrature points
    // instead counted the Q2 interpolant's undershoots at a sharp front,
    // 0.25 % of the thesis' bulb), condensed like the lumped mass: the mass and the Monod
    // term go on the diagonal after condensation, which keeps it an
    // M-matrix (a hanging node's mass condensed onto its masters would
    // couple them positively).
    TrilinosWrappers::MPI::Vector biomass(dofs.locally_owned_dofs(), mpi_communicator);
    Vector<double>                cell_biomass(n_dofs);
    std::vector<Tensor<1, dim>>          velocity(quadrature.size());
    std::vector<Tensor<1, dim>>          face_velocity(face_quadrature.size());
    std::vector<types::global_dof_index> local_dofs(n_dofs);
    const double mass_factor = parameters.quasi_steady ? 0.0 : 1.0 / time_step;

    TrilinosWrappers::MPI::Vector full_residual;
    if (rates)
      {
        *rates = Rates();
        full_residual.reinit(dofs.locally_owned_dofs(), mpi_communicator);
      }
    else
      {
        system_matrix = 0;
        system_rhs    = 0;
      }
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          values.reinit(cell);
          const auto stokes_cell = cell_of(stokes.dof_handler(), cell);
          stokes_values.reinit(stokes_cell);
          stokes_values[velocities].get_function_values(stokes.solution(), velocity);
          phi_values.reinit(cell_of(volume_fraction.dof_handler(), cell));
          phi_values.get_function_values(volume_fraction.solution(), phi_q);
          cell->get_dof_indices(local_dofs);
          cell_biomass = 0;
          for (const unsigned int q : values.quadrature_point_indices())
            for (unsigned int i = 0; i < n_dofs; ++i)
              cell_biomass(i) += values.shape_value(i, q) * phi_q[q] * values.JxW(q);
          hanging_node_constraints.distribute_local_to_global(cell_biomass, local_dofs, biomass);

          cell_matrix = 0;
          outflow     = 0;
          for (const unsigned int q : values.quadrature_point_indices())
            {
              const double diffusivity = parameters.diffusivity_at(phi_q[q]);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const double advected = velocity[q] * values.shape_grad(i, q);
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) +=
                      (diffusivity * (values.shape_grad(i, q) * values.shape_grad(j, q)) -
                       advected * values.shape_value(j, q)) *
                      values.JxW(q);
                }
            }
          // ∫ ψ_i ψ_j u·n where the flow leaves through a boundary without a
          // fixed value (walls: u·n = 0; periodic faces: none).
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) &&
                parameters.fixed_values.count(cell->face(f)->boundary_id()) == 0 &&
                boundary_conditions.boundary(cell->face(f)->boundary_id()).type !=
                  BoundaryConditions<dim>::Type::periodic)
              {
                face_values.reinit(cell, f);
                stokes_face.reinit(stokes_cell, f);
                stokes_face[velocities].get_function_values(stokes.solution(), face_velocity);
                for (const unsigned int q : face_values.quadrature_point_indices())
                  {
                    const double un = face_velocity[q] * face_values.normal_vector(q);
                    if (un > 0)
                      for (unsigned int i = 0; i < n_dofs; ++i)
                        for (unsigned int j = 0; j < n_dofs; ++j)
                          outflow(i, j) += face_values.shape_value(i, q) *
                                           face_values.shape_value(j, q) * un *
                                           face_values.JxW(q);
                  }
              }
          cell_matrix.add(1.0, outflow);
          // Discrete upwinding (Kuzmin): remove positive off-diagonal
          // entries, keeping row and column sums.
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = i + 1; j < n_dofs; ++j)
              {
                const double d = std::max({0.0, cell_matrix(i, j), cell_matrix(j, i)});
                cell_matrix(i, j) -= d;
                cell_matrix(j, i) -= d;
                cell_matrix(i, i) += d;
                cell_matrix(j, j) += d;
              }
          if (!rates)
            {
              cell_rhs = 0;
              constraints.distribute_local_to_global(
                cell_matrix, cell_rhs, local_dofs, system_matrix, system_rhs);
              continue;
            }
          // The balance: what enters through the fixed values is their rows'
          // residual; what leaves, Σ_ij outflow_ij S_j.
          cell->get_dof_values(current_solution, s.begin(), s.end());
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              residual(i) = 0;
              for (unsigned int j = 0; j < n_dofs; ++j)
                {
                  residual(i) += cell_matrix(i, j) * s[j];
                  rates->outflow += outflow(i, j) * s[j];
                }
            }
          hanging_node_constraints.distribute_local_to_global(residual, local_dofs, full_residual);
        }
    biomass.compress(VectorOperation::add);
    // Lumped mass and Monod consumption r_i(S) = (μmax/Y) ρX b_i S/(K_S + S),
    // by Newton about the iterate S^l (clipped at 0): r(S) ≈ r(S^l) +
    // r'(S^l)(S − S^l), r' >= 0 on the diagonal. Picard's S/(K_S + S^l) oscillates
    // where K_S ≪ S (zero order).
    for (const auto i : dofs.locally_owned_dofs())
      if (!hanging_node_constraints.is_constrained(i))
        {
          const double s_l   = std::max(static_cast<double>(iterate[i]), 0.0);
          const double k_s   = parameters.half_saturation;
          const double rate =
            parameters.uptake_rate() * std::clamp(static_cast<double>(biomass[i]), 0.0, static_cast<double>(lumped_mass[i]));
          const double r     = rate * s_l / (k_s + s_l);
          const double slope = rate * k_s / ((k_s + s_l) * (k_s + s_l));
          if (!rates)
            {
              if (!constraints.is_constrained(i))
                {
                  system_matrix.add(i, i, lumped_mass[i] * mass_factor + slope);
                  system_rhs(i) += lumped_mass[i] * mass_factor * old_solution[i] + slope * s_l - r;
                }
              continue;
            }
          const double consumed = r + slope * (current_solution[i] - s_l);
          rates->consumed += consumed;
          full_residual(i) +=
            lumped_mass[i] * mass_factor * (current_solution[i] - old_solution[i]) + consumed;
        }
    if (!rates)
      {
        system_matrix.compress(VectorOperation::add);
        system_rhs.compress(VectorOperation::add);
        return;
      }
    full_residual.compress(VectorOperation::add);
    for (const auto i : dofs.locally_owned_dofs())
      if (constraints.is_constrained(i) && !hanging_node_constraints.is_constrained(i))
        rates->inflow += full_residual[i];
    double sums[3] = {rates->inflow, rates->outflow, rates->consumed};
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    *rates = {sums[0], sums[1], sums[2]};
  }


  template <int dim>
  unsigned int
  Substrate<dim>::advance(const StokesFlow<dim> &stokes, const double time_step)
  {
    const unsigned int            max_iterations = 50;
    TrilinosWrappers::MPI::Vector iterate        = current_solution;
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(), mpi_communicator);
    TrilinosWrappers::PreconditionAMG preconditioner;
    for (unsigned int l = 1;; ++l)
      {
        assemble(stokes, time_step, iterate, nullptr);
        distributed = current_solution;
        const double norm = system_rhs.l2_norm();
        if (norm > 0)
          {
            // Diffusion dominates inside a biofilm: AMG, not ILU, keeps the
            // iterations independent of h. The balance is as good as this
            // tolerance.
            SolverControl control(1000, 1e-12 * norm);
            SolverGMRES<TrilinosWrappers::MPI::Vector> solver(
              control, SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(50));
            // Newton changes only the diagonal: the first iteration's AMG
            // serves the step.
            if (l == 1)
              preconditioner.initialize(system_matrix);
            try
              {
                solver.solve(system_matrix, distributed, system_rhs, preconditioner);
              }
            catch (const SolverControl::NoConvergence &e)
              {
                throw ExcMessage("the substrate solver (GMRES) did not converge in " +
                                 std::to_string(e.last_step) + " iterations: residual " +
                                 to_text(e.last_residual));
              }
          }
        else
          distributed = 0;
        constraints.distribute(distributed);
        AssertThrow(std::isfinite(distributed.l2_norm()),
                    ExcMessage("the substrate is not finite (NaN or inf)"));
        // Newton has converged when S moves by less than 1e-10 of its
        // largest value.
        TrilinosWrappers::MPI::Vector change(distributed);
        TrilinosWrappers::MPI::Vector previous(dofs.locally_owned_dofs(), mpi_communicator);
        previous = iterate;
        change -= previous;
        const double scale = std::max(distributed.linfty_norm(), 1e-300);
        current_solution   = distributed;
        if (change.linfty_norm() <= 1e-10 * scale)
          {
            last_iterations = l;
            break;
          }
        AssertThrow(l < max_iterations,
                    ExcMessage("the substrate's Newton iteration (Monod term) did not converge in " +
                               std::to_string(max_iterations) + " iterations (change " +
                               to_text(change.linfty_norm() / scale) + " of max S)"));
        iterate = current_solution;
      }
    assemble(stokes, time_step, iterate, &last_rates);
    totals.inflow += time_step * last_rates.inflow;
    totals.outflow += time_step * last_rates.outflow;
    totals.consumed += time_step * last_rates.consumed;
    return last_iterations;
  }


  template <int dim>
  void
  Substrate<dim>::restore_old()
  {
    FieldType::restore_old();
    totals = old_totals;
  }


  template <int dim>
  void
  Substrate<dim>::advance_time()
  {
    FieldType::advance_time();
    old_totals = totals;
  }


  template <int dim>
  const typename Substrate<dim>::Parameters &
  Substrate<dim>::kinetics() const
  {
    return parameters;
  }


  template <int dim>
  double
  Substrate<dim>::consumption_rate() const
  {
    return last_rates.consumed;
  }


  template <int dim>
  void
  Substrate<dim>::compute_lumped_mass()
  {
    const QGauss<dim>             quadrature(2);
    FEValues<dim>                 values(this->mapping(),
                         fe,
                         quadrature,
                         update_values | update_JxW_values);
    lumped_mass.reinit(dofs.locally_owned_dofs(), mpi_communicator);
    Vector<double>                cell_weights(fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> local_dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          values.reinit(cell);
          cell_weights = 0;
          for (const unsigned int q : values.quadrature_point_indices())
            for (unsigned int i = 0; i < cell_weights.size(); ++i)
              cell_weights(i) += values.shape_value(i, q) * values.JxW(q);
          cell->get_dof_indices(local_dofs);
          hanging_node_constraints.distribute_local_to_global(cell_weights, local_dofs, lumped_mass);
        }
    lumped_mass.compress(VectorOperation::add);
  }


  template <int dim>
  double
  Substrate<dim>::amount() const
  {
    TrilinosWrappers::MPI::Vector owned(dofs.locally_owned_dofs(), mpi_communicator);
    owned = current_solution;
    return lumped_mass * owned;
  }


  template <int dim>
  void
  Substrate<dim>::prepare_for_refinement()
  {
    amount_before_transfer = amount();
    FieldType::prepare_for_refinement();
  }


  template <int dim>
  void
  Substrate<dim>::transferred(TrilinosWrappers::MPI::Vector &distributed)
  {
    if (!amount_before_transfer)
      return;
    totals.remeshed += lumped_mass * distributed - *amount_before_transfer;
    old_totals = totals;
    amount_before_transfer.reset();
  }


  template <int dim>
  void
  Substrate<dim>::add_output(DataOut<dim> &data_out)
  {
    data_out.add_data_vector(dofs, current_solution, "substrate");
  }


  template <int dim>
  void
  Substrate<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    statistics.set("substrate_amount", amount());
    statistics.set("substrate_inflow", totals.inflow);
    statistics.set("substrate_outflow", totals.outflow);
    statistics.set("substrate_consumed", totals.consumed);
    statistics.set("substrate_remeshed", totals.remeshed);
    statistics.set("substrate_inflow_rate", last_rates.inflow);
    double low = std::numeric_limits<double>::max(), high = std::numeric_limits<double>::lowest();
    for (const auto i : dofs.locally_owned_dofs())
      {
        low  = std::min(low, current_solution[i]);
        high = std::max(high, current_solution[i]);
      }
    statistics.set("substrate_min", Utilities::MPI::min(low, mpi_communicator));
    statistics.set("substrate_max", Utilities::MPI::max(high, mpi_communicator));
    statistics.set("substrate_iterations", last_iterations);
  }


  template <int dim>
  void
  Substrate<dim>::save_state(CheckpointValues &values) const
  {
    values["substrate_inflow"]   = totals.inflow;
    values["substrate_outflow"]  = totals.outflow;
    values["substrate_consumed"] = totals.consumed;
    values["substrate_remeshed"] = totals.remeshed;
  }


  template <int dim>
  void
  Substrate<dim>::load_state(const CheckpointValues &values)
  {
    totals.inflow   = checkpoint_value(values, "substrate_inflow");
    totals.outflow  = checkpoint_value(values, "substrate_outflow");
    totals.consumed = checkpoint_value(values, "substrate_consumed");
    totals.remeshed = checkpoint_value(values, "substrate_remeshed");
    old_totals      = totals;
  }


  VISCOFILM_INSTANTIATE(Substrate)
} // namespace viscofilm
