// The velocity block's matrix-free operator of the GMG preconditioner,
// (m u, v) + (2 eta D(u), D(v)) with Q2 velocities, applied with deal.II's
// VectorizedArray<double, WIDTH>. Debian's deal.II 9.4.1 is configured
// without SIMD (DEAL_II_VECTORIZATION_WIDTH_IN_BITS = 0), so WIDTH > 1
// raises that macro for this program alone and instantiates the matrix-free
// templates the library does not hold; a measurement, not production code.
#include <deal.II/base/config.h>
#if WIDTH > 1
#  undef DEAL_II_VECTORIZATION_WIDTH_IN_BITS
#  define DEAL_II_VECTORIZATION_WIDTH_IN_BITS (64 * WIDTH)
#endif

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>

#if WIDTH > 1
#  include <deal.II/matrix_free/mapping_info.templates.h>
#  include <deal.II/matrix_free/matrix_free.templates.h>
#  include <deal.II/matrix_free/shape_info.templates.h>
#  define FE_EVAL_FACTORY_DEGREE_MAX 2
#  include <deal.II/matrix_free/evaluation_template_factory.templates.h>
// deal.II 9.4 gives the cell and face factories' templates one include guard.
#  undef dealii_matrix_free_evaluation_template_factory_templates_h
#  include <deal.II/matrix_free/evaluation_template_face_factory.templates.h>
#  include <deal.II/matrix_free/evaluation_template_factory_hanging_nodes.templates.h>
#endif

#include <functional>
#include <iostream>
#include <string>

using namespace dealii;
using Number = VectorizedArray<double, WIDTH>;
using VectorType = LinearAlgebra::distributed::Vector<double>;

#if WIDTH > 1
#  define INSTANTIATE(dim)                                                                  \
    template class dealii::MatrixFree<dim, double, Number>;                                 \
    template struct dealii::internal::MatrixFreeFunctions::MappingInfo<dim, double, Number>; \
    template struct dealii::internal::FEEvaluationFactory<dim, Number>;                     \
    template struct dealii::internal::FEFaceEvaluationFactory<dim, Number>;                 \
    template struct dealii::internal::FEEvaluationHangingNodesFactory<dim, double, Number>;
template struct dealii::internal::MatrixFreeFunctions::ShapeInfo<Number>;
INSTANTIATE(2)
INSTANTIATE(3)
#endif

// The best time of one operator application over 5 rounds of 20.
template <int dim>
void
run(const unsigned int refinement)
{
  Triangulation<dim> triangulation;
  GridGenerator::hyper_cube(triangulation);
  triangulation.refine_global(refinement);
  const FESystem<dim> fe(FE_Q<dim>(2), dim);
  DoFHandler<dim>     dofs(triangulation);
  dofs.distribute_dofs(fe);
  AffineConstraints<double> constraints;
  constraints.close();

  using MF = MatrixFree<dim, double, Number>;
  MF                          matrix_free;
  typename MF::AdditionalData data;
  data.tasks_parallel_scheme = MF::AdditionalData::none;
  data.mapping_update_flags  = update_values | update_gradients | update_JxW_values;
  matrix_free.reinit(MappingQ1<dim>(), dofs, constraints, QGauss<1>(3), data);

  // A viscosity that jumps between cells and points, by cell (not by
  // batch, whose cells depend on the width): the same operator at every width.
  const unsigned int n_points = Utilities::pow(3, dim);
  Table<2, Number>   viscosity(matrix_free.n_cell_batches(), n_points);
  for (unsigned int batch = 0; batch < matrix_free.n_cell_batches(); ++batch)
    for (unsigned int v = 0; v < matrix_free.n_active_entries_per_cell_batch(batch); ++v)
      {
        const unsigned int cell = matrix_free.get_cell_iterator(batch, v)->active_cell_index();
        for (unsigned int q = 0; q < n_points; ++q)
          viscosity(batch, q)[v] = 1.0 + 50.0 * ((cell + q) % 2);
      }

  VectorType src, dst;
  matrix_free.initialize_dof_vector(src);
  matrix_free.initialize_dof_vector(dst);
  for (unsigned int i = 0; i < src.locally_owned_size(); ++i)
    src.local_element(i) = std::sin(0.1 * i);

  const std::function<void(const MF &, VectorType &, const VectorType &,
                           const std::pair<unsigned int, unsigned int> &)>
    cells = [&](const MF &mf, VectorType &out, const VectorType &in,
                const std::pair<unsigned int, unsigned int> &range) {
      FEEvaluation<dim, 2, 3, dim, double, Number> velocity(mf);
      for (unsigned int cell = range.first; cell < range.second; ++cell)
        {
          velocity.reinit(cell);
          velocity.read_dof_values(in);
          velocity.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
          for (unsigned int q = 0; q < velocity.n_q_points; ++q)
            {
              velocity.submit_symmetric_gradient(viscosity(cell, q) *
                                                   velocity.get_symmetric_gradient(q),
                                                 q);
              velocity.submit_value(10.0 * velocity.get_value(q), q);
            }
          velocity.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
          velocity.distribute_local_to_global(out);
        }
    };

  double best = 1e300;
  for (unsigned int round = 0; round < 5; ++round)
    {
      Timer timer;
      for (unsigned int i = 0; i < 20; ++i)
        matrix_free.cell_loop(cells, dst, src, true);
      best = std::min(best, timer.wall_time() / 20);
    }
  // The norm checks that both widths compute the same operator.
  std::cout << "simd width=" << WIDTH << " dim=" << dim << " dofs=" << dofs.n_dofs()
            << " apply_ms=" << best * 1e3 << " norm=" << dst.l2_norm() << std::endl;
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const int          dim        = (argc > 1 ? std::stoi(argv[1]) : 2);
  const unsigned int refinement = (argc > 2 ? std::stoi(argv[2]) : (dim == 2 ? 7 : 4));
  if (dim == 2)
    run<2>(refinement);
  else
    run<3>(refinement);
}
