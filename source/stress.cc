#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/matrix_free/fe_point_evaluation.h>

#include <viscofilm/input.h>
#include <viscofilm/stokes.h>
#include <viscofilm/stress.h>
#include <viscofilm/volume_fraction.h>

#include <cmath>
#include <limits>

namespace viscofilm
{
  namespace
  {
    /// Smallest eigenvalue of the symmetric 2x2 matrix (xx, xy, yy).
    double
    smallest_eigenvalue(const double xx, const double xy, const double yy)
    {
      const double mean = 0.5 * (xx + yy);
      const double half = 0.5 * (xx - yy);
      return mean - std::sqrt(half * half + xy * xy);
    }

    /// τ = c − shift I as output fields.
    class StressPostprocessor : public DataPostprocessor<2>
    {
    public:
      explicit StressPostprocessor(const double shift)
        : shift(shift)
      {}

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<2> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        for (unsigned int q = 0; q < inputs.solution_values.size(); ++q)
          {
            computed[q][0] = inputs.solution_values[q][0] - shift;
            computed[q][1] = inputs.solution_values[q][1];
            computed[q][2] = inputs.solution_values[q][2] - shift;
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        return {"tau_xx", "tau_xy", "tau_yy"};
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values;
      }

    private:
      const double shift;
    };
  } // namespace


