#include "volume_textures.h"

#include <glm/gtc/packing.hpp>

#include "gpu_submit.h"

namespace lic3d {

Result<void> checkVolumeDims(const Context& context, Dims dims, const char* what) {
  const std::uint32_t limit = context.properties().limits.maxImageDimension3D;
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || static_cast<std::uint32_t>(dims[a]) > limit)
      return inputError(std::string(what) + " grid " + std::to_string(dims.x) + "x" +
                        std::to_string(dims.y) + "x" + std::to_string(dims.z) +
                        " exceeds what " + context.deviceInfo().name + " allows per axis (1.." +
                        std::to_string(limit) + ")");
  return {};
}

Result<FieldTexture> uploadField(const Context& context, const VectorField& field) {
  LIC3D_TRY(checkVolumeDims(context, field.dims, "field"));
  FieldTexture texture;
  texture.dims = field.dims;
  texture.geometry = field.geometry;
  texture.maxMagnitude = maxMagnitude(field);
  const double scale = texture.maxMagnitude > 0.0 ? 1.0 / texture.maxMagnitude : 1.0;

  std::vector<std::uint16_t> halves(4 * field.vectors.size());
  for (std::size_t i = 0; i < field.vectors.size(); ++i) {
    const glm::dvec3 v = glm::dvec3(field.vectors[i]) * scale;
    halves[4 * i + 0] = glm::packHalf1x16(static_cast<float>(v.x));
    halves[4 * i + 1] = glm::packHalf1x16(static_cast<float>(v.y));
    halves[4 * i + 2] = glm::packHalf1x16(static_cast<float>(v.z));
    halves[4 * i + 3] = 0;
  }
  ImageDesc desc;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.extent = {static_cast<std::uint32_t>(field.dims.x), static_cast<std::uint32_t>(field.dims.y),
                 static_cast<std::uint32_t>(field.dims.z)};
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "field texture";
  LIC3D_TRY_ASSIGN(texture.image, Image::create(context, desc));
  LIC3D_TRY(uploadImage(context, texture.image, halves.data(), halves.size() * sizeof(std::uint16_t)));
  return texture;
}

Result<Image> uploadNoise(const Context& context, const NoiseVolume& noise) {
  LIC3D_TRY(checkVolumeDims(context, noise.dims, "noise"));
  ImageDesc desc;
  switch (noise.type) {
    case NoiseType::UInt8: desc.format = VK_FORMAT_R8_UNORM; break;
    case NoiseType::UInt16: desc.format = VK_FORMAT_R16_UNORM; break;
    case NoiseType::Float32: desc.format = VK_FORMAT_R32_SFLOAT; break;
  }
  if (!supportsFormat(context, desc.format, VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    return unsupportedError(context.deviceInfo().name +
                            " cannot filter the noise texture format linearly");
  desc.extent = {static_cast<std::uint32_t>(noise.dims.x), static_cast<std::uint32_t>(noise.dims.y),
                 static_cast<std::uint32_t>(noise.dims.z)};
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "noise texture";
  LIC3D_TRY_ASSIGN(Image image, Image::create(context, desc));
  LIC3D_TRY(uploadImage(context, image, noise.bytes.data(), noise.bytes.size()));
  return image;
}

}  // namespace lic3d
