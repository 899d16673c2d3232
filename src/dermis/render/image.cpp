// PROVISIONAL (replaced by the image I/O branch).
#include "dermis/render/image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <stdexcept>

namespace dermis {

Image read_image(const std::string& path) {
  OIIO::ImageBuf buf(path);
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) throw std::runtime_error(path + ": could not read image: " + buf.geterror());
  Image img;
  img.width = buf.spec().width;
  img.height = buf.spec().height;
  img.pixels.resize(std::size_t(img.width) * img.height * 3);
  int nc = buf.spec().nchannels;
  std::vector<float> all(std::size_t(img.width) * img.height * nc);
  buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, all.data());
  for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i)
    for (int c = 0; c < 3; ++c) img.pixels[3 * i + c] = all[i * nc + std::min(c, nc - 1)];
  return img;
}

void write_image(const std::string& path, const Image& img) {
  OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf buf(spec, const_cast<float*>(img.pixels.data()));
  if (!buf.write(path)) throw std::runtime_error(path + ": could not write image: " + buf.geterror());
}

}  // namespace dermis
