// SPDX-License-Identifier: BSD-3-Clause
#include "passes/volume_textures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/packing.hpp>
#include <memory>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/submit.h"
#include "lic/lic_reference.h"

namespace lic3d {
namespace {

// Interleaves (v in voxel units / its largest length, noise) as RGBA texels of type T into
// `texels`, converted by `convert`. `scale` is voxelUnitScale / maxVoxelSpeed.
template <class T, class Convert>
void packTexels(const VectorField& field, const NoiseVolume& noise, glm::dvec3 scale,
                Convert convert, T* texels) {
  parallelChunks(field.vectors.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const glm::dvec3 v = glm::dvec3(field.vectors[i]) * scale;
      texels[4 * i + 0] = convert(static_cast<float>(v.x));
      texels[4 * i + 1] = convert(static_cast<float>(v.y));
      texels[4 * i + 2] = convert(static_cast<float>(v.z));
      texels[4 * i + 3] = convert(noise.value(i));
    }
  });
}

// FieldPrecision::Byte: a component in [-1, 1] as SNORM8.
std::int8_t snorm8(double value) {
  return static_cast<std::int8_t>(std::lround(std::clamp(value, -1.0, 1.0) * 127.0));
}

// FieldPrecision::Byte texels (see volume_textures.h): e = u/M / sqrt(|u|/M), noise shifted into
// the signed range so all 8 bits of it survive.
void packByteTexels(const VectorField& field, const NoiseVolume& noise, glm::dvec3 scale,
                    std::int8_t* texels) {
  parallelChunks(field.vectors.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const glm::dvec3 v = glm::dvec3(field.vectors[i]) * scale;
      const double speed = glm::length(v);
      const glm::dvec3 e = speed > 0.0 ? v / std::sqrt(speed) : glm::dvec3(0.0);
      texels[4 * i + 0] = snorm8(e.x);
      texels[4 * i + 1] = snorm8(e.y);
      texels[4 * i + 2] = snorm8(e.z);
      const double n =
          std::round(std::clamp(static_cast<double>(noise.value(i)), 0.0, 1.0) * 255.0);
      texels[4 * i + 3] = static_cast<std::int8_t>(n - 128.0);
    }
  });
}

}  // namespace

Result<void> checkVolumeDims(const Context& context, Dims dims, const char* what) {
  const std::uint32_t limit = context.properties().limits.maxImageDimension3D;
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || static_cast<std::uint32_t>(dims[a]) > limit)
      return inputError(std::string(what) + " grid " + gridText(dims) + " exceeds what " +
                        context.deviceInfo().name + " allows per axis (1.." +
                        std::to_string(limit) + ")");
  return {};
}

glm::vec4 texelToPhysicalForShader(glm::dvec3 texelToPhysical) {
  const double largest = std::max({texelToPhysical.x, texelToPhysical.y, texelToPhysical.z});
  if (!(largest > 0.0)) return glm::vec4(glm::vec3(texelToPhysical), 1.0f);
  return glm::vec4(glm::vec3(texelToPhysical / largest), static_cast<float>(largest));
}

FieldPrecision resolvePrecision(const Context& context, FieldPrecision requested) {
  if (requested != FieldPrecision::Auto) return requested;
  // A CPU driver gains nothing from half floats (no texture-cache bandwidth to save) and pays
  // for converting them: lavapipe runs the LIC pass about 1.4x faster on RGBA32F.
  return context.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? FieldPrecision::Float
                                                                  : FieldPrecision::Half;
}

