#include <deal.II/base/utilities.h>

#include <viscofilm/biofilm/image.h>
#include <viscofilm/core/input.h>

#include <png.h>
#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace viscofilm
{
  namespace
  {
    /// The largest intensity of @p bit_depth bits, which becomes 1.
    double
    full_scale(const unsigned int bit_depth)
    {
      return std::ldexp(1.0, bit_depth) - 1;
    }


    std::string
    no_grayscale(const std::string &what)
    {
      return " is " + what +
             "; 8- or 16-bit grayscale (one channel, no alpha) is needed "
             "(convert it first, e.g. ImageMagick: convert IN -colorspace "
             "Gray -alpha off OUT.png)";
    }


    struct PngError
    {
      std::string message;
    };


    void
    png_error_handler(png_structp png, png_const_charp message)
    {
      static_cast<PngError *>(png_get_error_ptr(png))->message = message;
      png_longjmp(png, 1);
    }


    void
    png_warning_handler(png_structp, png_const_charp)
    {}


    /// libpng reports errors by longjmp: read the whole image in this
    /// function, with nothing in it that a longjmp would skip destroying,
    /// and return libpng's message ("" on success).
    std::string
    read_png_rows(std::FILE *stream, GrayscaleSlice &slice, int &color_type)
    {
      PngError    error;
      png_structp png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, png_error_handler,
                               png_warning_handler);
      png_infop info = png_create_info_struct(png);
      if (setjmp(png_jmpbuf(png)))
        {
          png_destroy_read_struct(&png, &info, nullptr);
          return error.message;
        }
      png_init_io(png, stream);
      png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
      slice.width     = png_get_image_width(png, info);
      slice.height    = png_get_image_height(png, info);
      slice.bit_depth = png_get_bit_depth(png, info);
      color_type      = png_get_color_type(png, info);
      if (color_type == PNG_COLOR_TYPE_GRAY &&
          (slice.bit_depth == 8 || slice.bit_depth == 16))
        {
          const png_bytepp   rows  = png_get_rows(png, info);
          const unsigned int bytes = slice.bit_depth / 8;
          const double       scale = full_scale(slice.bit_depth);
          slice.intensity.resize(std::size_t(slice.width) * slice.height);
          for (unsigned int r = 0; r < slice.height; ++r)
            for (unsigned int c = 0; c < slice.width; ++c)
              {
                const png_bytep sample = rows[r] + std::size_t(c) * bytes;
                // PNG stores 16-bit samples big-endian.
                const unsigned int raw =
                  bytes == 1 ? sample[0] : (sample[0] << 8 | sample[1]);
                slice.intensity[std::size_t(r) * slice.width + c] = raw / scale;
              }
        }
      png_destroy_read_struct(&png, &info, nullptr);
      return "";
    }


    GrayscaleSlice
    read_png(const std::string &file, const std::string &where)
    {
      std::FILE *stream = std::fopen(file.c_str(), "rb");
      check_input(stream != nullptr, where + " cannot be opened");
      GrayscaleSlice    slice;
      int               color_type = 0;
      const std::string error      = read_png_rows(stream, slice, color_type);
      std::fclose(stream);
      check_input(error.empty(), where + " is not a readable PNG file: " + error);
      check_input(color_type == PNG_COLOR_TYPE_GRAY,
                  where + no_grayscale(color_type == PNG_COLOR_TYPE_GRAY_ALPHA ?
                                         "grayscale with an alpha channel" :
                                         "a colour PNG"));
      check_input(slice.bit_depth == 8 || slice.bit_depth == 16,
                  where + no_grayscale("a " + std::to_string(slice.bit_depth) +
                                       "-bit grayscale PNG"));
      return slice;
    }


    int
    tiff_error_handler(TIFF *, void *message, const char *module, const char *format, va_list arguments)
    {
      char text[512];
      std::vsnprintf(text, sizeof(text), format, arguments);
      *static_cast<std::string *>(message) =
        std::string(module != nullptr ? module : "") + ": " + text;
      return 1;
    }


    int
    tiff_warning_handler(TIFF *, void *, const char *, const char *, va_list)
    {
      return 1; // unknown tags and the like: not the user's concern
    }


    /// The current page (TIFF directory) of @p tiff.
    GrayscaleSlice
    read_tiff_page(TIFF *tiff, const std::string &where, const std::string &error)
    {
      uint32_t width = 0, height = 0;
      uint16_t samples = 1, bits = 1, photometric = PHOTOMETRIC_MINISBLACK,
               format = SAMPLEFORMAT_UINT;
      TIFFGetField(tiff, TIFFTAG_IMAGEWIDTH, &width);
      TIFFGetField(tiff, TIFFTAG_IMAGELENGTH, &height);
      TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLESPERPIXEL, &samples);
      TIFFGetFieldDefaulted(tiff, TIFFTAG_BITSPERSAMPLE, &bits);
      TIFFGetField(tiff, TIFFTAG_PHOTOMETRIC, &photometric);
      TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLEFORMAT, &format);
      const bool gray = photometric == PHOTOMETRIC_MINISBLACK ||
                        photometric == PHOTOMETRIC_MINISWHITE;
      check_input(gray && samples == 1,
                  where + no_grayscale(samples == 2 && gray ?
                                         "grayscale with an alpha channel" :
                                         "a colour TIFF"));
      check_input((bits == 8 || bits == 16) && format == SAMPLEFORMAT_UINT,
                  where + no_grayscale("a TIFF of " + std::to_string(bits) +
                                       "-bit" +
                                       (format == SAMPLEFORMAT_UINT ?
                                          "" :
                                          " signed or floating-point") +
                                       " samples"));
      check_input(!TIFFIsTiled(tiff),
                  where + " is a tiled TIFF; save it with strips (the "
                          "default of most programs)");

      GrayscaleSlice slice;
      slice.width     = width;
      slice.height    = height;
      slice.bit_depth = bits;
      slice.intensity.resize(std::size_t(width) * height);
      const double              scale = full_scale(bits);
      std::vector<unsigned char> row(TIFFScanlineSize(tiff));
      for (uint32_t r = 0; r < height; ++r)
        {
          check_input(TIFFReadScanline(tiff, row.data(), r) == 1,
                      where + ": row " + std::to_string(r) +
                        " cannot be read: " + error);
          for (uint32_t c = 0; c < width; ++c)
            {
              // libtiff returns samples in the machine's byte order.
              double raw = 0;
              if (bits == 8)
                raw = row[c];
              else
                {
                  uint16_t sample;
                  std::copy_n(&row[2 * std::size_t(c)], 2,
                              reinterpret_cast<unsigned char *>(&sample));
                  raw = sample;
                }
              // Min-is-white: 0 is white; we store brightness.
              if (photometric == PHOTOMETRIC_MINISWHITE)
                raw = scale - raw;
              slice.intensity[std::size_t(r) * width + c] = raw / scale;
            }
        }
      return slice;
    }


    std::vector<GrayscaleSlice>
    read_tiff(const std::string &file, const std::string &where)
    {
      std::string      error;
      TIFFOpenOptions *options = TIFFOpenOptionsAlloc();
      TIFFOpenOptionsSetErrorHandlerExtR(options, tiff_error_handler, &error);
      TIFFOpenOptionsSetWarningHandlerExtR(options, tiff_warning_handler, nullptr);
      TIFF *tiff = TIFFOpenExt(file.c_str(), "r", options);
      TIFFOpenOptionsFree(options);
      check_input(tiff != nullptr, where + " is not a readable TIFF file: " + error);
      std::vector<GrayscaleSlice> slices;
      try
        {
          do
            slices.push_back(read_tiff_page(
              tiff,
              where + (slices.empty() ? "" : " page " + std::to_string(slices.size() + 1)),
              error));
          while (TIFFReadDirectory(tiff) == 1);
        }
      catch (...)
        {
          TIFFClose(tiff);
          throw;
        }
      TIFFClose(tiff);
      return slices;
    }
  } // namespace


  std::vector<GrayscaleSlice>
  read_grayscale_slices(const std::string &file, const std::string &parameter)
  {
    const std::string where = parameter + " \"" + file + "\"";
    check_input(std::filesystem::is_regular_file(file), where + " does not exist");
    std::ifstream stream(file, std::ios::binary);
    char          magic[8] = {};
    stream.read(magic, sizeof(magic));
    const std::string head(magic, stream.gcount());

    std::vector<GrayscaleSlice> slices;
    if (head.size() == 8 &&
        png_sig_cmp(reinterpret_cast<png_const_bytep>(head.data()), 0, 8) == 0)
      slices.push_back(read_png(file, where));
    else if (head.rfind(std::string("II*\0", 4), 0) == 0 ||
             head.rfind(std::string("MM\0*", 4), 0) == 0 ||
             head.rfind(std::string("II+\0", 4), 0) == 0 ||
             head.rfind(std::string("MM\0+", 4), 0) == 0)
      slices = read_tiff(file, where);
    else
      check_input(false,
                  where + " is neither a PNG nor a TIFF file (told by its "
                          "first bytes, not its name)");
    for (const GrayscaleSlice &slice : slices)
      check_input(slice.width >= 2 && slice.height >= 2,
                  where + " has " + std::to_string(slice.width) + " × " +
                    std::to_string(slice.height) +
                    " pixels; at least 2 × 2 are needed");
    return slices;
  }


  template <int spacedim>
  Table<spacedim, double>
  pixel_table(const std::vector<GrayscaleSlice> &  slices,
              const std::function<double(double)> &to_phi,
              const std::string &                  parameter)
  {
    static_assert(spacedim == 2 || spacedim == 3, "images are 2D or 3D");
    check_input(spacedim == 3 || slices.size() == 1,
                parameter + " has " + std::to_string(slices.size()) +
                  " slices (pages or files); a 2D run needs one image");
    check_input(slices.size() >= (spacedim == 3 ? 2 : 1),
                parameter + ": a 3D run needs at least 2 slices");
    const unsigned int width = slices[0].width, height = slices[0].height;
    // 2D: columns along x, rows along y upwards. 3D: the slices are
    // sections parallel to the wall (a confocal stack), stacked along y
    // upwards from the wall; in each, columns along x and rows along z
    // (the section seen from above, x to the right).
    TableIndices<spacedim> size;
    size[0] = width;
    if constexpr (spacedim == 2)
      size[1] = height;
    else
      {
        size[1] = slices.size();
        size[2] = height;
      }
    Table<spacedim, double> phi;
    phi.reinit(size);
    for (unsigned int k = 0; k < slices.size(); ++k)
      {
        check_input(slices[k].width == width && slices[k].height == height,
                    parameter + ": slice " + std::to_string(k + 1) + " has " +
                      std::to_string(slices[k].width) + " × " +
                      std::to_string(slices[k].height) + " pixels, slice 1 " +
                      std::to_string(width) + " × " + std::to_string(height));
        for (unsigned int r = 0; r < height; ++r)
          for (unsigned int c = 0; c < width; ++c)
            {
              TableIndices<spacedim> pixel;
              pixel[0] = c;
              if constexpr (spacedim == 2)
                pixel[1] = height - 1 - r; // rows go down, y goes up
              else
                {
                  pixel[1] = k;
                  pixel[2] = r;
                }
              phi(pixel) = to_phi(slices[k].intensity[std::size_t(r) * width + c]);
            }
      }
    return phi;
  }


  template <int spacedim>
  ImageVolumeFraction<spacedim>::ImageVolumeFraction(
    Table<spacedim, double>             phi,
    const std::array<double, spacedim> &pixel_size,
    const Point<spacedim> &             origin)
    : box([&] {
      Point<spacedim> top = origin;
      for (unsigned int d = 0; d < spacedim; ++d)
        top[d] += phi.size(d) * pixel_size[d];
      return std::make_pair(origin, top);
    }())
    , interpolation(
        // the pixel centres
        [&] {
          std::array<std::pair<double, double>, spacedim> centres;
          for (unsigned int d = 0; d < spacedim; ++d)
            centres[d] = {origin[d] + 0.5 * pixel_size[d],
                          origin[d] + (phi.size(d) - 0.5) * pixel_size[d]};
          return centres;
        }(),
        [&] {
          std::array<unsigned int, spacedim> intervals;
          for (unsigned int d = 0; d < spacedim; ++d)
            intervals[d] = phi.size(d) - 1;
          return intervals;
        }(),
        phi)
  {}


  template <int spacedim>
  double
  ImageVolumeFraction<spacedim>::value(const Point<spacedim> &p,
                                       const unsigned int) const
  {
    // Beyond the centres of the outer pixels the interpolation is constant.
    return box.point_inside(p) ? interpolation.value(p) : 0.;
  }


  template <int spacedim>
  const BoundingBox<spacedim> &
  ImageVolumeFraction<spacedim>::extent() const
  {
    return box;
  }


  template <int dim>
  void
  BiofilmImage<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Image");
    prm.declare_entry("File",
                      "",
                      Patterns::Anything(),
                      "The image φ is read from when Volume fraction = image: "
                      "an 8- or 16-bit grayscale PNG or TIFF, relative to the "
                      "parameter file's directory. Columns go along x, rows "
                      "along y upwards (the image's top row is the highest). "
                      "A 3D run reads a stack of sections parallel to the "
                      "bottom wall, stacked along y upwards (lowest first: "
                      "the pages of a multi-page TIFF or files separated by "
                      "';'); in each, columns go along x and rows along z.");
    prm.declare_entry("Pixel size",
                      "0.01",
                      Patterns::Anything(),
                      "Edge of a pixel in the run's length unit (Model/Units), "
                      "> 0: one number (square pixels) or one per direction "
                      "\"dx, dy\" (3D: \"dx, dy, dz\", dy the slices' spacing).");
    prm.declare_entry("Origin",
                      dim == 2 ? "0, 0" : "0, 0, 0",
                      Patterns::Anything(),
                      "Where the lower-left corner of the image's lower-left "
                      "pixel lies, \"x, y\" (3D: \"x, y, z\", the corner of the first row and column of the lowest slice). The image must reach down to the "
                      "domain's lowest y (the wall the biofilm grows on).");
    prm.declare_entry("Map",
                      "threshold",
                      Patterns::Selection("threshold|linear"),
                      "How a pixel's intensity I (scaled to [0, 1]: 255 or "
                      "65535 is 1) becomes φ: threshold (φ = Biofilm volume "
                      "fraction where I > Threshold, 0 elsewhere) or linear (φ "
                      "= Biofilm volume fraction × (I − I0)/(I1 − I0), clipped "
                      "to [0, Biofilm volume fraction]; I1 < I0 for dark "
                      "biofilm on a bright background).");
    prm.declare_entry("Threshold",
                      "0.5",
                      Patterns::Double(0, 1),
                      "Intensity in [0, 1) above which a pixel is biofilm (Map "
                      "= threshold).");
    prm.declare_entry("Intensity range",
                      "0, 1",
                      Patterns::Anything(),
                      "\"I0, I1\": the intensities mapped to φ = 0 and φ = "
                      "Biofilm volume fraction (Map = linear), I0 ≠ I1.");
    prm.declare_entry("Biofilm volume fraction",
                      "0.1",
                      Patterns::Double(0, 1),
                      "φ of a pixel of biofilm, in (0, 1] (the thesis: 0.1).");
    prm.leave_subsection();
  }


  template <int dim>
  void
  BiofilmImage<dim>::parse_parameters(ParameterHandler & prm,
                                 const std::string &     directory,
                                 const BoundingBox<dim> &domain)
  {
    const std::string section = "Initial conditions/Image/";
    prm.enter_subsection("Image");
    file = prm.get("File");
    const std::string pixel_text = prm.get("Pixel size");
    const std::string origin_text = prm.get("Origin");
    map = prm.get("Map") == "threshold" ? Map::threshold : Map::linear;
    threshold = prm.get_double("Threshold");
    const std::string range_text = prm.get("Intensity range");
    biofilm_phi = prm.get_double("Biofilm volume fraction");
    prm.leave_subsection();

    check_input(!file.empty(),
                section + "File: Volume fraction = image needs an image file");
    std::vector<double> sizes;
    for (const std::string &item : Utilities::split_string_list(pixel_text))
      {
        double size = 0;
        try
          {
            size = Utilities::string_to_double(item);
          }
        catch (...)
          {}
        sizes.push_back(size);
      }
    const bool one_or_each = sizes.size() == 1 || sizes.size() == dim;
    check_input(one_or_each &&
                  std::all_of(sizes.begin(), sizes.end(), [](double s) { return s > 0; }),
                section + "Pixel size must be one number > 0 or " +
                  std::to_string(dim) + " numbers > 0 separated by ',', got \"" +
                  pixel_text + "\"");
    for (unsigned int d = 0; d < dim; ++d)
      pixel_size[d] = sizes[sizes.size() == 1 ? 0 : d];
    origin = parse_point<dim>(origin_text, section + "Origin");
    const Point<2> range = parse_point<2>(range_text, section + "Intensity range");
    intensity_range      = {{range[0], range[1]}};
    check_input(map == Map::threshold || range[0] != range[1],
                section + "Intensity range \"I0, I1\" needs I0 ≠ I1, got \"" +
                  range_text + "\"");
    check_input(biofilm_phi > 0,
                section + "Biofilm volume fraction must be in (0, 1], got 0");

    // One file, or a stack of slice files (3D), each relative to the .prm.
    std::vector<GrayscaleSlice> slices;
    for (std::string path : Utilities::split_string_list(file, ';'))
      {
        if (std::filesystem::path(path).is_relative())
          path = (std::filesystem::path(directory) / path).string();
        for (GrayscaleSlice &slice : read_grayscale_slices(path, section + "File"))
          slices.push_back(std::move(slice));
      }
    Table<dim, double> pixels = pixel_table<dim>(
      slices,
      [this](const double intensity) { return phi_of_intensity(intensity); },
      section + "File \"" + file + "\"");
    phi = std::make_unique<ImageVolumeFraction<dim>>(pixels, pixel_size, origin);

    // The image must cover the biofilm in the domain: reach down to the wall
    // and have water on its other sides wherever they lie inside the domain
    // (biofilm there would be cut off by the image's edge).
    const BoundingBox<dim> &image = phi->extent();
    // The biofilm grows on the bottom wall, y min, in 2D and 3D.
    constexpr unsigned int height = 1;
    const double tolerance = 1e-10 * domain.side_length(height);
    const double wall = domain.get_boundary_points().first[height];
    check_input(image.get_boundary_points().first[height] <= wall + tolerance,
                section + "Origin: the image's lower edge at y = " +
                  to_text(origin[height]) +
                  " lies above the domain's bottom wall y = " + to_text(wall) +
                  "; the image must reach down to the wall");
    const char *axes = "xyz";
    bool any_biofilm = false;
    const TableIndices<dim> n = pixels.size();
    for (std::size_t flat = 0; flat < pixels.n_elements(); ++flat)
      {
        TableIndices<dim> pixel; // the table's last index runs fastest
        for (std::size_t d = dim, rest = flat; d-- > 0; rest /= n[d])
          pixel[d] = rest % n[d];
        if (pixels(pixel) == 0)
          continue;
        Point<dim> centre;
        for (unsigned int d = 0; d < dim; ++d)
          centre[d] = origin[d] + (pixel[d] + 0.5) * pixel_size[d];
        any_biofilm = any_biofilm || domain.point_inside(centre);
        for (unsigned int d = 0; d < dim; ++d)
          for (const unsigned int side : {0u, 1u})
            {
              if ((side == 0 ? pixel[d] != 0 : pixel[d] != n[d] - 1) ||
                  (side == 0 && d == height))
                continue;
              const double edge = side == 0 ? image.get_boundary_points().first[d] :
                                              image.get_boundary_points().second[d];
              const double domain_edge = side == 0 ?
                                           domain.get_boundary_points().first[d] :
                                           domain.get_boundary_points().second[d];
              const bool inside = side == 0 ? edge > domain_edge + tolerance :
                                              edge < domain_edge - tolerance;
              check_input(!inside,
                          section + "File \"" + file + "\": biofilm (φ > 0) reaches "
                          "the image's " + (side == 0 ? "lower" : "upper") + " " +
                          axes[d] + " edge at " + axes[d] + " = " + to_text(edge) +
                          ", inside the domain (" + axes[d] + " from " +
                          to_text(domain.get_boundary_points().first[d]) + " to " +
                          to_text(domain.get_boundary_points().second[d]) +
                          "); the image must cover the biofilm: enlarge it or "
                          "move Initial conditions/Image/Origin");
            }
      }
    check_input(any_biofilm,
                section + "File \"" + file + "\": no pixel inside the domain is "
                "biofilm (φ > 0); check Origin, Pixel size and the Map's "
                "Threshold or Intensity range");
  }


  template <int dim>
  double
  BiofilmImage<dim>::phi_of_intensity(const double intensity) const
  {
    if (map == Map::threshold)
      return intensity > threshold ? biofilm_phi : 0.;
    const double s =
      (intensity - intensity_range[0]) / (intensity_range[1] - intensity_range[0]);
    return biofilm_phi * std::clamp(s, 0., 1.);
  }


  template <int dim>
  double
  BiofilmImage<dim>::smallest_pixel() const
  {
    return *std::min_element(pixel_size.begin(), pixel_size.end());
  }


  template <int dim>
  const Function<dim> &
  BiofilmImage<dim>::volume_fraction() const
  {
    Assert(phi, ExcMessage("BiofilmImage::parse_parameters() first"));
    return *phi;
  }


  VISCOFILM_INSTANTIATE(BiofilmImage)
  template class ImageVolumeFraction<2>;
  template class ImageVolumeFraction<3>;
  template Table<2, double>
  pixel_table<2>(const std::vector<GrayscaleSlice> &,
                 const std::function<double(double)> &,
                 const std::string &);
  template Table<3, double>
  pixel_table<3>(const std::vector<GrayscaleSlice> &,
                 const std::function<double(double)> &,
                 const std::string &);
} // namespace viscofilm