  void
  ElasticStress::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stress");
    prm.declare_entry("Element",
                      "continuous",
                      Patterns::Selection("continuous|discontinuous"),
                      "continuous: FE_Q(2) for c_xx, c_xy, c_yy (the thesis; a "
                      "node uses the mean of ∇u over its cells). discontinuous: "
                      "FE_DGQ(2) (each node uses its own cell's ∇u).");
    prm.declare_entry("Positivity safe feet",
                      "true",
                      Patterns::Bool(),
                      "Where the Q2 interpolant of c at a departure foot is not "
                      "positive definite, use the bilinear interpolant on the "
                      "Q1 sub-cell of the Q2 nodes instead (a convex "
                      "combination of nodal values, so positive definite).");
    prm.declare_entry("Positivity floor",
                      "1e-6",
                      Patterns::Double(0),
                      "c must stay positive definite (a > 0), but the Q2 "
                      "interpolation at hanging nodes and onto refined cells "
                      "has weights of -1/8 and can break it. A node whose "
                      "smallest eigenvalue there falls below this times "
                      "ηp/(a Wi) (c of the relaxed state) is raised to it, c "
                      "+= (floor − λ_min) I (counted in statistics.csv as "
                      "conformation_repairs). The update itself never goes below "
                      "k/(Wi + k) times ηp/(a Wi). >= 0 (0: only negative "
                      "eigenvalues are raised, to 0).");
    prm.declare_entry("Deformation gradient",
                      "implicit Euler",
                      Patterns::Selection("implicit Euler|Cayley"),
                      "How the step's deformation E in c = E c(foot) Eᵀ is "
                      "approximated. implicit Euler: E = (I − kΦ)^{-1}, the "
                      "thesis (eq. 3.42), first order; it shrinks a rotating "
                      "stress by 1/(1 + (ωk)²) per step. Cayley: E = (I − kΦ/2)^{-1}"
                      "(I + kΦ/2), second order and exact in rotation. Both keep "
                      "c symmetric and positive definite.");
    prm.leave_subsection();
  }


  void
  ElasticStress::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stress");
    discontinuous        = (prm.get("Element") == "discontinuous");
    positivity_safe_feet = prm.get_bool("Positivity safe feet");
    cayley               = (prm.get("Deformation gradient") == "Cayley");
    positivity_floor     = prm.get_double("Positivity floor");
    prm.leave_subsection();
  }


  ElasticStress::ElasticStress(
    const parallel::distributed::Triangulation<2> &triangulation,
    const Parameters &                             parameters,
    const Model &                                  model,
    const BoundaryConditions &                     boundary_conditions)
    : triangulation(triangulation)
    , parameters(parameters)
    , model(model)
    , boundary_conditions(boundary_conditions)
    , fe(parameters.discontinuous ?
           static_cast<const FiniteElement<2> &>(FE_DGQ<2>(2)) :
           static_cast<const FiniteElement<2> &>(FE_Q<2>(2)),
         3)
    , dofs(triangulation)
  {}


  double
  ElasticStress::shift() const
  {
    return model.viscosity_ratio / (model.slip_parameter * model.weissenberg);
  }


  void
  ElasticStress::setup_dofs(const Quadrature<2> &quadrature)
  {
    const MPI_Comm comm = triangulation.get_communicator();
    dofs.distribute_dofs(fe);
    const IndexSet &owned = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    current.reinit(owned, locally_relevant_dofs, comm);
    old.reinit(owned, locally_relevant_dofs, comm);
    hanging_node_constraints.clear();
    hanging_node_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, hanging_node_constraints);
    boundary_conditions.constrain_periodic(dofs, hanging_node_constraints);
    hanging_node_constraints.close();
    stokes_quadrature = quadrature;

    const std::vector<Point<2>> &unit_support =
      fe.base_element(0).get_unit_support_points();
    for (unsigned int k = 0; k < unit_support.size(); ++k)
      lexicographic_node[std::lround(2 * unit_support[k][0])]
                        [std::lround(2 * unit_support[k][1])] = k;

    nodes.clear();
    node_of_owned_dof.assign(owned.n_elements(), numbers::invalid_unsigned_int);
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(cell_dofs);
          for (unsigned int k = 0; k < unit_support.size(); ++k)
            {
              const auto dof = cell_dofs[fe.component_to_system_index(0, k)];
              if (!owned.is_element(dof) ||
                  node_of_owned_dof[owned.index_within_set(dof)] !=
                    numbers::invalid_unsigned_int)
                continue;
              node_of_owned_dof[owned.index_within_set(dof)] = nodes.size();
              Node node;
              node.position = StaticMappingQ1<2>::mapping.transform_unit_to_real_cell(
                cell, unit_support[k]);
              node.cell = cell;
              for (unsigned int c = 0; c < 3; ++c)
                node.dofs[c] = cell_dofs[fe.component_to_system_index(c, k)];
              nodes.push_back(node);
            }
        }

    quadrature_values = std::make_unique<FEValues<2>>(fe, quadrature, update_values);
    tau_postprocessor = std::make_unique<StressPostprocessor>(shift());
  }


  void
  ElasticStress::set_initial_conditions(const Function<2> &initial_stress)
  {
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              triangulation.get_communicator());
    // Without elastic stress τ ≡ 0 (c = shift I) whatever the input says:
    // nothing updates c then, so a non-zero τ0 would act on the flow for ever.
    Vector<double> tau(3);
    for (const Node &node : nodes)
      {
        // A discontinuous c takes its own cell's limit of τ0 on the cell's
        // boundary, so that a τ0 jumping across a face is kept.
        const Point<2> inside =
          parameters.discontinuous ?
            node.position + 1e-10 * (node.cell->center() - node.position) :
            node.position;
        if (model.viscoelastic)
          initial_stress.vector_value(inside, tau);
        const SymmetricTensor<2, dim> c = conformation(tau);
        distributed[node.dofs[0]]       = c[0][0];
        distributed[node.dofs[1]]       = c[0][1];
        distributed[node.dofs[2]]       = c[1][1];
      }
    distributed.compress(VectorOperation::insert);
    hanging_node_constraints.distribute(distributed);
    current          = distributed;
    old              = distributed;
    transfer_repairs = 0; // of the unset c carried by the initial refinement
  }


  SymmetricTensor<2, dim>
  ElasticStress::conformation(const Vector<double> &tau) const
  {
    AssertDimension(tau.size(), n_symmetric_components);
    return SymmetricTensor<2, dim>({tau[0] + shift(), tau[2] + shift(), tau[1]});
  }


  void
  ElasticStress::trace_back(DepartureFeet &     feet,
                            const StokesSolver &stokes,
                            const double        time,
                            const double        time_step)
  {
    std::vector<Point<2>>                               points(nodes.size());
    std::vector<Triangulation<2>::active_cell_iterator> cells(nodes.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        points[i] = nodes[i].position;
        cells[i]  = nodes[i].cell;
      }
    feet.compute(points, cells, stokes.dof_handler(), stokes.solution(), time_step);

    // c^n at the feet, on whichever rank owns them.
    const MPI_Comm     comm      = triangulation.get_communicator();
    const double       this_rank = Utilities::MPI::this_mpi_process(comm);
    const bool         guard     = parameters.positivity_safe_feet && shift() > 0;
    unsigned int       fixes     = 0;
    FEPointEvaluation<3, 2> conformation(StaticMappingQ1<2>::mapping, fe, update_values, 0);
    std::vector<double>     cell_values(fe.n_dofs_per_cell());

    const CellEvaluation<4> evaluate =
      [&](const Triangulation<2>::active_cell_iterator &cell,
          const ArrayView<const Point<2>> &             unit_points,
          const ArrayView<std::array<double, 4>> &      values) {
        const DoFHandler<2>::active_cell_iterator dof_cell(&triangulation,
                                                           cell->level(),
                                                           cell->index(),
                                                           &dofs);
        dof_cell->get_dof_values(old, cell_values.begin(), cell_values.end());
        conformation.reinit(cell, unit_points);
        conformation.evaluate(cell_values, EvaluationFlags::values);
        for (unsigned int q = 0; q < unit_points.size(); ++q)
          {
            Tensor<1, 3> c = conformation.get_value(q);
            if (guard && smallest_eigenvalue(c[0], c[1], c[2]) <= 0)
              {
                // Bilinear interpolation on the Q1 sub-cell of the Q2 nodes.
                const Point<2> &p  = unit_points[q];
                const unsigned  ix = p[0] < 0.5 ? 0 : 1, iy = p[1] < 0.5 ? 0 : 1;
                const double    xi  = std::clamp(2 * p[0] - ix, 0.0, 1.0);
                const double    eta = std::clamp(2 * p[1] - iy, 0.0, 1.0);
                const double weight[2][2] = {{(1 - xi) * (1 - eta), (1 - xi) * eta},
                                             {xi * (1 - eta), xi * eta}};
                c = 0;
                for (unsigned int a = 0; a < 2; ++a)
                  for (unsigned int b = 0; b < 2; ++b)
                    for (unsigned int component = 0; component < 3; ++component)
                      c[component] +=
                        weight[a][b] *
                        cell_values[fe.component_to_system_index(
                          component, lexicographic_node[ix + a][iy + b])];
                ++fixes;
              }
            values[q] = {{c[0], c[1], c[2], this_rank}};
          }
      };

    const auto   values = feet.at_feet().evaluate<4>(evaluate);
    const std::vector<types::boundary_id> &inflow   = feet.inflow_boundaries();
    const std::vector<Point<dim>> &        at_feet  = feet.at_feet().located_points();
    unsigned int                           remote   = 0;
    Vector<double>                         tau(n_symmetric_components);
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const auto &v = values[i];
        if (inflow[i] != numbers::invalid_boundary_id)
          {
            // The characteristic enters through boundary inflow[i]: its
            // Stress at the cut, at t_n like c^n at the other feet.
            FunctionParser<dim> &stress = boundary_conditions.boundary(inflow[i]).stress.function();
            stress.set_time(time);
            stress.vector_value(at_feet[i], tau);
            nodes[i].foot_conformation = ElasticStress::conformation(tau);
          }
        else
          nodes[i].foot_conformation =
            SymmetricTensor<2, 2>({v[0], v[2], v[1]}); // (xx, yy, xy)
        if (v[3] != this_rank)
          ++remote;
      }
    remote_feet      = Utilities::MPI::sum(remote, comm);
    positivity_fixes = Utilities::MPI::sum(fixes, comm);
  }


  void
  ElasticStress::nodal_fields(const StokesSolver &        stokes,
                              const VolumeFraction &      volume_fraction,
                              std::vector<Tensor<2, 2>> & velocity_gradient,
                              std::vector<double> &       phi) const
  {
    const Quadrature<2> at_nodes(fe.base_element(0).get_unit_support_points());
    FEValues<2> stokes_values(stokes.dof_handler().get_fe(), at_nodes, update_gradients);
    FEValues<2> phi_values(volume_fraction.dof_handler().get_fe(), at_nodes, update_values);
    const FEValuesExtractors::Vector velocities(0);
    std::vector<Tensor<2, 2>>        gradients(at_nodes.size());
    std::vector<double>              phis(at_nodes.size());
    std::vector<unsigned int>        n_cells(nodes.size(), 0);
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    const IndexSet &                 owned = dofs.locally_owned_dofs();

    velocity_gradient.assign(nodes.size(), Tensor<2, 2>());
    phi.assign(nodes.size(), 0.0);
    // Ghost cells too: a continuous node on a rank boundary averages over all
    // of its cells.
    for (const auto &cell : dofs.active_cell_iterators())
      if (!cell->is_artificial())
        {
          stokes_values.reinit(DoFHandler<2>::active_cell_iterator(
            &triangulation, cell->level(), cell->index(), &stokes.dof_handler()));
          stokes_values[velocities].get_function_gradients(stokes.solution(), gradients);
          phi_values.reinit(DoFHandler<2>::active_cell_iterator(
            &triangulation, cell->level(), cell->index(), &volume_fraction.dof_handler()));
          phi_values.get_function_values(volume_fraction.solution(), phis);
          cell->get_dof_indices(cell_dofs);
          for (unsigned int k = 0; k < at_nodes.size(); ++k)
            {
              const auto dof = cell_dofs[fe.component_to_system_index(0, k)];
              if (!owned.is_element(dof))
                continue;
              const unsigned int i = node_of_owned_dof[owned.index_within_set(dof)];
              velocity_gradient[i] += gradients[k];
              phi[i] = phis[k];
              ++n_cells[i];
            }
        }
    for (unsigned int i = 0; i < nodes.size(); ++i)
      velocity_gradient[i] /= n_cells[i];
  }


  double
  ElasticStress::update(const StokesSolver &  stokes,
                        const VolumeFraction &volume_fraction,
                        const double          time_step)
  {
    std::vector<Tensor<2, 2>> velocity_gradient;
    std::vector<double>       phi;
    nodal_fields(stokes, volume_fraction, velocity_gradient, phi);

    const double a     = model.slip_parameter;
    const double alpha = 1.0 / model.weissenberg;       // eq. 2.40
    const double beta  = shift() / model.weissenberg;   // ηp/(a Wi²)
    const double k     = time_step;
    const Tensor<2, 2> identity = unit_symmetric_tensor<2>();

    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              triangulation.get_communicator());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        // Φ = (a+1)/2 ∇u + (a−1)/2 ∇uᵀ; E = (I − kΦ)^{-1} (eq. 3.41-3.42)
        // or its Cayley form.
        const Tensor<2, 2> &L   = velocity_gradient[i];
        const Tensor<2, 2>  Phi = 0.5 * (a + 1) * L + 0.5 * (a - 1) * transpose(L);
        const Tensor<2, 2>  E =
          parameters.cayley ?
            invert(identity - 0.5 * k * Phi) * (identity + 0.5 * k * Phi) :
            invert(identity - k * Phi);
        // Q2 interpolation of a step overshoots below 0: clip φ as in η(φ).
        const double        f   = std::clamp(phi[i], 0.0, 1.0);
        const Tensor<2, 2>  c_foot(nodes[i].foot_conformation);
        // c^{n+1} = (φ E c(y) Eᵀ + kβ I) / (φ + kα)   (eq. 3.44)
        const SymmetricTensor<2, 2> c = symmetrize(
          (f * E * c_foot * transpose(E) + k * beta * identity) / (f + k * alpha));
        distributed[nodes[i].dofs[0]] = c[0][0];
        distributed[nodes[i].dofs[1]] = c[0][1];
        distributed[nodes[i].dofs[2]] = c[1][1];
      }
    distributed.compress(VectorOperation::insert);
    // A continuous c is continuous at hanging nodes too, except where the
    // repair below lifts a hanging node (by the repair's size, counted).
    hanging_node_constraints.distribute(distributed);
    constraint_repairs = repair_positivity(distributed);
    const TrilinosWrappers::MPI::Vector previous = current;
    current                                      = distributed;
    return relative_change(previous);
  }


  double
  ElasticStress::relative_change(const TrilinosWrappers::MPI::Vector &previous) const
  {
    // ‖Δτ‖_L2 / ‖τ‖_L2 with the Frobenius norm; Δτ = Δc, but τ's own size,
    // not c's (which includes the relaxed state shift·I), is the scale.
    FEValues<2> fe_values(fe, stokes_quadrature, update_values | update_JxW_values);
    std::vector<Vector<double>> now(stokes_quadrature.size(), Vector<double>(3));
    std::vector<Vector<double>> before(stokes_quadrature.size(), Vector<double>(3));
    const auto frobenius_square = [](const double xx, const double xy, const double yy) {
      return xx * xx + 2 * xy * xy + yy * yy;
    };
    double squares[2] = {0, 0}; // change, size
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(current, now);
          fe_values.get_function_values(previous, before);
          for (unsigned int q = 0; q < now.size(); ++q)
            {
              squares[0] += frobenius_square(now[q][0] - before[q][0],
                                             now[q][1] - before[q][1],
                                             now[q][2] - before[q][2]) *
                            fe_values.JxW(q);
              squares[1] +=
                frobenius_square(now[q][0] - shift(), now[q][1], now[q][2] - shift()) *
                fe_values.JxW(q);
            }
        }
    Utilities::MPI::sum(squares, triangulation.get_communicator(), squares);
    return squares[1] > 0 ? std::sqrt(squares[0] / squares[1]) : std::sqrt(squares[0]);
  }


  unsigned int
  ElasticStress::repair_positivity(TrilinosWrappers::MPI::Vector &distributed) const
  {
    // Nodes set by Q2 interpolation (hanging nodes, new nodes of refined
    // cells) are weighted sums with a weight −1/8, not convex ones; raise
    // their smallest eigenvalue to the floor, keeping the eigenvectors.
    unsigned int repairs = 0;
    if (shift() > 0)
      {
        const double floor = parameters.positivity_floor * shift();
        for (const Node &node : nodes)
          {
            const double smallest = smallest_eigenvalue(distributed[node.dofs[0]],
                                                        distributed[node.dofs[1]],
                                                        distributed[node.dofs[2]]);
            if (smallest < floor)
              {
                // Written, not added: every rank compresses with insert.
                const double lift          = floor - smallest;
                distributed[node.dofs[0]] = distributed[node.dofs[0]] + lift;
                distributed[node.dofs[2]] = distributed[node.dofs[2]] + lift;
                ++repairs;
              }
          }
      }
    distributed.compress(VectorOperation::insert);
    return Utilities::MPI::sum(repairs, triangulation.get_communicator());
  }


  void
  ElasticStress::stress_at_quadrature_points(
    const DoFHandler<2>::active_cell_iterator &cell,
    std::vector<SymmetricTensor<2, 2>> &       tau) const
  {
    quadrature_values->reinit(DoFHandler<2>::active_cell_iterator(
      &triangulation, cell->level(), cell->index(), &dofs));
    std::vector<Vector<double>> c(tau.size(), Vector<double>(3));
    quadrature_values->get_function_values(current, c);
    for (unsigned int q = 0; q < tau.size(); ++q)
      tau[q] = SymmetricTensor<2, 2>({c[q][0] - shift(), c[q][2] - shift(), c[q][1]});
  }


  void
  ElasticStress::prepare_for_refinement()
  {
    carrier.prepare(dofs, current);
  }


  void
  ElasticStress::finish_refinement()
  {
    setup_dofs(stokes_quadrature);
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              triangulation.get_communicator());
    carrier.finish(dofs, distributed);
    transfer_repairs += repair_positivity(distributed);
    current = distributed;
    old     = distributed;
  }


  void
  ElasticStress::prepare_for_checkpoint()
  {
    carrier.prepare_checkpoint(dofs, current);
  }


  void
  ElasticStress::checkpoint_written()
  {
    carrier.release();
  }


  void
  ElasticStress::advance_time()
  {
    old              = current;
    transfer_repairs = 0;
  }


  double
  ElasticStress::min_eigenvalue() const
  {
    double smallest = std::numeric_limits<double>::max();
    for (const Node &node : nodes)
      smallest = std::min(smallest,
                          smallest_eigenvalue(current[node.dofs[0]],
                                              current[node.dofs[1]],
                                              current[node.dofs[2]]));
    return Utilities::MPI::min(smallest, triangulation.get_communicator());
  }


  unsigned int
  ElasticStress::n_positivity_fixes() const
  {
    return positivity_fixes;
  }


  unsigned int
  ElasticStress::n_positivity_repairs() const
  {
    return transfer_repairs + constraint_repairs;
  }


  unsigned int
  ElasticStress::n_remote_feet() const
  {
    return remote_feet;
  }


  void
  ElasticStress::add_output(DataOut<2> &data_out) const
  {
    data_out.add_data_vector(dofs, current, *tau_postprocessor);
  }


  const DoFHandler<2> &
  ElasticStress::dof_handler() const
  {
    return dofs;
  }


  const TrilinosWrappers::MPI::Vector &
  ElasticStress::solution() const
  {
    return current;
  }
} // namespace viscofilm
