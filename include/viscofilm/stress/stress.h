// The elastic stress: conformation tensor c (τ = Model::stress(c, φ)) on its own
// DoFHandler, updated node by node by the symmetric matrix Riccati scheme
// along departure feet (MODEL.md §2-3, thesis eq. 2.39-2.40, 3.39-3.44).
#ifndef viscofilm_stress_h
#define viscofilm_stress_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <viscofilm/geometry/boundary_conditions.h>
#include <viscofilm/characteristics/departure_feet.h>
#include <viscofilm/core/dimension.h>
#include <viscofilm/core/field.h>
#include <viscofilm/material/model.h>

#include <array>
#include <memory>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  template <int dim>
  class StokesFlow;
  template <int dim>
  class VolumeFraction;

  template <int dim>
  class ElasticStress : public Field<dim, TrilinosWrappers::MPI::Vector>
  {
  public:
    struct Parameters
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// FE_Q(2)^n (the thesis; nodes use the mean ∇u of their cells) or
      /// FE_DGQ(2)^n (every node uses its own cell's ∇u), n = n_symmetric_components<dim>.
      bool discontinuous = false;
      /// Evaluate c at a foot on the Q1 sub-cells of the Q2 nodes where the
      /// Q2 interpolant is not positive definite.
      bool positivity_safe_feet = true;
      /// Interpolate log c at a foot and take its exponential (Foot
      /// interpolation = logarithm): positive definite by construction, and
      /// exact for c varying exponentially along a Q2 cell.
      bool logarithm_at_feet = false;
      /// E = (I − kΦ)^{-1} (the thesis, eq. 3.42) or the Cayley transform
      /// (I − kΦ/2)^{-1}(I + kΦ/2): second order, and exactly orthogonal in a
      /// rotation, so a co-rotating stress keeps its size.
      bool cayley = false;
      /// Nodes on a no-slip wall use the wall shear part of their ∇u
      /// (Wall velocity gradient = no-slip shear).
      bool wall_shear = false;
      /// Smallest eigenvalue of c, relative to ηp/(a Wi), that a node keeps
      /// after Q2 interpolation at hanging nodes and onto refined cells.
      double positivity_floor = 1e-6;
    };

    /// @p order: Time stepping/Order (1: the thesis' update, eq. 3.44; 2:
    /// the Strang-split update of update()). @p stokes_quadrature: the one
    /// the Stokes assembly asks τ at. @p volume_fraction: φ, which scales τ
    /// and whose values at the nodes and feet the update takes.
    ElasticStress(const parallel::distributed::Triangulation<dim> &triangulation,
                  const Mapping<dim> &                           mapping,
                  const Parameters &                             parameters,
                  const Model &                                  model,
                  const BoundaryConditions<dim> &boundary_conditions,
                  const unsigned int        order,
                  const Quadrature<dim> &   stokes_quadrature,
                  const VolumeFraction<dim> &volume_fraction);

    /// Distribute dofs and list the stress nodes.
    void
    setup_dofs() override;

    /// c = Model::conformation(τ0, φ) at the nodes (τ0 = 0 in the thesis;
    /// always 0 without Model/Viscoelastic).
    void
    set_initial_conditions(const Function<dim> &initial_stress);

    /// MODEL.md §3 step 1: the nodes' departure feet from u^n and c^n
    /// there; a foot on an inflow boundary takes that boundary's Stress at
    /// the cut and @p time (t_n, the time of the other feet's values).
    /// Order = 2: the feet follow the velocity extrapolated to t_{n+1/2}
    /// (StokesFlow::midpoint_velocity), and ∇u^n and φ^n are kept at the
    /// feet too.
    void
    trace_back(DepartureFeet<dim> &  feet,
               const StokesFlow<dim> & stokes,
               const double          time,
               const double          time_step);

    /// MODEL.md §3 step 2b: c^{n+1} at every node from the current Stokes
    /// iterate, φ^n and c^n at the feet (closed form, eq. 3.40-3.44).
    /// Returns ‖τ − τ_prev‖_L2 / ‖τ‖_L2 from the previous iterate, the
    /// Picard criterion on the stress.
    ///
    /// Order = 2: Strang splitting along the characteristic, each part
    /// keeping c symmetric positive definite: half a step of exact
    /// relaxation (a convex combination of c and the relaxed state), the
    /// deformation E c Eᵀ with the Cayley E of Φ averaged between the foot
    /// (∇u^n) and the node (∇u^{n+1}), half a step of relaxation; w, α, β
    /// of φ^n at the foot (φ is constant along the characteristic).
    double
    update(const StokesFlow<dim> &stokes, const double time_step);

    /// Order = 2, after update(): the local error of the step, max over the
    /// nodes of ‖τ₂ − τ₁‖_F, τ₁ from the first-order update (eq. 3.44, with
    /// the same feet), divided by max‖τ₂‖_F + max G |c_rest| (the stress
    /// and the elastic modulus ηp/(aλ): a relaxed stress still has a
    /// scale). Dimensionless. 0 with Order = 1.
    double
    error_estimate() const;


    /// τ of the conformation (its stored components, dimension.h) at a point where the volume
    /// fraction is @p volume_fraction (Model::stress); the Stokes assembly
    /// asks it at its quadrature points, on any thread.
    SymmetricTensor<2, dim>
    stress_of(const Vector<double> &conformation, const double volume_fraction) const;

    /// Whether τ depends on φ beyond c (Rheology = phases).
    bool
    stress_depends_on_volume_fraction() const;

    /// c^n := c^{n+1}, before the next time step; the repairs of mesh
    /// changes are counted from here.
    void
    advance_time() override;

    /// Smallest eigenvalue of c over all nodes (positive definiteness).
    double
    min_eigenvalue() const;

    /// Nodes whose foot value needed the positivity-safe evaluation.
    unsigned int
    n_positivity_fixes() const;

    /// Nodes raised to Stress/Positivity floor in the last update() and
    /// the mesh changes since the last advance_time().
    unsigned int
    n_positivity_repairs() const;

    /// Feet evaluated by another rank (summed over ranks) in the last
    /// trace_back().
    unsigned int
    n_remote_feet() const;

    /// The conformation of the elastic stress @p tau (stored components as the
    /// Stress expressions give it) at volume fraction @p phi (Model).
    SymmetricTensor<2, dim>
    conformation(const Vector<double> &tau, const double phi) const;

    /// Add tau_xx, tau_xy, ... (stored order) to @p data_out (τ needs φ with phases).
    void
    add_output(DataOut<dim> &data_out) override;

    /// statistics.csv: min_conformation_eigenvalue, feet_remote,
    /// feet_positivity_fixes, conformation_repairs.
    void
    add_statistics(CsvFile &statistics, const double time) const override;

  private:
    using FieldType = Field<dim, TrilinosWrappers::MPI::Vector>;
    using FieldType::constraints; // hanging nodes, periodicity: continuous c
    using FieldType::current_solution;
    using FieldType::dofs;
    using FieldType::locally_relevant_dofs;
    using FieldType::old_solution;

    /// Carried c on the new mesh: its positivity repaired.
    void
    transferred(TrilinosWrappers::MPI::Vector &distributed) override;

    struct Node
    {
      Point<dim>                                position;
      typename Triangulation<dim>::active_cell_iterator cell;
      // c's components in the stored order (c_xx, c_xy, c_yy in 2D)
      std::array<types::global_dof_index, n_symmetric_components<dim>> dofs;
      SymmetricTensor<2, dim>                   foot_conformation;
      Tensor<2, dim>                          foot_velocity_gradient; // Order = 2
      double                                  foot_volume_fraction = 0; // Order = 2
      // On a no-slip wall (Wall velocity gradient = no-slip shear): the
      // unit normal, the mean of its wall faces'; else 0.
      Tensor<1, dim>                          wall_normal;
    };

    /// c of @p node in @p vector.
    static SymmetricTensor<2, dim>
    conformation_at(const Node &node, const TrilinosWrappers::MPI::Vector &vector);

    /// Write @p c as @p node's values in @p vector.
    static void
    set_conformation(const Node &                   node,
                     const SymmetricTensor<2, dim> &c,
                     TrilinosWrappers::MPI::Vector &vector);

    /// ‖τ − τ(@p previous)‖_L2 / ‖τ‖_L2 (Frobenius norms) for the current c.
    double
    relative_change(const TrilinosWrappers::MPI::Vector &previous) const;

    /// Raise the smallest eigenvalue of c to Stress/Positivity floor at the
    /// nodes of @p distributed below it (after Q2 interpolation); returns
    /// their number over all ranks. Collective.
    unsigned int
    repair_positivity(TrilinosWrappers::MPI::Vector &distributed) const;

    /// Call @p on_cell(cell, support points, node of each support point or
    /// invalid) for every cell that holds owned nodes, ghost cells included.
    template <typename CellFunction>
    void
    for_each_node_on_cells(const CellFunction &on_cell) const;

    /// Order = 2: ∇u^n and φ^n at the feet of the last compute() of @p feet.
    void
    at_feet_for_second_order(const DepartureFeet<dim> &feet, const StokesFlow<dim> &stokes);

    /// ∇u at every node, averaged over the node's cells.
    std::vector<Tensor<2, dim>>
    nodal_velocity_gradient(const StokesFlow<dim> &stokes) const;

    /// Node::wall_normal of every node (after the nodes are set up).
    void
    find_wall_normals();

    /// φ at every node.
    std::vector<double>
    nodal_volume_fraction() const;

    const parallel::distributed::Triangulation<dim> &triangulation;
    const Parameters &                             parameters;
    const Model &                                  model;
    const BoundaryConditions<dim> &boundary_conditions;
    const unsigned int        order;

    const FESystem<dim>             fe;
    const Quadrature<dim>           stokes_quadrature;
    const VolumeFraction<dim> &     volume_fraction;
    std::vector<Node>             nodes;
    std::vector<unsigned int>     node_of_owned_dof; // component-0 dofs only
    std::array<unsigned int, Utilities::pow(3, dim)> lexicographic_node; // [ix + 3 iy (+ 9 iz)]

    std::unique_ptr<DataPostprocessor<dim>>      tau_postprocessor;
    unsigned int                               positivity_fixes = 0;
    unsigned int                               remote_feet      = 0;
    unsigned int                               transfer_repairs   = 0;
    unsigned int                               constraint_repairs = 0;
    double                                     step_error         = 0;
  };
} // namespace viscofilm

#endif
