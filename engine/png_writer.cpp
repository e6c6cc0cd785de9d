#include "rgba_image.h"

#include <string>

#include "file_util.h"

// stb's PNG writer is compiled into lic3d itself (not linked from libstb) so the binary needs
// nothing beyond libvulkan, libstdc++ and libc.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace lic3d {

Result<void> writePng(const std::filesystem::path& path, const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    return inputError("cannot write " + path.string() + ": the image is empty or malformed");
  std::string encoded;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 4, image.pixels.data(),
                              image.width * 4))
    return runtimeError("cannot encode " + path.string() + " as PNG");
  return writeFileAtomically(path, encoded);
}

}  // namespace lic3d
