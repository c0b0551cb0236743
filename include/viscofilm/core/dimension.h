// How a symmetric dim×dim tensor (c, τ) is stored as a list of components.
// Every class is a template on the space dimension dim, instantiated for 2
// and 3 (VISCOFILM_INSTANTIATE at the end of each .cc); main() reads
// Geometry/Dimension and runs Problem<2> or Problem<3>.
#ifndef viscofilm_dimension_h
#define viscofilm_dimension_h

#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <string>
#include <utility>

namespace viscofilm
{
  /// Independent components of a symmetric dim×dim tensor (c, τ).
  template <int dim>
  constexpr unsigned int n_symmetric_components = dim * (dim + 1) / 2;

  /// Row and column of the stored component @p k. The order is the upper
  /// triangle row by row: (xx, xy, yy) in 2D, (xx, xy, xz, yy, yz, zz) in 3D
  /// (c's FE components, the Stress expressions, the tau_* output fields).
  template <int dim>
  inline std::pair<unsigned int, unsigned int>
  symmetric_component(const unsigned int k)
  {
    unsigned int row = 0, first = 0; // first: the index of (row, row)
    while (k >= first + dim - row)
      first += dim - row++;
    return {row, row + (k - first)};
  }

  /// "xx", "xy", ... of the stored component @p k.
  template <int dim>
  inline std::string
  symmetric_component_name(const unsigned int k)
  {
    const auto [i, j] = symmetric_component<dim>(k);
    return {char('x' + i), char('x' + j)};
  }

  /// The stored component @p k of @p t.
  template <int dim>
  inline double
  stored_component(const dealii::SymmetricTensor<2, dim> &t, const unsigned int k)
  {
    const auto [i, j] = symmetric_component<dim>(k);
    return t[i][j];
  }

  /// The tensor whose stored components are v[0], ..., v[n_symmetric_components − 1].
  template <int dim, class Values>
  dealii::SymmetricTensor<2, dim>
  symmetric_tensor(const Values &v)
  {
    dealii::SymmetricTensor<2, dim> t;
    for (unsigned int k = 0; k < n_symmetric_components<dim>; ++k)
      {
        const auto [i, j] = symmetric_component<dim>(k);
        t[i][j]           = v[k];
      }
    return t;
  }

  /// The smallest eigenvalue of a symmetric tensor (c's positivity).
  template <int dim>
  inline double
  smallest_eigenvalue(const dealii::SymmetricTensor<2, dim> &t)
  {
    if constexpr (dim == 2)
      {
        // Closed form: exact to round-off where the general solver iterates.
        const double mean = 0.5 * (t[0][0] + t[1][1]);
        const double half = 0.5 * (t[0][0] - t[1][1]);
        return mean - std::sqrt(half * half + t[0][1] * t[0][1]);
      }
    else
      return dealii::eigenvalues(t)[dim - 1]; // in descending order
  }

  /// f(t) = Σ_i f(λ_i) v_i ⊗ v_i over the eigenpairs (λ_i, v_i) of a
  /// symmetric tensor (log c and exp of it for Stress/Foot interpolation).
  template <int dim, class ScalarFunction>
  dealii::SymmetricTensor<2, dim>
  symmetric_function(const dealii::SymmetricTensor<2, dim> &t, const ScalarFunction &f)
  {
    dealii::SymmetricTensor<2, dim> result;
    for (const auto &[value, vector] : dealii::eigenvectors(t))
      result += f(value) * dealii::symmetrize(dealii::outer_product(vector, vector));
    return result;
  }
} // namespace viscofilm

/// The explicit instantiations at the end of each .cc file: a class
/// template's members defined there for dim = 2 and 3, and any function
/// template through a macro INSTANTIATE(dim) of the file.
#define VISCOFILM_INSTANTIATE(Class) \
  template class Class<2>;           \
  template class Class<3>;
#define VISCOFILM_FOR_EACH_DIM(Macro) Macro(2) Macro(3)

#endif
