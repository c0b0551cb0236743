#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_q.h>

#include <deal.II/matrix_free/fe_point_evaluation.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/core/input.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/transport/volume_fraction.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace viscofilm
{
  namespace
  {
    /// For x = μk >= 0: e^{−x}, and x times the weights of a function linear
    /// in s ∈ [0, 1] against e^{−xs}: x ∫_0^1 e^{−xs} (1 − s) ds = 1 − (1 −
    /// e^{−x})/x and x ∫_0^1 e^{−xs} s ds = (1 − e^{−x})/x − e^{−x}, both in
    /// [0, 1] and finite for x = ∞ (w → 0); their series for small x, where
    /// the closed forms cancel.
    std::array<double, 3>
    exponential_weights(const double x)
    {
      const double decay = std::exp(-x);
      if (x >= 0.5)
        {
          const double mean = -std::expm1(-x) / x; // (1 − e^{−x})/x
          return {{decay, 1 - mean, mean - decay}};
        }
      // x Σ_{n≥2} (−x)^{n−2}/n! and x Σ_{n≥2} (n−1)(−x)^{n−2}/n!, to round-off.
      double at_start = 0, at_end = 0, term = 0.5 * x; // x (−x)^{n−2}/n!
      for (unsigned int n = 2; n < 20; ++n)
        {
          at_start += term;
          at_end += (n - 1) * term;
          term *= -x / (n + 1);
        }
      return {{decay, at_start, at_end}};
    }


    /// The stored components of f(c), c given by its stored components
    /// (symmetric_function: log c and exp for Stress/Foot interpolation).
    template <int dim, class ScalarFunction>
    Tensor<1, n_symmetric_components<dim>>
    function_of_components(const Tensor<1, n_symmetric_components<dim>> &c, const ScalarFunction &f)
    {
      const SymmetricTensor<2, dim>          fc = symmetric_function(symmetric_tensor<dim>(c), f);
      Tensor<1, n_symmetric_components<dim>> result;
      for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
        result[k] = stored_component(fc, k);
      return result;
    }


    /// τ = Model::stress(c, φ) as output fields; φ is evaluated at the
    /// output points only where τ depends on it (Rheology = phases).
    template <int dim>
    class StressPostprocessor : public DataPostprocessor<dim>
    {
    public:
      StressPostprocessor(const ElasticStress<dim> &stress, const VolumeFraction<dim> &volume_fraction)
        : stress(stress)
        , volume_fraction(volume_fraction)
      {}

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        const unsigned int  n = inputs.solution_values.size();
        std::vector<double> phi(n, 0.0);
        if (stress.stress_depends_on_volume_fraction())
          {
            AssertThrow(n == snapshot_points<dim>().size(), ExcInternalError());
            FEValues<dim> phi_values(volume_fraction.dof_handler().get_fe(),
                                     snapshot_points<dim>(),
                                     update_values);
            phi_values.reinit(
              cell_of(volume_fraction.dof_handler(), inputs.template get_cell<dim>()));
            phi_values.get_function_values(volume_fraction.solution(), phi);
          }
        for (unsigned int q = 0; q < n; ++q)
          {
            const SymmetricTensor<2, dim> tau =
              stress.stress_of(inputs.solution_values[q], phi[q]);
            for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
              computed[q][k] = stored_component(tau, k);
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names;
        for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
          names.push_back("tau_" + symmetric_component_name<dim>(k));
        return names;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values;
      }

    private:
      const ElasticStress<dim> & stress;
      const VolumeFraction<dim> &volume_fraction;
    };
  } // namespace


  template <int dim>
  void
  ElasticStress<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stress");
    prm.declare_entry("Element",
                      "continuous",
                      Patterns::Selection("continuous|discontinuous"),
                      "continuous: FE_Q(2) for each component of c (the thesis; a "
                      "node uses the mean of ∇u over its cells). discontinuous: "
                      "FE_DGQ(2) (each node uses its own cell's ∇u).");
    prm.declare_entry("Positivity safe feet",
                      "true",
                      Patterns::Bool(),
                      "Where the Q2 interpolant of c at a departure foot is not "
                      "positive definite, use the multilinear interpolant on the "
                      "Q1 sub-cell of the Q2 nodes instead (a convex "
                      "combination of nodal values, so positive definite).");
    prm.declare_entry("Foot interpolation",
                      "conformation",
                      Patterns::Selection("conformation|logarithm"),
                      "What is interpolated at a departure foot. conformation: "
                      "the Q2 interpolant of c (the thesis). logarithm: the Q2 "
                      "interpolant of log c at the foot, exponentiated, as in "
                      "the log-conformation formulation (Fattal & Kupferman "
                      "2004): positive definite by construction (Positivity "
                      "safe feet does not apply), and exact where c varies "
                      "exponentially, as in the narrow stress layers and wake "
                      "strands of high Wi, which polynomials of c resolve "
                      "poorly. Needs Model/Slip parameter > 0 (c positive "
                      "definite).");
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
    prm.declare_entry("Wall velocity gradient",
                      "mean of cells",
                      Patterns::Selection("mean of cells|no-slip shear"),
                      "The velocity gradient with which a node on a no-slip "
                      "wall updates c. mean of cells: the mean of ∇u over the "
                      "node's cells, as everywhere else (the thesis). no-slip "
                      "shear: its wall shear part (I − n⊗n)(∇u n)⊗n, the form "
                      "the exact ∇u has where u = 0 on the wall. The fluid on "
                      "the wall never leaves its node, so the discrete "
                      "divergence in the mean (n·∂u/∂n ≠ 0) acts on it as an "
                      "extension rate for ever and, past 1/(2λ), makes c grow "
                      "without bound (doc/numerics.md).");
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


  template <int dim>
  void
  ElasticStress<dim>::Parameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stress");
    discontinuous        = (prm.get("Element") == "discontinuous");
    positivity_safe_feet = prm.get_bool("Positivity safe feet");
    logarithm_at_feet    = (prm.get("Foot interpolation") == "logarithm");
    cayley               = (prm.get("Deformation gradient") == "Cayley");
    positivity_floor     = prm.get_double("Positivity floor");
    wall_shear           = (prm.get("Wall velocity gradient") == "no-slip shear");
    prm.leave_subsection();
  }


  template <int dim>
  ElasticStress<dim>::ElasticStress(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const Mapping<dim> &                           mapping,
    const Parameters &                             parameters,
    const Model &                                  model,
    const BoundaryConditions<dim> &                boundary_conditions,
    const unsigned int                             order,
    const Quadrature<dim> &                        stokes_quadrature,
    const VolumeFraction<dim> &                    volume_fraction)
    : FieldType(triangulation, mapping)
    , triangulation(triangulation)
    , parameters(parameters)
    , model(model)
    , boundary_conditions(boundary_conditions)
    , order(order)
    , fe(parameters.discontinuous ?
           static_cast<const FiniteElement<dim> &>(FE_DGQ<dim>(2)) :
           static_cast<const FiniteElement<dim> &>(FE_Q<dim>(2)),
         n_symmetric_components<dim>)
    , stokes_quadrature(stokes_quadrature)
    , volume_fraction(volume_fraction)
  {}


  template <int dim>
  SymmetricTensor<2, dim>
  ElasticStress<dim>::stress_of(const Vector<double> &conformation,
                           const double          volume_fraction) const
  {
    return model.stress(symmetric_tensor<dim>(conformation), volume_fraction);
  }


  template <int dim>
  bool
  ElasticStress<dim>::stress_depends_on_volume_fraction() const
  {
    return model.rheology == Model::Rheology::phases;
  }


  template <int dim>
  void
  ElasticStress<dim>::setup_dofs()
  {
    dofs.distribute_dofs(fe);
    const IndexSet &owned = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, locally_relevant_dofs);
    this->setup_vectors(owned, locally_relevant_dofs);
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraints);
    boundary_conditions.constrain_periodic(dofs, constraints);
    constraints.close();

    const std::vector<Point<dim>> &unit_support =
      fe.base_element(0).get_unit_support_points();
    for (unsigned int k = 0; k < unit_support.size(); ++k)
      {
        unsigned int index = 0;
        for (unsigned int d = 0, stride = 1; d < dim; ++d, stride *= 3)
          index += std::lround(2 * unit_support[k][d]) * stride;
        lexicographic_node[index] = k;
      }

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
              node.position = this->mapping().transform_unit_to_real_cell(cell, unit_support[k]);
              node.cell = cell;
              for (unsigned int c = 0; c < n_symmetric_components<dim>; ++c)
                node.dofs[c] = cell_dofs[fe.component_to_system_index(c, k)];
              nodes.push_back(node);
            }
        }

    if (parameters.wall_shear)
      find_wall_normals();
  }


  template <int dim>
  void
  ElasticStress<dim>::find_wall_normals()
  {
    // The outward normal of face f (normal to the unit axis f/2) at a
    // point: ±(row f/2 of the inverse Jacobian), normalised.
    const Quadrature<dim> at_nodes(fe.base_element(0).get_unit_support_points());
    FEValues<dim>         geometry(this->mapping(),
                                   fe,
                                   at_nodes,
                                   update_inverse_jacobians);
    const auto no_slip = [this](const auto &face) {
      return face->at_boundary() && boundary_conditions.boundary(face->boundary_id()).type ==
                                      BoundaryConditions<dim>::Type::no_slip;
    };
    for_each_node_on_cells([&](const typename DoFHandler<dim>::active_cell_iterator &cell,
                               const Quadrature<dim> &,
                               const std::vector<unsigned int> &node_of_support) {
      const auto faces = cell->face_iterators();
      if (std::none_of(faces.begin(), faces.end(), no_slip))
        return;
      geometry.reinit(cell);
      for (const unsigned int f : cell->face_indices())
        if (no_slip(cell->face(f)))
          for (unsigned int k = 0; k < at_nodes.size(); ++k)
            if (node_of_support[k] != numbers::invalid_unsigned_int &&
                at_nodes.point(k)[f / 2] == f % 2)
              {
                Tensor<1, dim> normal;
                for (unsigned int d = 0; d < dim; ++d)
                  normal[d] = geometry.inverse_jacobian(k)[f / 2][d];
                nodes[node_of_support[k]].wall_normal +=
                  (f % 2 ? 1.0 : -1.0) * normal / normal.norm();
              }
    });
    for (Node &node : nodes)
      if (node.wall_normal.norm() > 0)
        node.wall_normal /= node.wall_normal.norm();
  }


  template <int dim>
  void
  ElasticStress<dim>::set_initial_conditions(const Function<dim> &initial_stress)
  {
    const std::vector<double> phi = nodal_volume_fraction();
    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              triangulation.get_communicator());
    // Without elastic stress τ ≡ 0 (c = shift I) whatever the input says:
    // nothing updates c then, so a non-zero τ0 would act on the flow for ever.
    Vector<double> tau(n_symmetric_components<dim>);
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const Node &node = nodes[i];
        // A discontinuous c takes its own cell's limit of τ0 on the cell's
        // boundary, so that a τ0 jumping across a face is kept.
        const Point<dim> inside =
          parameters.discontinuous ?
            node.position + 1e-10 * (node.cell->center() - node.position) :
            node.position;
        if (model.viscoelastic)
          initial_stress.vector_value(inside, tau);
        const SymmetricTensor<2, dim> c = conformation(tau, phi[i]);
        set_conformation(node, c, distributed);
      }
    distributed.compress(VectorOperation::insert);
    constraints.distribute(distributed);
    current_solution = distributed;
    old_solution     = distributed;
    transfer_repairs = 0; // of the unset c carried by the initial refinement
  }


  template <int dim>
  SymmetricTensor<2, dim>
  ElasticStress<dim>::conformation(const Vector<double> &tau, const double phi) const
  {
    AssertDimension(tau.size(), n_symmetric_components<dim>);
    return model.conformation(symmetric_tensor<dim>(tau), phi);
  }


  template <int dim>
  void
  ElasticStress<dim>::trace_back(DepartureFeet<dim> & feet,
                            const StokesFlow<dim> & stokes,
                            const double          time,
                            const double          time_step)
  {
    std::vector<Point<dim>>                               points(nodes.size());
    std::vector<typename Triangulation<dim>::active_cell_iterator> cells(nodes.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        points[i] = nodes[i].position;
        cells[i]  = nodes[i].cell;
      }
    // Order 2: the implicit midpoint rule with u at t_{n+1/2}.
    feet.compute(points,
                 cells,
                 stokes.dof_handler(),
                 order == 2 ? stokes.extrapolated_solution(0.5 * time_step) :
                              stokes.solution(),
                 time_step);

    // c^n at the feet, on whichever rank owns them.
    const MPI_Comm     comm      = triangulation.get_communicator();
    const double       this_rank = Utilities::MPI::this_mpi_process(comm);
    const bool         logarithm = parameters.logarithm_at_feet;
    const bool         guard = !logarithm && parameters.positivity_safe_feet && model.relaxed_conformation() > 0;
    const unsigned int n_cell_nodes = fe.base_element(0).n_dofs_per_cell();
    unsigned int       fixes     = 0;
    FEPointEvaluation<n_symmetric_components<dim>, dim> conformation(this->mapping(), fe, update_values, 0);
    std::vector<double>     cell_values(fe.n_dofs_per_cell());

    // The foot's c, and the rank that evaluated it (to count remote feet).
    constexpr unsigned int                     n_values = n_symmetric_components<dim> + 1;
    const CellEvaluation<dim, n_values> evaluate =
      [&](const typename Triangulation<dim>::active_cell_iterator &cell,
          const ArrayView<const Point<dim>> &             unit_points,
          const ArrayView<std::array<double, n_values>> & values) {
        cell_of(dofs, cell)->get_dof_values(old_solution, cell_values.begin(), cell_values.end());
        if (logarithm)
          for (unsigned int node = 0; node < n_cell_nodes; ++node)
            {
              Tensor<1, n_symmetric_components<dim>> c;
              for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
                c[k] = cell_values[fe.component_to_system_index(k, node)];
              // An eigenvalue the floor let reach 0 maps to a finite log.
              const auto log_c = function_of_components<dim>(c, [](const double x) {
                return std::log(std::max(x, std::numeric_limits<double>::min()));
              });
              for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
                cell_values[fe.component_to_system_index(k, node)] = log_c[k];
            }
        conformation.reinit(cell, unit_points);
        conformation.evaluate(cell_values, EvaluationFlags::values);
        for (unsigned int q = 0; q < unit_points.size(); ++q)
          {
            Tensor<1, n_symmetric_components<dim>> c = conformation.get_value(q);
            if (logarithm)
              c = function_of_components<dim>(c, [](const double x) { return std::exp(x); });
            else if (guard && smallest_eigenvalue(symmetric_tensor<dim>(c)) <= 0)
              {
                // Multilinear interpolation on the Q1 sub-cell of the Q2 nodes.
                const Point<dim> &p = unit_points[q];
                unsigned int      corner[dim];
                double            xi[dim];
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    corner[d] = p[d] < 0.5 ? 0 : 1;
                    xi[d]     = std::clamp(2 * p[d] - corner[d], 0.0, 1.0);
                  }
                c = 0;
                for (const unsigned int v : GeometryInfo<dim>::vertex_indices())
                  {
                    double       weight = 1;
                    unsigned int node = 0, stride = 1;
                    for (unsigned int d = 0; d < dim; ++d, stride *= 3)
                      {
                        const unsigned int offset = (v >> d) & 1;
                        weight *= offset ? xi[d] : 1 - xi[d];
                        node += (corner[d] + offset) * stride;
                      }
                    for (unsigned int component = 0; component < n_symmetric_components<dim>;
                         ++component)
                      c[component] += weight * cell_values[fe.component_to_system_index(
                                                 component, lexicographic_node[node])];
                  }
                ++fixes;
              }
            for (unsigned int component = 0; component < n_symmetric_components<dim>; ++component)
              values[q][component] = c[component];
            values[q][n_symmetric_components<dim>] = this_rank;
          }
      };

    const auto   values = feet.at_feet().template evaluate<n_values>(evaluate);
    const std::vector<types::boundary_id> &inflow   = feet.inflow_boundaries();
    const std::vector<Point<dim>> &        at_feet  = feet.at_feet().located_points();
    unsigned int                           remote   = 0;
    Vector<double>                         tau(n_symmetric_components<dim>);
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const auto &v = values[i];
        if (inflow[i] != numbers::invalid_boundary_id)
          {
            // The characteristic enters through boundary inflow[i]: its
            // Stress at the cut, at t_n like c^n at the other feet, and its
            // volume fraction there.
            boundary_conditions.boundary(inflow[i]).stress.vector_value(at_feet[i], time, tau);
            nodes[i].foot_conformation = ElasticStress<dim>::conformation(
              tau, boundary_conditions.boundary(inflow[i]).volume_fraction);
          }
        else
          nodes[i].foot_conformation =
            symmetric_tensor<dim>(v);
        if (v[n_symmetric_components<dim>] != this_rank)
          ++remote;
      }
    remote_feet      = Utilities::MPI::sum(remote, comm);
    positivity_fixes = Utilities::MPI::sum(fixes, comm);
    if (order == 2)
      at_feet_for_second_order(feet, stokes);
  }


  template <int dim>
  void
  ElasticStress<dim>::at_feet_for_second_order(const DepartureFeet<dim> &feet,
                                               const StokesFlow<dim> &   stokes)
  {
    // ∇u^n (the deformation's rate at t_n) and φ^n at the feet (inflow feet:
    // the boundary's volume fraction, as for c there). ∇u^n is the field a
    // node uses (nodal_velocity_gradient: the mean over the node's cells),
    // interpolated in c's element: the foot's own cell's ∇u differs from it
    // by the jump of ∇u across faces, O(1) at the biofilm's interface, and
    // Φ̄ would then not tend to the node's Φ as k → 0 (doc/numerics.md).
    // Entry m = dim d + e of ∇u is component m % n of vector m / n, n = c's
    // number of components.
    constexpr unsigned int n_entries = dim * dim;
    constexpr unsigned int n_vectors =
      (n_entries + n_symmetric_components<dim> - 1) / n_symmetric_components<dim>;
    const std::vector<Tensor<2, dim>>             nodal_gradient = nodal_velocity_gradient(stokes);
    std::array<TrilinosWrappers::MPI::Vector, n_vectors> gradient;
    for (TrilinosWrappers::MPI::Vector &vector : gradient)
      vector.reinit(dofs.locally_owned_dofs(), triangulation.get_communicator());
    for (unsigned int i = 0; i < nodes.size(); ++i)
      for (unsigned int m = 0; m < n_entries; ++m)
        gradient[m / n_symmetric_components<dim>][nodes[i].dofs[m % n_symmetric_components<dim>]] =
          nodal_gradient[i][m / dim][m % dim];
    for (TrilinosWrappers::MPI::Vector &vector : gradient)
      {
        vector.compress(VectorOperation::insert);
        constraints.distribute(vector);
        TrilinosWrappers::MPI::Vector ghosted(dofs.locally_owned_dofs(),
                                              locally_relevant_dofs,
                                              triangulation.get_communicator());
        ghosted = vector;
        vector.swap(ghosted);
      }

    // At the feet in the layout of evaluate_velocity(): ∂u_d/∂x_e at
    // [dim + dim d + e]; φ^n at [0].
    const FiniteElement<dim> &phi_fe = volume_fraction.dof_handler().get_fe();
    FEPointEvaluation<1, dim> phi(this->mapping(), phi_fe, update_values);
    FEPointEvaluation<n_symmetric_components<dim>, dim> gradient_values(this->mapping(),
                                                                   fe,
                                                                   update_values);
    std::vector<double> phi_dofs(phi_fe.n_dofs_per_cell());
    std::vector<double> gradient_dofs(fe.n_dofs_per_cell());
    const auto          values = feet.at_feet().template evaluate<n_velocity_values<dim>>(
      [&](const typename Triangulation<dim>::active_cell_iterator &   cell,
          const ArrayView<const Point<dim>> &                         unit_points,
          const ArrayView<std::array<double, n_velocity_values<dim>>> & values) {
        gradient_values.reinit(cell, unit_points);
        for (unsigned int v = 0; v < n_vectors; ++v)
          {
            cell_of(dofs, cell)->get_dof_values(gradient[v],
                                                gradient_dofs.begin(),
                                                gradient_dofs.end());
            gradient_values.evaluate(gradient_dofs, EvaluationFlags::values);
            for (unsigned int q = 0; q < unit_points.size(); ++q)
              for (unsigned int m = v * n_symmetric_components<dim>;
                   m < std::min(n_entries, (v + 1) * n_symmetric_components<dim>);
                   ++m)
                values[q][dim + m] = gradient_values.get_value(q)[m % n_symmetric_components<dim>];
          }
        cell_of(volume_fraction.dof_handler(), cell)
          ->get_dof_values(volume_fraction.solution(), phi_dofs.begin(), phi_dofs.end());
        phi.reinit(cell, unit_points);
        phi.evaluate(phi_dofs, EvaluationFlags::values);
        for (unsigned int q = 0; q < unit_points.size(); ++q)
          values[q][0] = phi.get_value(q);
      });
    const std::vector<types::boundary_id> &inflow = feet.inflow_boundaries();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        for (unsigned int m = 0; m < n_entries; ++m)
          nodes[i].foot_velocity_gradient[m / dim][m % dim] = values[i][dim + m];
        nodes[i].foot_volume_fraction =
          inflow[i] != numbers::invalid_boundary_id ?
            boundary_conditions.boundary(inflow[i]).volume_fraction :
            values[i][0];
      }
  }


  template <int dim>
  template <typename CellFunction>
  void
  ElasticStress<dim>::for_each_node_on_cells(const CellFunction &on_cell) const
  {
    // Ghost cells too: a continuous node on a rank boundary sees all of its
    // cells.
    const Quadrature<dim> at_nodes(fe.base_element(0).get_unit_support_points());
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    std::vector<unsigned int>            node_of_support(at_nodes.size());
    const IndexSet &                     owned = dofs.locally_owned_dofs();
    for (const auto &cell : dofs.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(cell_dofs);
          for (unsigned int k = 0; k < at_nodes.size(); ++k)
            {
              const auto dof     = cell_dofs[fe.component_to_system_index(0, k)];
              node_of_support[k] = owned.is_element(dof) ?
                                     node_of_owned_dof[owned.index_within_set(dof)] :
                                     numbers::invalid_unsigned_int;
            }
          on_cell(cell, at_nodes, node_of_support);
        }
  }


  template <int dim>
  std::vector<Tensor<2, dim>>
  ElasticStress<dim>::nodal_velocity_gradient(const StokesFlow<dim> &stokes) const
  {
    const Quadrature<dim> at_nodes(fe.base_element(0).get_unit_support_points());
    FEValues<dim> stokes_values(this->mapping(),
                                stokes.dof_handler().get_fe(),
                                at_nodes,
                                update_gradients);
    const FEValuesExtractors::Vector velocities(0);
    std::vector<Tensor<2, dim>>        gradients(at_nodes.size());
    std::vector<Tensor<2, dim>>        velocity_gradient(nodes.size());
    std::vector<unsigned int>        n_cells(nodes.size(), 0);
    for_each_node_on_cells([&](const typename DoFHandler<dim>::active_cell_iterator &cell,
                               const Quadrature<dim> &,
                               const std::vector<unsigned int> &node_of_support) {
      stokes_values.reinit(cell_of(stokes.dof_handler(), cell));
      stokes_values[velocities].get_function_gradients(stokes.solution(), gradients);
      for (unsigned int k = 0; k < gradients.size(); ++k)
        if (node_of_support[k] != numbers::invalid_unsigned_int)
          {
            velocity_gradient[node_of_support[k]] += gradients[k];
            ++n_cells[node_of_support[k]];
          }
    });
    const Tensor<2, dim> identity = unit_symmetric_tensor<dim>();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        velocity_gradient[i] /= n_cells[i];
        const Tensor<1, dim> &n = nodes[i].wall_normal;
        if (n.norm() > 0)
          // u = 0 on the wall: ∂u/∂t = 0 and n·∂u/∂n = ∇·u = 0, so ∇u =
          // (I − n⊗n)(∇u n)⊗n, a pure shear.
          velocity_gradient[i] =
            outer_product((identity - outer_product(n, n)) * (velocity_gradient[i] * n), n);
      }
    return velocity_gradient;
  }


  template <int dim>
  std::vector<double>
  ElasticStress<dim>::nodal_volume_fraction() const
  {
    const Quadrature<dim> at_nodes(fe.base_element(0).get_unit_support_points());
    FEValues<dim> phi_values(volume_fraction.dof_handler().get_fe(), at_nodes, update_values);
    std::vector<double> phis(at_nodes.size());
    std::vector<double> phi(nodes.size(), 0.0);
    for_each_node_on_cells([&](const typename DoFHandler<dim>::active_cell_iterator &cell,
                               const Quadrature<dim> &,
                               const std::vector<unsigned int> &node_of_support) {
      phi_values.reinit(cell_of(volume_fraction.dof_handler(), cell));
      phi_values.get_function_values(volume_fraction.solution(), phis);
      for (unsigned int k = 0; k < phis.size(); ++k)
        if (node_of_support[k] != numbers::invalid_unsigned_int)
          phi[node_of_support[k]] = phis[k];
    });
    return phi;
  }


  template <int dim>
  double
  ElasticStress<dim>::update(const StokesFlow<dim> &stokes, const double time_step)
  {
    const std::vector<Tensor<2, dim>> velocity_gradient = nodal_velocity_gradient(stokes);
    const std::vector<double>       phi = nodal_volume_fraction();

    const double a     = model.slip_parameter;
    const double k     = time_step;
    const Tensor<2, dim> identity = unit_symmetric_tensor<dim>();
    // Φ = (a+1)/2 ∇u + (a−1)/2 ∇uᵀ (eq. 3.41); the Cayley transform of kΦ,
    // (I − kΦ/2)^{-1}(I + kΦ/2), is orthogonal for a skew kΦ.
    const auto deformation_rate = [a](const Tensor<2, dim> &L) {
      return 0.5 * (a + 1) * L + 0.5 * (a - 1) * transpose(L);
    };
    const auto cayley = [&identity](const Tensor<2, dim> &kPhi) {
      return invert(identity - 0.5 * kPhi) * (identity + 0.5 * kPhi);
    };

    TrilinosWrappers::MPI::Vector distributed(dofs.locally_owned_dofs(),
                                              triangulation.get_communicator());
    double largest[3] = {0, 0, 0}; // ‖τ₂ − τ₁‖, ‖τ₂‖, G |c_rest| (Order 2)
    // The first step of an impulsive start (Res > 0, u^0 = 0 and boundary
    // data that are not zero at t = 0): the flow leaves u^0 within a time of
    // order Res, and a mean with ∇u^0 would be an O(k) error that stays
    // (rate 1 in channel_startup_inertia_order2). ∇u^{n+1} alone errs by
    // O(k²), once.
    const bool impulsive = stokes.old_velocity_is_impulsive_start();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        // E = (I − kΦ)^{-1} (eq. 3.42) or its Cayley form.
        const Tensor<2, dim> Phi = deformation_rate(velocity_gradient[i]);
        const Tensor<2, dim> E =
          parameters.cayley ? cayley(k * Phi) : invert(identity - k * Phi);
        const Model::Relaxation r =
          model.relaxation(order == 2 ? nodes[i].foot_volume_fraction : phi[i]);
        const Tensor<2, dim>      c_foot(nodes[i].foot_conformation);
        // c^{n+1} = (w E c(y) Eᵀ + kβ I) / (w + kα)   (thesis: w = φ, eq. 3.44)
        const SymmetricTensor<2, dim> c_first =
          symmetrize((r.weight * E * c_foot * transpose(E) + k * r.beta * identity) /
                     (r.weight + k * r.alpha));
        SymmetricTensor<2, dim> c = c_first;
        if (order == 2)
          {
            // Along the characteristic w c' = w (Φc + cΦᵀ) + β I − α c has,
            // for frozen Φ and μ = α/w, the solution
            //   c(k) = e^{−μk} E(k) c(y) E(k)ᵀ + (β/w) ∫_0^k e^{−μs} E(s)E(s)ᵀ ds
            // with E(s) = exp(sΦ). E(k): the Cayley form of kΦ, Φ the mean of
            // the foot's (t_n) and the node's (t_{n+1}); the integral: E(s)E(s)ᵀ
            // linear between I and E Eᵀ, integrated exactly against e^{−μs}.
            // A sum of SPD terms with weights >= 0 (β > 0): SPD; for μk → ∞ it
            // tends to the quasi-steady c = β/α (I + (Φ + Φᵀ)/μ), which a
            // Strang splitting of relaxation and deformation misses.
            const Tensor<2, dim> E_mid =
              cayley(0.5 * k * (Phi + (impulsive ? Phi : deformation_rate(nodes[i].foot_velocity_gradient))));
            // (βk/w) C(μk) = (β/α) μk C(μk): bounded as w → 0 (α > 0).
            const auto [decay, at_start, at_end] =
              r.weight > 0 ? exponential_weights(r.alpha * k / r.weight) :
                             std::array<double, 3>{{0, 1, 0}};
            const double relaxed = r.beta / r.alpha;
            c = symmetrize(decay * E_mid * c_foot * transpose(E_mid) +
                           relaxed * at_start * identity +
                           relaxed * at_end * E_mid * transpose(E_mid));
            const double G = model.stress_modulus(nodes[i].foot_volume_fraction);
            largest[0] = std::max(largest[0], G * (c - c_first).norm());
            largest[1] = std::max(largest[1],
                                  G * (c - model.relaxed_conformation() *
                                             unit_symmetric_tensor<dim>())
                                        .norm());
            largest[2] = std::max(largest[2], G * std::abs(model.relaxed_conformation()));
          }
        set_conformation(nodes[i], c, distributed);
      }
    distributed.compress(VectorOperation::insert);
    Utilities::MPI::max(largest, triangulation.get_communicator(), largest);
    step_error = largest[0] > 0 ? largest[0] / (largest[1] + largest[2]) : 0;
    // A continuous c is continuous at hanging nodes too, except where the
    // repair below lifts a hanging node (by the repair's size, counted).
    constraints.distribute(distributed);
    constraint_repairs = repair_positivity(distributed);
    const TrilinosWrappers::MPI::Vector previous = current_solution;
    current_solution                             = distributed;
    return relative_change(previous);
  }


  template <int dim>
  double
  ElasticStress<dim>::relative_change(const TrilinosWrappers::MPI::Vector &previous) const
  {
    // ‖Δτ‖_L2 / ‖τ‖_L2 with the Frobenius norm; Δτ = G Δc, but τ's own size,
    // not c's (which includes the relaxed state), is the scale.
    FEValues<dim> fe_values(this->mapping(),
                            fe,
                            stokes_quadrature,
                            update_values | update_JxW_values);
    FEValues<dim> phi_values(volume_fraction.dof_handler().get_fe(),
                           stokes_quadrature,
                           update_values);
    std::vector<Vector<double>> now(stokes_quadrature.size(),
                                    Vector<double>(n_symmetric_components<dim>));
    std::vector<Vector<double>> before(stokes_quadrature.size(),
                                       Vector<double>(n_symmetric_components<dim>));
    std::vector<double>         phi(stokes_quadrature.size());
    const double                rest = model.relaxed_conformation();
    // ‖G (a − b)‖_F² of two tensors given by their stored components, with
    // b's diagonal shifted by @p shift.
    const auto frobenius_square =
      [](const double G, const Vector<double> &a, const Vector<double> &b, const double shift) {
        double square = 0;
        for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
          {
            const auto [i, j]    = symmetric_component<dim>(k);
            const double entry   = G * (a[k] - (i == j ? b[k] + shift : b[k]));
            square += (i == j ? 1 : 2) * entry * entry;
          }
        return square;
      };
    const Vector<double> zero(n_symmetric_components<dim>);
    double squares[2] = {0, 0}; // change, size
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(current_solution, now);
          fe_values.get_function_values(previous, before);
          phi_values.reinit(cell_of(volume_fraction.dof_handler(), cell));
          phi_values.get_function_values(volume_fraction.solution(), phi);
          for (unsigned int q = 0; q < now.size(); ++q)
            {
              const double G = model.stress_modulus(phi[q]);
              squares[0] += frobenius_square(G, now[q], before[q], 0) * fe_values.JxW(q);
              squares[1] += frobenius_square(G, now[q], zero, rest) * fe_values.JxW(q);
            }
        }
    Utilities::MPI::sum(squares, triangulation.get_communicator(), squares);
    return squares[1] > 0 ? std::sqrt(squares[0] / squares[1]) : std::sqrt(squares[0]);
  }


  template <int dim>
  unsigned int
  ElasticStress<dim>::repair_positivity(TrilinosWrappers::MPI::Vector &distributed) const
  {
    // Nodes set by Q2 interpolation (hanging nodes, new nodes of refined
    // cells) are weighted sums with a weight −1/8, not convex ones; raise
    // their smallest eigenvalue to the floor, keeping the eigenvectors.
    unsigned int repairs = 0;
    if (model.relaxed_conformation() > 0)
      {
        const double floor = parameters.positivity_floor * model.relaxed_conformation();
        for (const Node &node : nodes)
          {
            const SymmetricTensor<2, dim> c        = conformation_at(node, distributed);
            const double                  smallest = smallest_eigenvalue(c);
            if (smallest < floor)
              {
                // Written, not added: every rank compresses with insert.
                set_conformation(node,
                                 c + (floor - smallest) * unit_symmetric_tensor<dim>(),
                                 distributed);
                ++repairs;
              }
          }
      }
    distributed.compress(VectorOperation::insert);
    return Utilities::MPI::sum(repairs, triangulation.get_communicator());
  }


  template <int dim>
  SymmetricTensor<2, dim>
  ElasticStress<dim>::conformation_at(const Node &node, const TrilinosWrappers::MPI::Vector &vector)
  {
    SymmetricTensor<2, dim> c;
    for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
      {
        const auto [i, j] = symmetric_component<dim>(k);
        c[i][j]           = vector[node.dofs[k]];
      }
    return c;
  }


  template <int dim>
  void
  ElasticStress<dim>::set_conformation(const Node &              node,
                                  const SymmetricTensor<2, dim> &c,
                                  TrilinosWrappers::MPI::Vector &vector)
  {
    for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
      vector[node.dofs[k]] = stored_component(c, k);
  }


  template <int dim>
  void
  ElasticStress<dim>::transferred(TrilinosWrappers::MPI::Vector &distributed)
  {
    transfer_repairs += repair_positivity(distributed);
  }


  template <int dim>
  double
  ElasticStress<dim>::error_estimate() const
  {
    return step_error;
  }


  template <int dim>
  void
  ElasticStress<dim>::advance_time()
  {
    FieldType::advance_time();
    transfer_repairs = 0;
  }


  template <int dim>
  double
  ElasticStress<dim>::min_eigenvalue() const
  {
    double smallest = std::numeric_limits<double>::max();
    for (const Node &node : nodes)
      smallest = std::min(smallest, smallest_eigenvalue(conformation_at(node, current_solution)));
    return Utilities::MPI::min(smallest, triangulation.get_communicator());
  }


  template <int dim>
  unsigned int
  ElasticStress<dim>::n_positivity_fixes() const
  {
    return positivity_fixes;
  }


  template <int dim>
  unsigned int
  ElasticStress<dim>::n_positivity_repairs() const
  {
    return transfer_repairs + constraint_repairs;
  }


  template <int dim>
  unsigned int
  ElasticStress<dim>::n_remote_feet() const
  {
    return remote_feet;
  }


  template <int dim>
  void
  ElasticStress<dim>::add_output(DataOut<dim> &data_out)
  {
    tau_postprocessor = std::make_unique<StressPostprocessor<dim>>(*this, volume_fraction);
    data_out.add_data_vector(dofs, current_solution, *tau_postprocessor);
  }


  template <int dim>
  void
  ElasticStress<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    statistics.set("min_conformation_eigenvalue", min_eigenvalue());
    statistics.set("feet_remote", n_remote_feet());
    statistics.set("feet_positivity_fixes", n_positivity_fixes());
    statistics.set("conformation_repairs", n_positivity_repairs());
  }


  VISCOFILM_INSTANTIATE(ElasticStress)
} // namespace viscofilm
