#pragma once
// One name per value for every parameter enum: the CLI's flag values, the session files and the
// UI's combo boxes all read these tables, so a name is spelled one way everywhere.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "lic_params.h"
#include "sparsity.h"
#include "view_params.h"
#include "volume_textures.h"

namespace lic3d {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

template <class E>
std::span<const EnumName<E>> enumNames();

#define LIC3D_ENUM_NAMES(Type, ...)                                        \
  template <>                                                              \
  inline std::span<const EnumName<Type>> enumNames<Type>() {               \
    static constexpr EnumName<Type> kNames[] = {__VA_ARGS__};              \
    return kNames;                                                         \
  }

LIC3D_ENUM_NAMES(Integrator, {Integrator::Euler, "euler"}, {Integrator::Rk2, "rk2"},
                 {Integrator::Rk4, "rk4"})
LIC3D_ENUM_NAMES(Kernel, {Kernel::Box, "box"}, {Kernel::Hann, "hann"}, {Kernel::Gauss, "gauss"})
LIC3D_ENUM_NAMES(NoiseFilter, {NoiseFilter::Nearest, "nearest"}, {NoiseFilter::Linear, "linear"})
LIC3D_ENUM_NAMES(DirectionMode, {DirectionMode::Normalized, "normalized"},
                 {DirectionMode::Magnitude, "magnitude"})
LIC3D_ENUM_NAMES(StepScheme, {StepScheme::Exact, "exact"}, {StepScheme::Ab2, "ab2"})
LIC3D_ENUM_NAMES(SparsityDistribution, {SparsityDistribution::None, "none"},
                 {SparsityDistribution::Checkerboard, "checkerboard"},
                 {SparsityDistribution::Poisson, "poisson"},
                 {SparsityDistribution::PoissonApprox, "poisson-approx"},
                 {SparsityDistribution::Jitter, "jitter"}, {SparsityDistribution::Halton, "halton"},
                 {SparsityDistribution::Hammersley, "hammersley"})
LIC3D_ENUM_NAMES(Slicing, {Slicing::ViewAligned, "view"}, {Slicing::AxisAligned, "axis"})
LIC3D_ENUM_NAMES(OpacityMode, {OpacityMode::Constant, "constant"},
                 {OpacityMode::Intensity, "intensity"})
LIC3D_ENUM_NAMES(VolumeFilter, {VolumeFilter::Nearest, "nearest"}, {VolumeFilter::Linear, "linear"})
LIC3D_ENUM_NAMES(ColorMode, {ColorMode::None, "none"}, {ColorMode::Magnitude, "magnitude"})
LIC3D_ENUM_NAMES(Colormap, {Colormap::Thesis, "thesis"}, {Colormap::Viridis, "viridis"},
                 {Colormap::CoolWarm, "coolwarm"})
LIC3D_ENUM_NAMES(RoiShape, {RoiShape::None, "none"}, {RoiShape::Sphere, "sphere"},
                 {RoiShape::Cube, "cube"}, {RoiShape::Cylinder, "cylinder"})
LIC3D_ENUM_NAMES(StereoMode, {StereoMode::None, "none"}, {StereoMode::Anaglyph, "anaglyph"},
                 {StereoMode::SideBySide, "side-by-side"})
LIC3D_ENUM_NAMES(Lighting, {Lighting::None, "none"}, {Lighting::Phong, "phong"},
                 {Lighting::Lines, "lines"})
LIC3D_ENUM_NAMES(FieldPrecision, {FieldPrecision::Auto, "auto"}, {FieldPrecision::Half, "half"},
                 {FieldPrecision::Float, "float"}, {FieldPrecision::Byte, "byte"})
#undef LIC3D_ENUM_NAMES

template <class E>
std::optional<E> parseEnum(std::string_view name) {
  for (const EnumName<E>& n : enumNames<E>())
    if (n.name == name) return n.value;
  return std::nullopt;
}

template <class E>
std::string_view enumName(E value) {
  for (const EnumName<E>& n : enumNames<E>())
    if (n.value == value) return n.name;
  return "?";
}

// "a|b|c", for help texts and error messages.
template <class E>
std::string enumChoices() {
  std::string text;
  for (const EnumName<E>& n : enumNames<E>()) text += (text.empty() ? "" : "|") + std::string(n.name);
  return text;
}

}  // namespace lic3d
