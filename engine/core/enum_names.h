// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One name per value for every parameter enum: the CLI's flag values, the session files, the
// UI's combo boxes, error messages and pipeline names all read these tables, so a name is
// spelled one way everywhere. Each enum's header lists its names right below the enum with
// LIC3D_ENUM_NAMES.

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace lic3d {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

// Specialised for each enum by LIC3D_ENUM_NAMES, in the enum's own header.
template <class E>
std::span<const EnumName<E>> enumNames();

#define LIC3D_ENUM_NAMES(Type, ...)                           \
  template <>                                                 \
  inline std::span<const EnumName<Type>> enumNames<Type>() {  \
    static constexpr EnumName<Type> kNames[] = {__VA_ARGS__}; \
    return kNames;                                            \
  }

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
  for (const EnumName<E>& n : enumNames<E>())
    text += (text.empty() ? "" : "|") + std::string(n.name);
  return text;
}

}  // namespace lic3d
