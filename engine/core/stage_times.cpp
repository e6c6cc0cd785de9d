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

// Adds `amount` to the row of `stage`, made at the end of `rows` the first time. With the
// mutex held.
template <class T>
void addToRow(std::vector<std::pair<std::string, T>>& rows, std::string_view stage, T amount) {
  for (auto& [name, total] : rows)
    if (name == stage) {
      total += amount;
      return;
    }
  rows.emplace_back(std::string(stage), amount);
}

}  // namespace

void addStageTime(std::string_view stage, double seconds) {
  const std::scoped_lock lock(stageMutex());
  addToRow(table(), stage, seconds);
}

StageTimings stageTimings() {
  const std::scoped_lock lock(stageMutex());
  return table();
}

void addStageBytes(std::string_view stage, std::uint64_t bytes) {
  const std::scoped_lock lock(stageMutex());
  addToRow(bytesTable(), stage, bytes);
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
