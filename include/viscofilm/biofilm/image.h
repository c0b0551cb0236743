// A biofilm from an image: 8- or 16-bit grayscale PNG or TIFF files (a stack
// of slices or a multi-page TIFF for a 3D volume) read by libpng and libtiff,
// their intensities mapped to φ and sampled onto the mesh (doc/images.md).
#ifndef viscofilm_image_h
#define viscofilm_image_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/function.h>
#include <deal.II/base/function_lib.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <viscofilm/core/dimension.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace viscofilm
{
  using namespace dealii;

  /// One grayscale image as stored: rows from the top, intensities scaled by
  /// the largest value of the bit depth to [0, 1].
  struct GrayscaleSlice
  {
    unsigned int        width     = 0;
    unsigned int        height    = 0;
    unsigned int        bit_depth = 0;
    std::vector<double> intensity; // intensity[row * width + column]
  };

  /**
   * The slices of @p file: one for a PNG, one per page for a TIFF. The format
   * is told by the file's first bytes, not its name. Throws ExcInput naming
   * @p parameter for a missing or unreadable file, another format, colour or
   * an alpha channel, or a bit depth other than 8 and 16.
   */
  std::vector<GrayscaleSlice>
  read_grayscale_slices(const std::string &file, const std::string &parameter);

  /**
   * φ sampled from an image or a stack of slices: a pixel (voxel) grid of
   * edge pixel_size[d] whose lower-left corner is @p origin, indexed as
   * pixel_table() orders it. φ is
   * bilinear (trilinear) between pixel centres, constant over the outer half
   * pixels, and 0 outside the image: so its integral over the image is
   * exactly Σ φ_pixel × pixel area (volume).
   */
  template <int spacedim>
  class ImageVolumeFraction : public Function<spacedim>
  {
  public:
    /// @p phi: φ of each pixel, indexed [x][y] (and [z]) from the lower left.
    ImageVolumeFraction(Table<spacedim, double>                  phi,
                        const std::array<double, spacedim> &     pixel_size,
                        const Point<spacedim> &                  origin);

    double
    value(const Point<spacedim> &p, const unsigned int component = 0) const override;

    /// The box the image covers.
    const BoundingBox<spacedim> &
    extent() const;

  private:
    BoundingBox<spacedim>                         box;
    Functions::InterpolatedUniformGridData<spacedim> interpolation;
  };

  /**
   * The slices' pixels as a table indexed [x][y] (and [z] for spacedim = 3)
   * from the lower left, each mapped by @p to_phi. In 2D @p slices must be
   * one image: columns along x, rows along y upwards (the file's first row
   * is the top one). In 3D the slices, of equal size, are sections parallel
   * to the bottom wall stacked along y upwards (the first is the lowest),
   * each with columns along x and rows along z (first row at the lowest z).
   */
  template <int spacedim>
  Table<spacedim, double>
  pixel_table(const std::vector<GrayscaleSlice> &slices,
              const std::function<double(double)> &to_phi,
              const std::string &                  parameter);

  /**
   * Initial conditions/Image: which file, where it lies, and how its
   * intensities become φ; parse_parameters() reads the file and checks that
   * it covers the biofilm in the domain.
   */
  template <int dim>
  class BiofilmImage
  {
  public:
    /// Declares the subsection Image in the current subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Reads the subsection Image of the current subsection and the image.
    /// @p directory: the parameter file's, which a relative File is read
    /// from; @p domain: the mesh's bounding box, whose lowest side in the
    /// last coordinate is the wall the biofilm grows on.
    void
    parse_parameters(ParameterHandler &       prm,
                     const std::string &      directory,
                     const BoundingBox<dim> & domain);

    /// φ at t = 0 (parse_parameters() first).
    const Function<dim> &
    volume_fraction() const;

    /// The smallest edge of a pixel.
    double
    smallest_pixel() const;

    /// φ of a pixel of normalised intensity @p intensity in [0, 1].
    double
    phi_of_intensity(const double intensity) const;

  private:
    enum class Map
    {
      threshold,
      linear
    };

    std::string           file;
    std::array<double, dim> pixel_size{};
    Point<dim>            origin;
    Map                   map       = Map::threshold;
    double                threshold = 0.5;
    std::array<double, 2> intensity_range{{0, 1}};
    double                biofilm_phi = 0.1;

    std::unique_ptr<ImageVolumeFraction<dim>> phi;
  };
} // namespace viscofilm

#endif
