// The 3D path of Initial conditions/Image at unit level (tests/image/
// half_ball_3d.prm runs it through Problem<3>): the 10-page TIFF
// half_ball_stack.tif (geometry/make_images.py), a half-ball of radius
// R = 0.25 on 20 × 20 pixels per page, pages 0.05 apart: sections parallel to
// the bottom wall stacked along y, so the ball is centred at (0.5, 0, 0.5) on
// 20 × 10 × 20 voxels of 0.05, sampled by ImageVolumeFraction<3>.
#include <viscofilm/biofilm/image.h>

#include <cmath>
#include <iostream>

namespace
{
  int n_failed = 0;

  void
  check(const bool condition, const std::string &what)
  {
    std::cout << (condition ? "ok     " : "FAILED ") << what << std::endl;
    n_failed += condition ? 0 : 1;
  }
} // namespace


int
main(int argc, char *argv[])
{
  using namespace viscofilm;
  if (argc != 2)
    {
      std::cerr << "usage: image_3d half_ball_stack.tif" << std::endl;
      return 2;
    }
  const double phi_b = 0.1, voxel = 0.05, R = 0.25;
  const auto   slices = read_grayscale_slices(argv[1], "File");
  check(slices.size() == 10 && slices[0].width == 20 && slices[0].height == 20 &&
          slices[0].bit_depth == 8,
        "10 pages of 20 × 20 8-bit pixels");
  Table<3, double> voxels = pixel_table<3>(
    slices, [&](const double intensity) { return intensity > 0.5 ? phi_b : 0.; }, "File");
  double voxel_sum = 0;
  for (unsigned int i = 0; i < 20; ++i)
    for (unsigned int j = 0; j < 10; ++j)
      for (unsigned int k = 0; k < 20; ++k)
        voxel_sum += voxels(i, j, k) * std::pow(voxel, 3);
  const ImageVolumeFraction<3> phi(std::move(voxels), {{voxel, voxel, voxel}}, Point<3>());

  // The trilinear interpolant between voxel centres (constant beyond the
  // outer ones) is trilinear on each box between voxel centres and edges:
  // the midpoint rule on those boxes integrates it exactly.
  double integral = 0;
  const double h = voxel / 2;
  for (unsigned int i = 0; i < 40; ++i)
    for (unsigned int j = 0; j < 20; ++j)
      for (unsigned int k = 0; k < 40; ++k)
        integral += phi.value(Point<3>((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h)) *
                    h * h * h;
  const double ball = phi_b * 2 * M_PI * R * R * R / 3;
  std::cout << "∫φ = " << integral << ", Σ φ_voxel × voxel volume = " << voxel_sum
            << ", 0.1 · 2πR³/3 = " << ball << std::endl;
  check(std::abs(integral - voxel_sum) < 1e-12 * voxel_sum,
        "∫φ equals the voxels' sum to round-off");
  // The voxels' error: the half-ball's surface 2πR² times a tenth of a voxel
  // (measured: 1.8e-4 of 3.27e-3, R = 5 voxels).
  check(std::abs(voxel_sum - ball) < phi_b * 2 * M_PI * R * R * voxel / 10,
        "Σ φ_voxel × voxel volume equals the half-ball's 0.1 · 2πR³/3 to the "
        "voxels' error");
  // The first page is the lowest slice: at y = 0.025 the ball's radius is
  // 0.249, at y = 0.225 it is 0.109. The ball is symmetric in z (the rows),
  // so probe the slice's shape in x only.
  check(phi.value(Point<3>(0.72, 0.025, 0.5)) == phi_b &&
          phi.value(Point<3>(0.72, 0.225, 0.5)) == 0,
        "the first page is the lowest slice");
  check(phi.value(Point<3>(0.5, 0.6, 0.5)) == 0 && phi.value(Point<3>(1.2, 0.1, 0.5)) == 0,
        "φ = 0 outside the image");
  return n_failed == 0 ? 0 : 1;
}
