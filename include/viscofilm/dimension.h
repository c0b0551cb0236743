// The space dimension. The code is written for `dim`; a later step turns this
// constant into a template parameter and instantiates 2 and 3 (issue 12).
#ifndef viscofilm_dimension_h
#define viscofilm_dimension_h

namespace viscofilm
{
  constexpr int dim = 2;

  /// Independent components of a symmetric dim×dim tensor (c, τ).
  constexpr unsigned int n_symmetric_components = dim * (dim + 1) / 2;
} // namespace viscofilm

#endif
