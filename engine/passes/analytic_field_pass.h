#pragma once
// The analytic fields (lic/analytic_fields.h) made on the device: shaders/analytic_field.comp
// evaluates them in float, slab by slab, and the host reads each slab into the field. The CPU
// version stays the oracle; the device's differs by float rounding (tests/
// test_analytic_device.cpp). Not yet what the front ends use: read back to the host it was no
// faster on the H100 (tornado 512^3: 1.88 s against 1.76 s on 16 cores, docs/BENCHMARKS.md); the
// shader is the first part of making the packed field texture on the device directly.
#include "core/error.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "lic/analytic_fields.h"

namespace lic3d {

// makeAnalyticField(field, dims, time) evaluated on `context`'s device.
Result<VectorField> makeAnalyticFieldOnDevice(const Context& context, AnalyticField field,
                                              Dims dims, double time = 0.0);

}  // namespace lic3d
