#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>

#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/core/input.h>
#include <viscofilm/biofilm/loads.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/flow/stokes.h>
#include <viscofilm/stress/stress.h>
#include <viscofilm/material/total_stress.h>
#include <viscofilm/transport/volume_fraction.h>

#include <algorithm>
#include <cmath>

namespace viscofilm
{
  namespace
  {
    /// The tangential part of the traction @p force_density on a wall with
    /// outward normal @p normal: in 2D signed along the tangent n rotated by
    /// +90° (along +x on the bottom wall, where it is σ_xy), in 3D its length.
    template <int dim>
    double
    wall_shear(const Tensor<1, dim> &force_density, const Tensor<1, dim> &normal)
    {
      if constexpr (dim == 2)
        return force_density[0] * -normal[1] + force_density[1] * normal[0];
      else
        return (force_density - (force_density * normal) * normal).norm();
    }


    /// σ_xy and σ_vm at a snapshot's points.
    template <int dim>
    class LoadsPostprocessor : public DataPostprocessor<dim>
    {
    public:
      LoadsPostprocessor(const Model &         model,
                         const StokesFlow<dim> & stokes,
                         const VolumeFraction<dim> &volume_fraction,
                         const ElasticStress<dim> & stress)
        : points(snapshot_points<dim>())
        , model(model)
        , stokes(stokes)
        , volume_fraction(volume_fraction)
        , stress(stress)
      {}

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        AssertThrow(inputs.solution_values.size() == points.size(),
                    ExcInternalError());
        // One per call: DataOut calls this from several threads.
        TotalStress<FEValues<dim>> total_stress(
          points, model, stokes, volume_fraction, stress);
        total_stress.reinit(inputs.template get_cell<dim>());
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            computed[q][0] = total_stress.sigma[q][0][1];
            computed[q][1] = von_mises(total_stress.sigma[q]);
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        return {"shear_stress", "von_mises"};
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values;
      }

