// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How the LIC pass' field texture stores the field and the noise (passes/volume_textures.h packs
// it): a choice of the session, of the memory estimates and of the GPU upload.

#include <cstdint>
#include <string_view>

#include "core/enum_names.h"

namespace lic3d {

enum class FieldPrecision {
  Auto,   // Float on CPU devices (lavapipe), Half on GPUs
  Half,   // RGBA16F: half the memory and bandwidth; 11 significant bits per component
  Float,  // RGBA32F: exact float32 field and noise; GPUs fetch it markedly slower, CPUs faster
  // RGBA8 SNORM, a quarter of float's memory: xyz = e with e |e| = u / max|u| (the square root
  // of the relative speed scales the unit direction, so slow flow keeps 7-bit directions down to
  // 1e-4 of the top speed) and w = (255 n - 128) / 127 for noise n in [0,1] (8-bit noise).
  Byte,
};
LIC3D_ENUM_NAMES(FieldPrecision, {FieldPrecision::Auto, "auto"}, {FieldPrecision::Half, "half"},
                 {FieldPrecision::Float, "float"}, {FieldPrecision::Byte, "byte"})

// Bytes per texel of the field texture (Auto must be resolved first), and its format's name.
inline std::uint32_t fieldTexelBytes(FieldPrecision precision) {
  switch (precision) {
    case FieldPrecision::Byte: return 4;
    case FieldPrecision::Float: return 16;
    default: return 8;
  }
}

inline std::string_view fieldTextureFormatName(FieldPrecision precision) {
  switch (precision) {
    case FieldPrecision::Byte: return "RGBA8";
    case FieldPrecision::Float: return "RGBA32F";
    default: return "RGBA16F";
  }
}

}  // namespace lic3d
