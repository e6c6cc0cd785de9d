// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The analytic fields (lic/analytic_fields.h) evaluated on the device in float, slab by slab, and
// read back into a VectorField (shaders/analytic_vectors.comp): for tests and hosts that need the
// field itself (read back it was no faster than the CPU on the H100). The CPU versions in double
// stay the oracle (tests/test_analytic_device.cpp).

#include "core/error.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "lic/analytic_fields.h"

namespace lic3d {

// makeAnalyticField(field, dims, time) evaluated on `context`'s device.
Result<VectorField> makeAnalyticFieldOnDevice(const Context& context, AnalyticField field,
                                              Dims dims, double time = 0.0);

}  // namespace lic3d
