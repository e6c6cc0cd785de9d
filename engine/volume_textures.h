#pragma once
// The LIC inputs on the GPU: the vector field and the noise as sampled 3D textures.

#include "error.h"
#include "gpu_resources.h"
#include "volume.h"
#include "vulkan_context.h"

namespace lic3d {

struct FieldTexture {
  Image image;  // RGBA16F: xyz = v / max|v| (w = 0), so half floats keep full relative precision
  Dims dims{0};
  GridGeometry geometry;
  double maxMagnitude = 0.0;
};

// Fails with InvalidInput when the grid exceeds the device's 3D image limit.
Result<FieldTexture> uploadField(const Context& context, const VectorField& field);

// R8/R16 UNORM for integer noise (bit-exact), R32F for float noise.
Result<Image> uploadNoise(const Context& context, const NoiseVolume& noise);

// Checks that the device can hold a 3D image of `dims`.
Result<void> checkVolumeDims(const Context& context, Dims dims, const char* what);

}  // namespace lic3d
