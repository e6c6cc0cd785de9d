// SPDX-License-Identifier: BSD-3-Clause
#include "core/stage_times.h"

#include <mutex>

namespace lic3d {
namespace {

std::mutex& stageMutex() {
  static std::mutex mutex;
  return mutex;
}

StageTimings& table() {
  static StageTimings timings;
  return timings;
}

}  // namespace

void addStageTime(std::string_view stage, double seconds) {
  const std::scoped_lock lock(stageMutex());
  for (auto& [name, total] : table())
    if (name == stage) {
      total += seconds;
      return;
    }
  table().emplace_back(std::string(stage), seconds);
}

StageTimings stageTimings() {
  const std::scoped_lock lock(stageMutex());
  return table();
}

void clearStageTimings() {
  const std::scoped_lock lock(stageMutex());
  table().clear();
}

}  // namespace lic3d
