// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How a long call (a LIC volume, the CPU reference, a bricked run) tells how far it got and
// learns that it should stop: the finished fraction goes to a function, and a stop token asks the
// call to give up between its units of work (the GPU pass' slabs, the CPU reference's rows, the
// bricks). A stopped call returns a Cancelled error once the work in flight has finished, with no
// device work left running and nothing written.

#include <concepts>
#include <functional>
#include <stop_token>
#include <type_traits>
#include <utility>

namespace lic3d {

class ProgressCallback {
 public:
  ProgressCallback() = default;
  // `report` gets the finished fraction in [0,1] from the calling thread.
  template <class F>
  requires std::invocable<F&, double> &&
      (!std::same_as<std::decay_t<F>, ProgressCallback>)ProgressCallback(F report)
      : report_(std::move(report)) {}
  ProgressCallback(std::function<void(double)> report, std::stop_token stop)
      : report_(std::move(report)), stop_(std::move(stop)) {}

  // Whether the call reports progress or may be stopped: it then works in units small enough
  // for either.
  explicit operator bool() const { return report_ || stop_.stop_possible(); }
  void operator()(double fraction) const {
    if (report_) report_(fraction);
  }
  bool stopRequested() const { return stop_.stop_requested(); }
  // Another report for a part of the call (a brick's LIC), stopped by the same token.
  ProgressCallback withReport(std::function<void(double)> report) const {
    return {std::move(report), stop_};
  }

 private:
  std::function<void(double)> report_;
  std::stop_token stop_;
};

}  // namespace lic3d
