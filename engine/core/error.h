// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Errors that come back as values: user input (bad flag, bad file), unsupported setups (no Vulkan
// device, missing feature) and runtime failures (device lost, out of memory). Programming errors
// are not values: they abort through LIC3D_VK_CHECK / LIC3D_ASSERT.

#include <cstdlib>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace lic3d {

enum class ErrorKind {
  InvalidInput,   // a bad flag, value or file: the user can fix it (CLI exit status 2)
  Unsupported,    // no usable device, missing layer or feature (CLI exit status 1)
  Runtime,        // a Vulkan call failed at run time: out of memory, device lost (exit status 1)
  ResourceLimit,  // the request needs more memory than the device or host has (exit status 3)
  Cancelled,      // stopped on request (ProgressCallback's stop token) before it finished
};

struct Error {
  ErrorKind kind = ErrorKind::Runtime;
  std::string message;
  // VK_ERROR_DEVICE_LOST or VK_ERROR_SURFACE_LOST_KHR: nothing made on the device can be used
  // again, but a new device (and surface) can carry on (the desktop app does, docs/RELIABILITY.md).
  bool deviceLost = false;
  // The parameter the error is about, by its session key ("lic.length", "view.camera.fov",
  // "field.source"), or empty. The message names it by that key; a front end may put its own
  // name for it in place of the key (the CLI its flag, the app its widget).
  std::string parameter;
};

inline Error inputError(std::string message) {
  return {ErrorKind::InvalidInput, std::move(message)};
}
// An InvalidInput error about a parameter: "<key> <problem>".
inline Error parameterError(std::string_view key, std::string problem) {
  Error error{ErrorKind::InvalidInput, std::string(key) + " " + std::move(problem)};
  error.parameter = key;
  return error;
}
inline Error unsupportedError(std::string message) {
  return {ErrorKind::Unsupported, std::move(message)};
}
inline Error runtimeError(std::string message) { return {ErrorKind::Runtime, std::move(message)}; }
inline Error resourceLimitError(std::string message) {
  return {ErrorKind::ResourceLimit, std::move(message)};
}
inline Error cancelledError() { return {ErrorKind::Cancelled, "stopped on request"}; }

// A value or the Error that explains why there is none.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::in_place_index<0>, std::move(value)) {}
  Result(Error error) : state_(std::in_place_index<1>, std::move(error)) {}

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { return std::get<0>(state_); }
  const T& value() const& { return std::get<0>(state_); }
  T&& value() && { return std::get<0>(std::move(state_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  const Error& error() const& { return std::get<1>(state_); }
  Error&& error() && { return std::get<1>(std::move(state_)); }

 private:
  std::variant<T, Error> state_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), failed_(true) {}

  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const& { return error_; }
  Error&& error() && { return std::move(error_); }

 private:
  Error error_;
  bool failed_ = false;
};

}  // namespace lic3d

// Propagates an error from an expression returning Result<T>; on success binds the value to `var`.
#define LIC3D_CONCAT_INNER(a, b) a##b
#define LIC3D_CONCAT(a, b) LIC3D_CONCAT_INNER(a, b)
#define LIC3D_TRY_ASSIGN_IMPL(tmp, var, expr)   \
  auto tmp = (expr);                            \
  if (!tmp.ok()) return std::move(tmp).error(); \
  var = std::move(tmp).value()
#define LIC3D_TRY_ASSIGN(var, expr) \
  LIC3D_TRY_ASSIGN_IMPL(LIC3D_CONCAT(lic3dTry_, __LINE__), var, expr)
// Propagates an error from an expression returning Result<void>.
#define LIC3D_TRY(expr)                                                 \
  do {                                                                  \
    auto lic3dTryResult = (expr);                                       \
    if (!lic3dTryResult.ok()) return std::move(lic3dTryResult).error(); \
  } while (false)