Result<FieldPrecision> checkFieldPrecision(const Context& context, FieldPrecision requested) {
  const FieldPrecision resolved = resolvePrecision(context, requested);
  if (resolved == FieldPrecision::Float &&
      !supportsFormat(context, VK_FORMAT_R32G32B32A32_SFLOAT,
                      VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    return unsupportedError(context.deviceInfo().name +
                            " cannot filter RGBA32F textures; use half precision");
  return resolved;
}

int fieldTexelVariant(FieldPrecision resolved) {
  switch (resolved) {
    case FieldPrecision::Float: return 0;
    case FieldPrecision::Byte: return 2;
    default: return 1;
  }
}

VkFormat fieldTextureFormat(FieldPrecision resolved) {
  switch (resolved) {
    case FieldPrecision::Float: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case FieldPrecision::Byte: return VK_FORMAT_R8G8B8A8_SNORM;
    default: return VK_FORMAT_R16G16B16A16_SFLOAT;
  }
}

Result<FieldTexture> createWritableFieldTexture(const Context& context, Dims dims,
                                                const GridGeometry& geometry,
                                                FieldPrecision precision, const std::string& name) {
  LIC3D_TRY(checkVolumeDims(context, dims, "field"));
  LIC3D_TRY(checkSpacing(geometry));
  LIC3D_TRY_ASSIGN(const FieldPrecision resolved, checkFieldPrecision(context, precision));
  FieldTexture texture;
  texture.dims = dims;
  texture.geometry = geometry;
  texture.precision = resolved;
  ImageDesc desc;
  desc.format = fieldTextureFormat(resolved);
  if (!supportsFormat(context, desc.format, VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT))
    return unsupportedError(context.deviceInfo().name + " cannot write " +
                            std::string(fieldTextureFormatName(resolved)) + " storage images (" +
                            name + ")");
  desc.extent = extentOf(dims);
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = name;
  LIC3D_TRY_ASSIGN(texture.image, Image::create(context, desc));
  return texture;
}

Result<FieldTexture> uploadLicInputs(const Context& context, const VectorField& field,
                                     const NoiseVolume& noise, FieldPrecision precision) {
  LIC3D_TRY(checkVolumeDims(context, field.dims, "field"));
  LIC3D_TRY(checkSpacing(field.geometry));
  LIC3D_TRY_ASSIGN(const FieldPrecision resolved, checkFieldPrecision(context, precision));
  // The texture, its staging copy and the LIC volume must fit (a CPU driver would otherwise
  // accept the allocation and fail when the memory is first touched). Front ends check their
  // whole request earlier; this guards every other caller.
  MemoryRequest request;
  request.dims = field.dims;
  request.precision = resolved;
  LIC3D_TRY(checkMemoryBudget(request, queryMemoryBudget(context), "the field"));
  if (noise.dims != field.dims)
    return inputError("the noise grid (" + gridText(noise.dims) + ") must match the field grid (" +
                      gridText(field.dims) + ")");
  FieldTexture texture;
  texture.dims = field.dims;
  texture.geometry = field.geometry;
  // On isotropic grids voxelUnitScale is exactly 1 and maxVoxelSpeed is max|v|: the texels are
  // v / max|v| bit for bit, as before anisotropic grids were converted.
  const glm::dvec3 unit = voxelUnitScale(field.geometry);
  StageTimer statistics("field statistics");
  // The histogram's range is min and max |v| (the same arithmetic as min/maxMagnitude): two
  // passes over the field rather than five.
  texture.speeds = std::make_shared<const ValueHistogram>(speedHistogram(field));
  texture.maxMagnitude = texture.speeds->max;
  texture.minMagnitude = texture.speeds->min;
  texture.unit = field.unit;
  texture.maxVoxelSpeed =
      !field.piece && unit == glm::dvec3(1.0) ? texture.maxMagnitude : maxVoxelSpeed(field);
  statistics.stop();
  texture.precision = resolved;
  const double speed = texture.maxVoxelSpeed > 0.0 ? texture.maxVoxelSpeed : 1.0;
  const glm::dvec3 scale = unit / speed;
  texture.texelToPhysical = speed / unit;

  ImageDesc desc;
  desc.format = fieldTextureFormat(resolved);
  desc.extent = extentOf(field.dims);
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // read back by tests
  desc.name = "field and noise texture";
  StageTimer allocating("field texture allocation");
  LIC3D_TRY_ASSIGN(texture.image, Image::create(context, desc));
  allocating.stop();
  // The texels are packed straight into the staging buffer: no host array of the texture's size.
  double packingSeconds = 0.0;
  const auto pack = [&](void* staging) {
    const auto start = std::chrono::steady_clock::now();
    switch (resolved) {
      case FieldPrecision::Byte:
        packByteTexels(field, noise, scale, static_cast<std::int8_t*>(staging));
        break;
      case FieldPrecision::Float:
        packTexels(
            field, noise, scale, [](float f) { return f; }, static_cast<float*>(staging));
        break;
      default:
        packTexels(
            field, noise, scale, [](float f) { return glm::packHalf1x16(f); },
            static_cast<std::uint16_t*>(staging));
    }
    packingSeconds = secondsSince(start);
  };
  const auto start = std::chrono::steady_clock::now();
  LIC3D_TRY(uploadImageFilled(context, texture.image,
                              field.vectors.size() * fieldTexelBytes(resolved), pack));
  addStageTime("field packing", packingSeconds);
  addStageTime("field upload", secondsSince(start) - packingSeconds);
  return texture;
}

Result<ScalarTexture> uploadScalars(const Context& context, Dims dims, const PointScalars* color,
                                    const PointScalars* opacity) {
  constexpr std::uint16_t kHalfNaN = 0x7e00;  // a quiet NaN: no value there
  ScalarTexture texture;
  texture.color = color != nullptr;
  texture.opacity = opacity != nullptr;
  const Dims size = color || opacity ? dims : Dims{1};
  for (const PointScalars* s : {color, opacity})
    if (s && s->dims != dims)
      return inputError("the scalar '" + s->name + "' (" + gridText(s->dims) +
                        ") must be on the field's grid " + gridText(dims));
  std::vector<std::uint16_t> texels(2 * voxelCount(size), glm::packHalf1x16(0.0f));
  for (int c = 0; c < 2; ++c) {
    const PointScalars* s = c == 0 ? color : opacity;
    if (!s) continue;
    auto histogram = std::make_shared<const ValueHistogram>(histogramOf(s->values));
    const double span = histogram->max > histogram->min ? histogram->max - histogram->min : 1.0;
    texture.range[2 * c] = static_cast<float>(histogram->min);
    texture.range[2 * c + 1] = static_cast<float>(span);
    for (std::size_t i = 0; i < s->values.size(); ++i)
      texels[2 * i + static_cast<std::size_t>(c)] =
          std::isnan(s->values[i])
              ? kHalfNaN
              : glm::packHalf1x16(static_cast<float>(
                    (static_cast<double>(s->values[i]) - histogram->min) / span));
    (c == 0 ? texture.colorValues : texture.opacityValues) = std::move(histogram);
  }
  if (color) {
    texture.colorName = color->name;
    texture.colorUnit = color->unit;
  }
  ImageDesc desc;
  desc.extent = extentOf(size);
  desc.format = VK_FORMAT_R16G16_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "colour and opacity scalars";
  LIC3D_TRY_ASSIGN(texture.image, Image::create(context, desc));
  LIC3D_TRY(uploadImage(context, texture.image, texels.data(), texels.size() * sizeof(texels[0])));
  return texture;
}

}  // namespace lic3d
