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

std::vector<std::pair<std::string, std::uint64_t>>& bytesTable() {
  static std::vector<std::pair<std::string, std::uint64_t>> bytes;
  return bytes;
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

void addStageBytes(std::string_view stage, std::uint64_t bytes) {
  const std::scoped_lock lock(stageMutex());
  for (auto& [name, total] : bytesTable())
    if (name == stage) {
      total += bytes;
      return;
    }
  bytesTable().emplace_back(std::string(stage), bytes);
}

std::uint64_t stageBytes(std::string_view stage) {
  const std::scoped_lock lock(stageMutex());
  for (const auto& [name, total] : bytesTable())
    if (name == stage) return total;
  return 0;
}

void clearStageTimings() {
  const std::scoped_lock lock(stageMutex());
  table().clear();
  bytesTable().clear();
}

}  // namespace lic3d