    private:
      const QIterated<dim>    points;
      const Model &         model;
      const StokesFlow<dim> & stokes;
      const VolumeFraction<dim> &volume_fraction;
      const ElasticStress<dim> & stress;
    };
  } // namespace




  template <int dim>
  void
  BiofilmLoads<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Forces");
    prm.declare_entry("Boundaries",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Boundaries (names of Boundary conditions, "
                      "comma-separated) whose force goes into statistics.csv as "
                      "force_x_<name>, force_y_<name> (3D: and force_z_<name>): "
                      "the total force (pressure, viscous and elastic) the "
                      "fluid exerts on the boundary, F = −∫ σ n ds with n the "
                      "domain's outward normal: per unit depth in 2D, the "
                      "whole boundary's in 3D. Empty: none.");
    prm.declare_entry("Method",
                      "consistent",
                      Patterns::Selection("consistent|surface integral"),
                      "consistent: F·e = −R(v), the residual of the discrete "
                      "momentum equation for the test function v that is e on "
                      "the boundary's velocity nodes and 0 at the others (the "
                      "reaction force). surface integral: −∫ σ n ds with the "
                      "face values of the fields. The measurements that chose "
                      "the default: doc/loads.md.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  BiofilmLoads<dim>::Parameters::parse_parameters(
    ParameterHandler &        prm,
    const BoundaryConditions<dim> &boundary_conditions)
  {
    prm.enter_subsection("Forces");
    force_boundaries =
      named_boundaries(prm.get("Boundaries"), "Forces/Boundaries", boundary_conditions);
    force_method = (prm.get("Method") == "surface integral" ?
                      ForceMethod::surface_integral :
                      ForceMethod::consistent);
    prm.leave_subsection();
  }


  template <int dim>
  BiofilmLoads<dim>::BiofilmLoads(const Parameters &    parameters,
                             const Biofilm<dim> &  biofilm,
                             const Model &         model,
                             const StokesFlow<dim> & stokes,
                             const VolumeFraction<dim> &volume_fraction,
                             const ElasticStress<dim> & stress)
    : parameters(parameters)
    , biofilm(biofilm)
    , model(model)
    , stokes(stokes)
    , volume_fraction(volume_fraction)
    , stress(stress)
    , postprocessor(
        std::make_unique<LoadsPostprocessor<dim>>(model, stokes, volume_fraction, stress))
  {}


  template <int dim>
  void
  BiofilmLoads<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    const QGauss<dim> quadrature(3);
    const QGauss<dim - 1> face_quadrature(3);
    TotalStress<FEValues<dim>>     cell_stress(quadrature, model, stokes, volume_fraction, stress);
    TotalStress<FEFaceValues<dim>> wall_stress(
      face_quadrature, model, stokes, volume_fraction, stress, update_normal_vectors);
    const double level = biofilm.interface_level;

    // sums: walls ∫ shear, walls length, interface ∫|σn|, interface measure,
    // detachment area; maxima: |shear| on the walls, |σn|, σ_vm
    double sums[5]   = {0, 0, 0, 0, 0};
    double maxima[3] = {0, 0, 0};
    for (const auto &cell : stokes.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() && biofilm.is_wall(cell->face(f)->boundary_id()))
              {
                wall_stress.reinit(cell, f);
                const auto &normals = wall_stress.stokes_fe_values().get_normal_vectors();
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    // The force per area on the wall, −σ n.
                    const double shear =
                      wall_shear(-(wall_stress.sigma[q] * normals[q]), normals[q]);
                    sums[0] += shear * wall_stress.JxW(q);
                    sums[1] += wall_stress.JxW(q);
                    maxima[0] = std::max(maxima[0], std::abs(shear));
                  }
              }

          cell_stress.reinit(cell);
          const auto [low, high] =
            std::minmax_element(cell_stress.phi.begin(), cell_stress.phi.end());
          const bool cut = (*low < level && *high > level);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const SymmetricTensor<2, dim> &sigma = cell_stress.sigma[q];
              if (cut && cell_stress.grad_phi[q].norm() > 0)
                {
                  // n points out of the biofilm: down the gradient of φ.
                  const Tensor<1, dim> n =
                    -cell_stress.grad_phi[q] / cell_stress.grad_phi[q].norm();
                  const double traction = (sigma * n).norm();
                  sums[2] += traction * cell_stress.JxW(q);
                  sums[3] += cell_stress.JxW(q);
                  maxima[1] = std::max(maxima[1], traction);
                }
              if (cell_stress.phi[q] >= level)
                {
                  const double equivalent = von_mises(sigma);
                  maxima[2] = std::max(maxima[2], equivalent);
                  if (equivalent > biofilm.stress_threshold)
                    sums[4] += cell_stress.JxW(q);
                }
            }
        }
    const MPI_Comm comm = stokes.dof_handler().get_communicator();
    Utilities::MPI::sum(sums, comm, sums);
    Utilities::MPI::max(maxima, comm, maxima);

    statistics.set("wall_shear_stress_mean", sums[1] > 0 ? sums[0] / sums[1] : 0);
    statistics.set("wall_shear_stress_max", maxima[0]);
    statistics.set("interface_traction_mean", sums[3] > 0 ? sums[2] / sums[3] : 0);
    statistics.set("interface_traction_max", maxima[1]);
    statistics.set("von_mises_max", maxima[2]);
    statistics.set("detachment_area", sums[4]);

    const std::vector<Tensor<1, dim>> forces = boundary_forces();
    for (unsigned int b = 0; b < forces.size(); ++b)
      for (unsigned int d = 0; d < dim; ++d)
        statistics.set(std::string("force_") + "xyz"[d] + "_" +
                         parameters.force_boundaries[b].name,
                       forces[b][d]);
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  BiofilmLoads<dim>::boundary_forces() const
  {
    if (parameters.force_boundaries.empty())
      return {};
    std::vector<Tensor<1, dim>> forces =
      (parameters.force_method == Parameters::ForceMethod::surface_integral ?
         surface_integral_forces() :
         consistent_forces());
    for (Tensor<1, dim> &force : forces)
      force = Utilities::MPI::sum(force, stokes.dof_handler().get_communicator());
    return forces;
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  BiofilmLoads<dim>::surface_integral_forces() const
  {
    const std::vector<NamedBoundaryId> &boundaries =
      parameters.force_boundaries;
    std::vector<Tensor<1, dim>> forces(boundaries.size());
    const DoFHandler<dim> &dofs = stokes.dof_handler();
    const auto &           fe   = dofs.get_fe();

    const QGauss<dim - 1>          quadrature(fe.degree + 1);
    TotalStress<FEFaceValues<dim>> face_stress(
      quadrature, model, stokes, volume_fraction, stress, update_normal_vectors);
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (unsigned int b = 0; b < boundaries.size(); ++b)
              if (cell->face(f)->boundary_id() == boundaries[b].id)
                {
                  face_stress.reinit(cell, f);
                  const auto &normals =
                    face_stress.stokes_fe_values().get_normal_vectors();
                  for (unsigned int q = 0; q < quadrature.size(); ++q)
                    forces[b] -= face_stress.sigma[q] * normals[q] * face_stress.JxW(q);
                }
    return forces;
  }


  template <int dim>
  std::vector<Tensor<1, dim>>
  BiofilmLoads<dim>::consistent_forces() const
  {
    const std::vector<NamedBoundaryId> &boundaries =
      parameters.force_boundaries;
    std::vector<Tensor<1, dim>> forces(boundaries.size());
    const DoFHandler<dim> &dofs = stokes.dof_handler();
    const auto &           fe   = dofs.get_fe();

    // F·e = −R(v) = −∫_Ω (Res Du/Dt · v + σ : ∇v) for v = e at the
    // boundary's velocity nodes and 0 at all others: the momentum equation's
    // weak form integrated by parts, ∫_Ω σ : ∇v = ∫_∂Ω σn · v − ∫_Ω ∇·σ · v,
    // with the step's own discretisation of the inertia (StokesFlow::
    // inertia(); without it DFG 2D-1's drag is 0.1 % lower), evaluated with
    // the assembly's quadrature, so that for a discrete solution it is the
    // reaction of the constrained equations. v must be a finite element
    // function: hanging nodes take the values of the nodes they hang on.
    // Where the boundary meets another one (a channel's corners), v
    // reaches onto the other's first faces; their part ∫ σn · v there is
    // taken off with the face values (zero on a closed boundary such as
    // a cylinder), else the force would pick up an O(h) share of the
    // neighbour's traction.
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dofs, relevant);
    AffineConstraints<double> hanging(relevant);
    DoFTools::make_hanging_node_constraints(dofs, hanging);
    hanging.close();
    const ComponentMask velocity = fe.component_mask(FEValuesExtractors::Vector(0));

    std::vector<IndexSet> on_boundary;
    for (const auto &boundary : boundaries)
      on_boundary.push_back(
        DoFTools::extract_boundary_dofs(dofs, velocity, {boundary.id}));
    // v's nodal value at dof i for boundary b.
    const auto value = [&](const unsigned int b, const types::global_dof_index i) {
      if (!hanging.is_constrained(i))
        return on_boundary[b].is_element(i) ? 1.0 : 0.0;
      double sum = 0;
      for (const auto &[j, weight] : *hanging.get_constraint_entries(i))
        sum += (on_boundary[b].is_element(j) ? weight : 0.0);
      return sum;
    };

    TotalStress<FEValues<dim>> cell_stress(
      stokes.quadrature(), model, stokes, volume_fraction, stress);
    const QGauss<dim - 1>          face_quadrature(fe.degree + 1);
    TotalStress<FEFaceValues<dim>> face_stress(
      face_quadrature, model, stokes, volume_fraction, stress, update_normal_vectors);
    const FEValuesExtractors::Vector     velocities(0);
    std::vector<types::global_dof_index> local_dofs(fe.n_dofs_per_cell());
    std::vector<double>                  v(fe.n_dofs_per_cell());
    std::vector<Tensor<1, dim>>          inertia;
    std::size_t                          owned_index = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          ++owned_index;
          cell->get_dof_indices(local_dofs);
          bool reinitialized = false;
          for (unsigned int b = 0; b < boundaries.size(); ++b)
            {
              bool touches = false;
              for (unsigned int i = 0; i < local_dofs.size(); ++i)
                {
                  v[i]    = (velocity[fe.system_to_component_index(i).first] ?
                               value(b, local_dofs[i]) :
                               0.0);
                  touches = touches || v[i] != 0;
                }
              if (!touches)
                continue;
              if (!reinitialized)
                {
                  cell_stress.reinit(cell);
                  stokes.inertia(cell_stress.stokes_fe_values(), owned_index - 1, inertia);
                }
              reinitialized = true;
              const auto &values = cell_stress.stokes_fe_values();
              for (unsigned int i = 0; i < local_dofs.size(); ++i)
                if (v[i] != 0)
                  {
                    const unsigned int d = fe.system_to_component_index(i).first;
                    for (unsigned int q = 0; q < values.n_quadrature_points; ++q)
                      forces[b][d] -= v[i] *
                                      (inertia[q] * values[velocities].value(i, q) +
                                       scalar_product(cell_stress.sigma[q],
                                                      values[velocities].gradient(i, q))) *
                                      values.JxW(q);
                  }

              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    cell->face(f)->boundary_id() != boundaries[b].id)
                  {
                    face_stress.reinit(cell, f);
                    const auto &face_values = face_stress.stokes_fe_values();
                    for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                      {
                        Tensor<1, dim> v_q;
                        for (unsigned int i = 0; i < local_dofs.size(); ++i)
                          if (v[i] != 0)
                            v_q += v[i] * face_values[velocities].value(i, q);
                        // v_q[d] is the weight of the component d.
                        const Tensor<1, dim> traction =
                          face_stress.sigma[q] * face_values.normal_vector(q);
                        for (unsigned int d = 0; d < dim; ++d)
                          forces[b][d] += traction[d] * v_q[d] * face_values.JxW(q);
                      }
                  }
            }
        }
    return forces;
  }


  template <int dim>
  void
  BiofilmLoads<dim>::add_output(DataOut<dim> &data_out)
  {
    data_out.add_data_vector(stokes.dof_handler(), stokes.solution(), *postprocessor);
  }


  VISCOFILM_INSTANTIATE(BiofilmLoads)
} // namespace viscofilm
