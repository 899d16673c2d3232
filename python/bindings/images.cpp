// Images between NumPy and Dermis: files, comparison statistics, false-colour error
// maps, and the subsurface-object mask.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "dermis/render/film.h"
#include "dermis/render/image.h"
#include "dermis/render/image_compare.h"
#include "dermis/render/object_mask.h"
#include "dermis/render/scene_assembly.h"
#include "scene.h"

namespace py = pybind11;

namespace dermis::python {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

Image to_image(const FloatArray& a, const char* what) {
  if (a.ndim() != 3 || a.shape(2) != 3)
    throw py::value_error(fmt::format("{}: expected an array of shape (height, width, 3), got {} dimensions{}", what,
                                      a.ndim(), a.ndim() == 3 ? fmt::format(" with {} channels", a.shape(2)) : ""));
  Image img;
  img.width = int(a.shape(1));
  img.height = int(a.shape(0));
  img.pixels.assign(a.data(), a.data() + a.size());
  return img;
}

py::array_t<float> to_array(const Image& img) {
  py::array_t<float> a({py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(3)});
  std::copy(img.pixels.begin(), img.pixels.end(), a.mutable_data());
  return a;
}

py::tuple rgb(RGB c) { return py::make_tuple(c[0], c[1], c[2]); }

}  // namespace

void bind_images(py::module_& m) {
  m.def(
      "read_image", [](const std::string& path) { return to_array(read_image(path)); }, py::arg("path"),
      "Reads an image (any format OpenImageIO reads) as float32 (height, width, 3) linear RGB; 8/16-bit sRGB "
      "data is linearized. Raises RuntimeError naming the file and the reason.");
  m.def(
      "write_image", [](const std::string& path, const FloatArray& a) { write_image(path, to_image(a, path.c_str())); },
      py::arg("path"), py::arg("image"),
      "Writes a (height, width, 3) linear RGB image; the format follows the extension (.exr float; .png, .jpg, "
      ".tif 8-bit sRGB).");
  m.def(
      "compare",
      [](const FloatArray& a, const FloatArray& b) {
        const ImageComparison c = compare_images(to_image(a, "a"), to_image(b, "b"));
        py::dict d;
        d["rmse"] = c.rmse_all;
        d["rmse_rgb"] = rgb(c.rmse);
        d["relmse"] = c.relative_mse_all;
        d["relmse_rgb"] = rgb(c.relative_mse);
        d["max_abs_diff"] = c.max_abs_diff_all;
        d["mean_a"] = rgb(c.mean_a);
        d["mean_b"] = rgb(c.mean_b);
        return d;
      },
      py::arg("a"), py::arg("b"),
      "Error statistics of image a (the test) against b (the reference), both (height, width, 3): rmse = "
      "sqrt(mean (a-b)^2) over pixels and channels, relmse = mean (a-b)^2 / (b^2 + 0.01), max_abs_diff, per-channel "
      "rmse_rgb and relmse_rgb, and the means mean_a, mean_b. Raises ValueError if the sizes differ.");
  m.def(
      "error_map",
      [](const FloatArray& a, const FloatArray& b) {
        double scale = 0;
        Image map = difference_image(to_image(a, "a"), to_image(b, "b"), &scale);
        return py::make_tuple(to_array(map), scale);
      },
      py::arg("a"), py::arg("b"),
      "False-colour map of |a - b| (luminance), scaled so that its 99th percentile is the top of the ramp: returns "
      "(linear RGB float32 (height, width, 3), the luminance difference at the top of the ramp).");
  m.def(
      "subsurface_mask",
      [](Scene& s) {
        Diagnostics diag;
        std::unique_ptr<RenderScene> scene;
        {
          py::gil_scoped_release release;
          scene = assemble_scene(s.desc, diag);
        }
        const std::vector<uint8_t> mask = subsurface_object_mask(*scene);
        const PixelBounds px = film_pixel_bounds(scene->film);
        py::array_t<bool> out({py::ssize_t(px.height()), py::ssize_t(px.width())});
        std::copy(mask.begin(), mask.end(), out.mutable_data());
        return out;
      },
      py::arg("scene"),
      "Bool (height, width): True where the camera ray through the pixel's centre first hits a subsurface object "
      "(the pixels a comparison of subsurface methods is about).");
}

}  // namespace dermis::python
