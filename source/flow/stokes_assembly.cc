// The Stokes system's assembly (MODEL.md §3 step 2a): the momentum equation
// with the elastic stress, the velocity at the departure feet (or Eulerian
// convection) and the boundary tractions on the right; each cell's matrix
// goes to the linear-solver strategy (stokes_linear_solver.h). And the
// step's inertia for the consistent forces (inertia()).
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/lac/affine_constraints.templates.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>

#include <viscofilm/core/dof_cell.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/flow/stokes_linear_solver.h>
#include <viscofilm/stress/stress.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace viscofilm
{
  template <int dim>
  void
  StokesFlow<dim>::average_viscosity(const Averaging       averaging,
                                  const std::vector<double> &JxW,
                                  std::vector<double> &      viscosity)
  {
    if (averaging == Averaging::none)
      return;
    double weight = 0, sum = 0;
    for (unsigned int q = 0; q < JxW.size(); ++q)
      {
        weight += JxW[q];
        switch (averaging)
          {
            case Averaging::arithmetic:
              sum += JxW[q] * viscosity[q];
              break;
            case Averaging::harmonic:
              sum += JxW[q] / viscosity[q];
              break;
            default:
              sum += JxW[q] * std::log(viscosity[q]);
          }
      }
    const double mean =
      (averaging == Averaging::arithmetic ? sum / weight :
       averaging == Averaging::harmonic   ? weight / sum :
                                            std::exp(sum / weight));
    std::fill(viscosity.begin(), viscosity.end(), mean);
  }


  namespace
  {
    /// A WorkStream thread's FEValues of the fields the momentum equation
    /// reads, Stokes', φ's and c's, and its arrays at the quadrature points
    /// (step-32's scratch data).
    template <int dim>
    struct AssemblyScratch
    {
      AssemblyScratch(const Mapping<dim> &      mapping,
                      const FiniteElement<dim> &stokes_fe,
                      const FiniteElement<dim> &volume_fraction_fe,
                      const FiniteElement<dim> &stress_fe,
                      const Quadrature<dim> &   quadrature,
                      const Quadrature<dim - 1> &face_quadrature)
        : fe_values(mapping,
                    stokes_fe,
                    quadrature,
                    update_values | update_gradients | update_quadrature_points |
                      update_JxW_values)
        , volume_fraction_values(mapping, volume_fraction_fe, quadrature, update_values)
        , stress_values(mapping, stress_fe, quadrature, update_values)
        , fe_face_values(mapping,
                         stokes_fe,
                         face_quadrature,
                         update_values | update_normal_vectors |
                           update_quadrature_points | update_JxW_values)
        , volume_fraction(quadrature.size())
        , expansion(quadrature.size())
        , old_velocity(quadrature.size())
        , older_velocity(quadrature.size()) // zero unless BDF2
        , body_force(quadrature.size(), Vector<double>(dim))
        , conformation(quadrature.size(), Vector<double>(stress_fe.n_components()))
        , tau(quadrature.size())
        , iterate_strain_rate(quadrature.size())
        , phi_u(stokes_fe.n_dofs_per_cell())
        , grad_phi_u(stokes_fe.n_dofs_per_cell())
        , convection(stokes_fe.n_dofs_per_cell(), stokes_fe.n_dofs_per_cell())
        , symgrad_phi_u(stokes_fe.n_dofs_per_cell())
        , div_phi_u(stokes_fe.n_dofs_per_cell())
        , phi_p(stokes_fe.n_dofs_per_cell())
      {}

      AssemblyScratch(const AssemblyScratch &other)
        : AssemblyScratch(other.fe_values.get_mapping(),
                          other.fe_values.get_fe(),
                          other.volume_fraction_values.get_fe(),
                          other.stress_values.get_fe(),
                          other.fe_values.get_quadrature(),
                          other.fe_face_values.get_quadrature())
      {}

      FEValues<dim>                        fe_values;
      FEValues<dim>                        volume_fraction_values;
      FEValues<dim>                        stress_values;
      FEFaceValues<dim>                    fe_face_values;
      std::vector<double>                  volume_fraction;
      std::vector<double>                  expansion; // ∇·u (growth)
      std::vector<Tensor<1, dim>>          old_velocity;
      std::vector<Tensor<1, dim>>          older_velocity;
      std::vector<Vector<double>>          body_force;
      std::vector<Vector<double>>          conformation;
      std::vector<SymmetricTensor<2, dim>> tau;
      std::vector<SymmetricTensor<2, dim>> iterate_strain_rate;
      std::vector<Tensor<1, dim>>          phi_u;
      std::vector<Tensor<2, dim>>          grad_phi_u;
      FullMatrix<double>                   convection; // Eulerian (u*·∇)u
      std::vector<SymmetricTensor<2, dim>> symgrad_phi_u;
      std::vector<double>                  div_phi_u;
      std::vector<double>                  phi_p;
    };


    /// The strategy's StokesViscosity: the model at φ (of a matrix
    /// assembly) interpolated to the strategy's points, averaged as the
    /// assembly averages.
    template <int dim>
    class ModelViscosity : public StokesViscosity<dim>
    {
    public:
      ModelViscosity(const Model &                             model,
                     const typename StokesFlow<dim>::Averaging averaging,
                     const DoFHandler<dim> &                   volume_fraction_dofs,
                     const TrilinosWrappers::MPI::Vector &     volume_fraction)
        : model(model)
        , averaging(averaging)
        , volume_fraction_dofs(volume_fraction_dofs)
        , volume_fraction(volume_fraction)
      {}

      void
      evaluate(const FEValues<dim> &values, std::vector<double> &viscosity) override
      {
        // One FEValues of φ per quadrature, not one per cell.
        if (!volume_fraction_values ||
            !(volume_fraction_values->get_quadrature() == values.get_quadrature()))
          volume_fraction_values = std::make_unique<FEValues<dim>>(volume_fraction_dofs.get_fe(),
                                                                   values.get_quadrature(),
                                                                   update_values);
        volume_fraction_values->reinit(cell_of(volume_fraction_dofs, values.get_cell()));
        phi.resize(values.n_quadrature_points);
        volume_fraction_values->get_function_values(volume_fraction, phi);
        viscosity.resize(phi.size());
        for (unsigned int q = 0; q < phi.size(); ++q)
          viscosity[q] = model.viscosity(phi[q]);
        StokesFlow<dim>::average_viscosity(averaging, values.get_JxW_values(), viscosity);
      }

    private:
      const Model &                             model;
      const typename StokesFlow<dim>::Averaging averaging;
      const DoFHandler<dim> &                   volume_fraction_dofs;
      const TrilinosWrappers::MPI::Vector &     volume_fraction;
      std::unique_ptr<FEValues<dim>>            volume_fraction_values;
      std::vector<double>                       phi;
    };


    /// A cell's matrix (with η and JxW for the strategy) and right-hand side.
    template <int dim>
    struct AssemblyCopy
    {
      AssemblyCopy(const unsigned int dofs_per_cell, const unsigned int n_q_points)
        : rhs(dofs_per_cell)
      {
        cell.JxW.resize(n_q_points);
        cell.viscosity.resize(n_q_points);
        cell.elastic_viscosity.resize(n_q_points, 0.0);
        cell.dof_indices.resize(dofs_per_cell);
        cell.matrix.reinit(dofs_per_cell, dofs_per_cell);
      }

      StokesCellMatrix<dim> cell;
      Vector<double>        rhs;
    };
  } // namespace


  template <int dim>
  void
  StokesFlow<dim>::assemble(const Coefficients &coefficients)
  {
    make_constraints(coefficients.time);

    const bool assemble_matrix = !matrix_is_current;
    if (assemble_matrix)
      {
        assembled_viscosity =
          std::make_unique<ModelViscosity<dim>>(model,
                                                parameters.averaging,
                                                *coefficients.volume_fraction_dof_handler,
                                                *coefficients.volume_fraction);
        linear_solver->start_matrix(*assembled_viscosity);
      }
    system_rhs = 0;

    const Quadrature<dim> quadrature = this->quadrature();
    // The prescribed normal traction −P n of pressure boundaries.
    const QGauss<dim - 1> face_quadrature(fe.degree + 1);
    const unsigned int    dofs_per_cell = fe.n_dofs_per_cell();
    const unsigned int    n_q_points    = quadrature.size();
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(dim);
    // The component of each shape function (dim: the pressure).
    std::vector<unsigned int> component(dofs_per_cell);
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      component[i] = fe.system_to_component_index(i).first;

    const bool implicit_elastic =
      parameters.implicit_elastic_viscosity && model.viscoelastic;
    if (implicit_elastic && assemble_matrix)
      elastic_viscosity_cache.resize(triangulation.n_locally_owned_active_cells() *
                                     n_q_points);
    const bool use_feet = !old_velocity_at_feet.empty();
    const bool eulerian =
      parameters.convection == Convection::eulerian && model.density > 0;

    // Res Du/Dt (ρ Du/Dt in SI) by implicit Euler, (Res/k)(u − u^n, v), or
    // with u^{n-1} by BDF2 (inertia_weights()); u^n and u^{n-1} at the
    // departure feet (semi-Lagrangian) or at the point, with Res ((u*·∇)u, v)
    // added (Eulerian, u* = u^n or its extrapolation to t_{n+1}, so that the
    // step stays second order at Order 2).
    const bool bdf2 = inertia_bdf2();
    const auto [mass_coefficient, old_coefficient, older_coefficient] =
      inertia_weights(coefficients.time_step);
    const ExpressionAt<dim> body_force_now = coefficients.body_force->at(coefficients.time);
    const ElasticStress<dim> &elastic_stress = *coefficients.elastic_stress;

    // The owned cells in a list: a cell's number in it locates its
    // quadrature points' entries in the per-point arrays (feet, η_e cache).
    std::vector<typename DoFHandler<dim>::active_cell_iterator> owned_cells;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        owned_cells.push_back(cell);

    const auto assemble_cell = [&](const typename decltype(owned_cells)::const_iterator &it,
                                   AssemblyScratch<dim> &                             scratch,
                                   AssemblyCopy<dim> &                                copy) {
      const auto &       cell  = *it;
      const std::size_t  first = (it - owned_cells.begin()) * n_q_points;
      FEValues<dim> &    fe_values = scratch.fe_values;
      StokesCellMatrix<dim> &data  = copy.cell;
      std::vector<double> &viscosity         = data.viscosity;
      std::vector<double> &elastic_viscosity = data.elastic_viscosity;
      std::vector<double> &volume_fraction   = scratch.volume_fraction;

      fe_values.reinit(cell);
      data.cell             = cell;
      data.mass_coefficient = mass_coefficient;
      data.JxW              = fe_values.get_JxW_values();
      scratch.volume_fraction_values.reinit(
        cell_of(*coefficients.volume_fraction_dof_handler, cell));
      scratch.volume_fraction_values.get_function_values(*coefficients.volume_fraction,
                                                         volume_fraction);
      for (unsigned int q = 0; q < n_q_points; ++q)
        viscosity[q] = model.viscosity(volume_fraction[q]);
      if (coefficients.expansion)
        scratch.volume_fraction_values.get_function_values(*coefficients.expansion,
                                                           scratch.expansion);
      scratch.stress_values.reinit(cell_of(elastic_stress.dof_handler(), cell));
      scratch.stress_values.get_function_values(elastic_stress.solution(),
                                                scratch.conformation);
      for (unsigned int q = 0; q < n_q_points; ++q)
        scratch.tau[q] = elastic_stress.stress_of(scratch.conformation[q], volume_fraction[q]);
      average_viscosity(parameters.averaging, data.JxW, viscosity);
      if (implicit_elastic)
        {
          // From τ^n (the stress iterate when the matrix is built, at the
          // step's first Picard iteration), kept for the step: matrix and
          // right-hand side must use the same η_e for the two to cancel (added
          // after the averaging, which is a model of ηs only).
          fe_values[velocities].get_function_symmetric_gradients(current_solution,
                                                                 scratch.iterate_strain_rate);
          for (unsigned int q = 0; q < n_q_points; ++q)
            {
              if (assemble_matrix)
                elastic_viscosity_cache[first + q] =
                  model.elastic_viscosity(volume_fraction[q],
                                          coefficients.time_step,
                                          scratch.tau[q]);
              elastic_viscosity[q] = elastic_viscosity_cache[first + q];
              viscosity[q] += elastic_viscosity[q];
            }
        }

      if (use_feet)
        for (unsigned int q = 0; q < n_q_points; ++q)
          {
            scratch.old_velocity[q] = old_velocity_at_feet[first + q];
            if (bdf2)
              scratch.older_velocity[q] = previous_velocity_at_feet[first + q];
          }
      else
        {
          fe_values[velocities].get_function_values(old_solution, scratch.old_velocity);
          if (bdf2)
            fe_values[velocities].get_function_values(older_solution, scratch.older_velocity);
        }
      body_force_now.vector_value_list(fe_values.get_quadrature_points(),
                                       scratch.body_force);

      // With the matrix current, the cell matrix is needed only to move
      // the inhomogeneities of constrained dofs to the right-hand side:
      // boundary values, and hanging dofs constrained to boundary dofs,
      // which interior cells touching the wall at a vertex also hold.
      cell->get_dof_indices(data.dof_indices);
      const bool need_matrix =
        assemble_matrix ||
        std::any_of(data.dof_indices.begin(),
                    data.dof_indices.end(),
                    [this](const types::global_dof_index i) {
                      return constraints.is_inhomogeneously_constrained(i);
                    });
      FullMatrix<double> &cell_matrix = data.matrix;
      Vector<double> &    cell_rhs    = copy.rhs;
      const bool convect = eulerian && need_matrix;
      cell_matrix = 0;
      cell_rhs    = 0;
      if (convect)
        scratch.convection = 0;
      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          for (unsigned int k = 0; k < dofs_per_cell; ++k)
            {
              scratch.phi_u[k]         = fe_values[velocities].value(k, q);
              scratch.symgrad_phi_u[k] = fe_values[velocities].symmetric_gradient(k, q);
              scratch.div_phi_u[k]     = fe_values[velocities].divergence(k, q);
              scratch.phi_p[k]         = fe_values[pressure].value(k, q);
              if (convect)
                scratch.grad_phi_u[k] = fe_values[velocities].gradient(k, q);
            }
          const auto &   phi_u         = scratch.phi_u;
          const auto &   symgrad_phi_u = scratch.symgrad_phi_u;
          const auto &   div_phi_u     = scratch.div_phi_u;
          const auto &   phi_p         = scratch.phi_p;
          const double   JxW           = fe_values.JxW(q);
          Tensor<1, dim> force;
          for (unsigned int d = 0; d < dim; ++d)
            force[d] = scratch.body_force[q][d];
          const Tensor<1, dim> rhs_vector = old_coefficient * scratch.old_velocity[q] +
                                            force -
                                            older_coefficient * scratch.older_velocity[q];
          // s(φ) τ: φ τ in the thesis (eq. 2.34), τ for phases.
          // With the implicit elastic viscosity η_e in the matrix, its
          // explicit twin 2 η_e D(u^l) joins s τ on the right.
          const SymmetricTensor<2, dim> phi_tau =
            model.stress_coupling(volume_fraction[q]) * scratch.tau[q] -
            2 * elastic_viscosity[q] * scratch.iterate_strain_rate[q];

          // The lower triangle of the symmetric (m u, v) + (2η D(u), D(v)) −
          // (p, ∇·v) − (∇·u, q), mirrored below; a shape function has one
          // non-zero component, so the terms a pair cannot have are skipped
          // (the 3D assembly in a third of the time, doc/performance.md).
          const double two_eta = 2 * viscosity[q];
          for (unsigned int i = 0; i < dofs_per_cell && need_matrix; ++i)
            {
              const unsigned int ci = component[i];
              if (ci == dim)
                for (unsigned int j = 0; j <= i; ++j)
                  cell_matrix(i, j) -= (component[j] == dim ? 0.0 : phi_p[i] * div_phi_u[j]) * JxW;
              else
                for (unsigned int j = 0; j <= i; ++j)
                  {
                    const unsigned int cj = component[j];
                    cell_matrix(i, j) +=
                      (cj == dim ?
                         -div_phi_u[i] * phi_p[j] :
                         (cj == ci ? (mass_coefficient * phi_u[i][ci]) * phi_u[j][ci] : 0.0) +
                           two_eta * (symgrad_phi_u[i] * symgrad_phi_u[j])) *
                      JxW;
                  }
            }
          // Eulerian: the unsymmetric Res ((u*·∇)u, v), added after the
          // mirroring.
          if (convect)
            {
              const Tensor<1, dim> w =
                model.density * JxW *
                convecting_velocity(scratch.old_velocity[q], scratch.older_velocity[q]);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                if (component[i] < dim)
                  for (unsigned int j = 0; j < dofs_per_cell; ++j)
                    if (component[j] == component[i])
                      scratch.convection(i, j) += phi_u[i] * (scratch.grad_phi_u[j] * w);
            }
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            cell_rhs(i) += (rhs_vector * phi_u[i] - phi_tau * symgrad_phi_u[i]) * JxW;
          // −(q, ∇·u) = −(q, P/φmax): the volume growth adds.
          if (coefficients.expansion)
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              if (component[i] == dim)
                cell_rhs(i) -= phi_p[i] * scratch.expansion[q] * JxW;
        }
      if (need_matrix)
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
            cell_matrix(i, j) = cell_matrix(j, i);
      if (convect)
        cell_matrix.add(1.0, scratch.convection);

      // −∫ P n·v ds (Type = pressure; outflow has P = 0).
      FEFaceValues<dim> &fe_face_values = scratch.fe_face_values;
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary() &&
            boundary_conditions.boundary(face->boundary_id()).type ==
              BoundaryConditions<dim>::Type::pressure)
          {
            const ParsedExpression<dim> &pressure =
              boundary_conditions.boundary(face->boundary_id()).pressure;
            fe_face_values.reinit(cell, face);
            for (unsigned int q = 0; q < face_quadrature.size(); ++q)
              {
                const double traction =
                  pressure.value(fe_face_values.quadrature_point(q), coefficients.time) *
                  fe_face_values.JxW(q);
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  cell_rhs(i) -= traction * (fe_face_values[velocities].value(i, q) *
                                             fe_face_values.normal_vector(q));
              }
          }

      if (assemble_matrix)
        linear_solver->add_cell_preconditioner(fe_values, data);
    };

    // In the order of the cells, whatever the threads: the sums are those
    // of one thread.
    const auto copy_cell = [&](const AssemblyCopy<dim> &copy) {
      if (assemble_matrix)
        linear_solver->add_cell_matrix(copy.cell, constraints);
      constraints.distribute_local_to_global(copy.rhs,
                                             copy.cell.dof_indices,
                                             system_rhs,
                                             copy.cell.matrix);
    };

    const auto &stress_fe = elastic_stress.dof_handler().get_fe();
    // Every worker reads the same const objects (the Stokes, φ and c
    // vectors, the constraints, the model) and writes only its scratch, its
    // copy and its cells' entries of the η_e cache.
    WorkStream::run(owned_cells.cbegin(),
                    owned_cells.cend(),
                    assemble_cell,
                    copy_cell,
                    AssemblyScratch<dim>(this->mapping(),
                                         fe,
                                         coefficients.volume_fraction_dof_handler->get_fe(),
                                         stress_fe,
                                         quadrature,
                                         face_quadrature),
                    AssemblyCopy<dim>(dofs_per_cell, n_q_points));

    if (assemble_matrix)
      {
        linear_solver->finish_matrix();
        matrix_is_current = true;
      }
    system_rhs.compress(VectorOperation::add);
    // Constrained rows are decoupled (their values come from distribute()).
    // With zero right-hand side and first guess there they stay zero in the
    // Krylov space; otherwise their diagonal, of the size of η, meets the
    // preconditioner's pressure mass, of the size of h²/η, at hanging pressure
    // nodes and stalls FGMRES at large viscosity contrasts.
    constraints.set_zero(system_rhs);
  }


  template <int dim>
  bool
  StokesFlow<dim>::inertia_bdf2() const
  {
    return parameters.convection == Convection::eulerian ?
             model.density > 0 && order == 2 && previous_step > 0 :
             !previous_velocity_at_feet.empty();
  }


  template <int dim>
  std::array<double, 3>
  StokesFlow<dim>::inertia_weights(const double k) const
  {
    // BDF2 with variable steps, ω = k_n/k_{n-1}:
    // (Res/k)((1+2ω)/(1+ω) u − (1+ω) u^n + ω²/(1+ω) u^{n-1}).
    const double omega = inertia_bdf2() ? k / previous_step : 0;
    const double scale = model.density / k;
    return {{scale * (1 + 2 * omega) / (1 + omega),
             scale * (1 + omega),
             scale * omega * omega / (1 + omega)}};
  }


  template <int dim>
  Tensor<1, dim>
  StokesFlow<dim>::convecting_velocity(const Tensor<1, dim> &old_velocity,
                                         const Tensor<1, dim> &older_velocity) const
  {
    const double theta = inertia_bdf2() ? step_length / previous_step : 0.0;
    return (1 + theta) * old_velocity - theta * older_velocity;
  }


  template <int dim>
  void
  StokesFlow<dim>::inertia(const FEValues<dim> &         fe_values,
                             const std::size_t             owned_index,
                             std::vector<Tensor<1, dim>> &result) const
  {
    const unsigned int n_q_points = fe_values.n_quadrature_points;
    result.assign(n_q_points, Tensor<1, dim>());
    if (model.density == 0 || step_length == 0)
      return;
    const FEValuesExtractors::Vector velocities(0);
    const bool                       bdf2 = inertia_bdf2();
    const auto [a, b, c]                  = inertia_weights(step_length);
    std::vector<Tensor<1, dim>> u(n_q_points), old(n_q_points), older(n_q_points);
    fe_values[velocities].get_function_values(current_solution, u);
    if (!old_velocity_at_feet.empty())
      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          old[q] = old_velocity_at_feet[owned_index * n_q_points + q];
          if (bdf2)
            older[q] = previous_velocity_at_feet[owned_index * n_q_points + q];
        }
    else
      {
        fe_values[velocities].get_function_values(old_solution, old);
        if (bdf2)
          fe_values[velocities].get_function_values(older_solution, older);
      }
    for (unsigned int q = 0; q < n_q_points; ++q)
      result[q] = a * u[q] - b * old[q] + c * older[q];
    if (parameters.convection == Convection::eulerian)
      {
        std::vector<Tensor<2, dim>> grad_u(n_q_points);
        fe_values[velocities].get_function_gradients(current_solution, grad_u);
        for (unsigned int q = 0; q < n_q_points; ++q)
          result[q] += model.density * (grad_u[q] * convecting_velocity(old[q], older[q]));
      }
  }


  template <int dim>
  Quadrature<dim>
  StokesFlow<dim>::quadrature() const
  {
    return QGauss<dim>(fe.degree + 1);
  }


  template <int dim>
  void
  StokesFlow<dim>::trace_back(DepartureFeet<dim> &feet, const double time_step)
  {
    step_length = time_step;
    old_velocity_at_feet.clear();
    previous_velocity_at_feet.clear();
    if (model.density == 0 || parameters.convection == Convection::eulerian)
      return;
    FEValues<dim> fe_values(this->mapping(), fe, quadrature(), update_quadrature_points);
    std::vector<Point<dim>>                               points;
    std::vector<typename Triangulation<dim>::active_cell_iterator> cells;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const Point<dim> &p : fe_values.get_quadrature_points())
            {
              points.push_back(p);
              cells.push_back(cell);
            }
        }
    // Order 1: feet by u^n. Order 2: u^n at the feet one step back and, for
    // BDF2, u^{n-1} at the feet two steps back, each traced with the velocity
    // at the middle of its interval, t_{n+1} − duration/2 (second order).
    const auto at_feet = [&](const double                              duration,
                             const TrilinosWrappers::MPI::BlockVector &values,
                             std::vector<Tensor<1, dim>> &               result) {
      feet.compute(points,
                   cells,
                   dofs,
                   order == 2 ? extrapolated_solution(time_step - 0.5 * duration) :
                                old_solution,
                   duration);
      for (const auto &value : evaluate_velocity(feet.at_feet(), dofs, values))
        {
          Tensor<1, dim> u;
          for (unsigned int d = 0; d < dim; ++d)
            u[d] = value[d];
          result.push_back(u);
        }
    };
    at_feet(time_step, old_solution, old_velocity_at_feet);
    if (order == 2 && previous_step > 0)
      at_feet(time_step + previous_step, older_solution, previous_velocity_at_feet);
  }


  // The class is instantiated once, in stokes.cc; each file instantiates the
  // members it defines (an explicit instantiation of the whole class in two
  // files would be ill-formed).
#define INSTANTIATE(dim)                                                          \
  template void StokesFlow<dim>::average_viscosity(const Averaging,           \
                                                   const std::vector<double> &, \
                                                   std::vector<double> &);      \
  template void StokesFlow<dim>::assemble(const Coefficients &);                  \
  template bool StokesFlow<dim>::inertia_bdf2() const;                            \
  template std::array<double, 3> StokesFlow<dim>::inertia_weights(const double) const; \
  template Tensor<1, dim> StokesFlow<dim>::convecting_velocity(const Tensor<1, dim> &, \
                                                               const Tensor<1, dim> &) \
    const;                                                                        \
  template void StokesFlow<dim>::inertia(const FEValues<dim> &,                   \
                                         const std::size_t,                       \
                                         std::vector<Tensor<1, dim>> &) const;    \
  template Quadrature<dim> StokesFlow<dim>::quadrature() const;                   \
  template void StokesFlow<dim>::trace_back(DepartureFeet<dim> &, const double);

  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
