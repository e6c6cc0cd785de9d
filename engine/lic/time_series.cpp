// SPDX-License-Identifier: BSD-3-Clause
#include "lic/time_series.h"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "core/text.h"
#include "io/field_io.h"
#include "io/file_util.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using Conversion = NumberConversion;

// The pattern's step number, or why it has none usable.
std::optional<Conversion> findConversion(std::string_view text, std::string* problem) {
  const NumberScan scan = scanNumberConversion(text);
  const char* why = nullptr;
  switch (scan.problem) {
    case NumberScan::Problem::None: return scan.conversion;
    case NumberScan::Problem::NotAConversion:
      why = "only %d or %0Nd can number the steps (write %% for a literal %)";
      break;
    case NumberScan::Problem::MoreThanOne: why = "it holds more than one step number"; break;
    case NumberScan::Problem::NoConversion: why = "it holds no step number"; break;
  }
  if (problem) *problem = why;
  return std::nullopt;
}

bool isDigits(std::string_view text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

Result<std::vector<fs::path>> numberedFiles(const std::string& pattern) {
  const fs::path path(pattern);
  const std::string name = path.filename().string();
  std::string problem;
  const std::optional<Conversion> c = findConversion(name, &problem);
  if (!c) {
    if (findConversion(pattern, nullptr))
      return parameterError("field.source", pattern +
                                                ": the step number must be in the file name, not "
                                                "in a folder name");
    return parameterError("field.source", pattern + ": " + problem);
  }
  const std::string prefix = unescapePercent(std::string_view(name).substr(0, c->begin));
  const std::string suffix = unescapePercent(std::string_view(name).substr(c->end));
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    return parameterError("field.source",
                          pattern + ": folder " + folder.string() + " does not exist");
  std::vector<std::pair<unsigned long long, fs::path>> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    const std::string file = entry.path().filename().string();
    if (file.size() <= prefix.size() + suffix.size() || !file.starts_with(prefix) ||
        !file.ends_with(suffix))
      continue;
    const std::string number =
        file.substr(prefix.size(), file.size() - prefix.size() - suffix.size());
    if (!isDigits(number) || number.size() < static_cast<std::size_t>(c->width) ||
        number.size() > 18)
      continue;
    if (!entry.is_regular_file(ec)) continue;
    found.emplace_back(std::stoull(number), path.parent_path() / file);
  }
  if (ec)
    return parameterError("field.source",
                          pattern + ": cannot list " + folder.string() + ": " + ec.message());
  std::sort(found.begin(), found.end());
  // dup_1, dup_01 and dup_001 are one step number written three ways: which file is the step?
  for (std::size_t i = 1; i < found.size(); ++i)
    if (found[i].first == found[i - 1].first)
      return parameterError("field.source",
                            pattern + ": " + found[i - 1].second.string() + " and " +
                                found[i].second.string() + " both give step number " +
                                std::to_string(found[i].first) + "; keep one of them");
  std::vector<fs::path> files;
  for (auto& [number, file] : found) files.push_back(std::move(file));
  return files;
}

Result<std::vector<fs::path>> globbedFiles(const std::string& pattern) {
  glob_t matches{};
  const int status = ::glob(pattern.c_str(), 0, nullptr, &matches);
  std::vector<fs::path> files;
  if (status == 0)
    for (std::size_t i = 0; i < matches.gl_pathc; ++i) {
      std::error_code ec;
      if (fs::is_regular_file(matches.gl_pathv[i], ec)) files.emplace_back(matches.gl_pathv[i]);
    }
  globfree(&matches);
  if (status != 0 && status != GLOB_NOMATCH)
    return parameterError("field.source", pattern + ": cannot read the folders it names");
  return files;
}

}  // namespace

bool isFieldSeriesPattern(std::string_view field) {
  if (field.find_first_of("*?[") != std::string_view::npos) return true;
  std::string problem;
  if (findConversion(field, &problem)) return true;
  return problem != "it holds no step number";  // a bad conversion is still meant as a series
}

double TimeSeries::stepTime(int k) const {
  return periodic() ? k * period / steps : static_cast<double>(k);
}

double TimeSeries::endTime() const { return periodic() ? period : static_cast<double>(steps - 1); }

TimeBracket TimeSeries::bracket(double time) const {
  TimeBracket b;
  if (steps < 2) return b;
  if (periodic()) {
    double position = std::fmod(time / (period / steps), static_cast<double>(steps));
    if (position < 0.0) position += steps;
    b.first = std::min(static_cast<int>(std::floor(position)), steps - 1);
    b.second = (b.first + 1) % steps;
    b.weight = std::clamp(position - b.first, 0.0, 1.0);
    return b;
  }
  const double position = std::clamp(time, 0.0, static_cast<double>(steps - 1));
  b.first = std::min(static_cast<int>(std::floor(position)), steps - 2);
  b.second = b.first + 1;
  b.weight = position - b.first;
  return b;
}

Result<VectorField> TimeSeries::loadStep(int k, std::string_view arrayName,
                                         FieldReadInfo* info) const {
  if (k < 0 || k >= steps) return inputError("time step " + std::to_string(k) + " does not exist");
  if (analytic) return makeAnalyticField(*analytic, grid, stepTime(k));
  return readVectorField(files[static_cast<std::size_t>(k)], arrayName, info);
}

std::string TimeSeries::describe() const {
  if (analytic)
    return std::to_string(steps) + " steps of " + std::string(enumName(*analytic)) +
           " over its period";
  return std::to_string(steps) + " files " + files.front().string() + " .. " +
         files.back().string();
}

Result<TimeSeries> fileSeries(const std::string& pattern) {
  // A glob character makes it a glob (a % there is literal); otherwise it numbers the steps.
  const bool numbered = pattern.find_first_of("*?[") == std::string::npos;
  TimeSeries series;
  if (numbered) {
    LIC3D_TRY_ASSIGN(series.files, numberedFiles(pattern));
  } else {
    LIC3D_TRY_ASSIGN(series.files, globbedFiles(pattern));
  }
  if (series.files.size() < 2)
    return parameterError(
        "field.source",
        pattern + ": a time series needs at least two files; " +
            (series.files.empty() ? std::string("none match")
                                  : "only " + series.files.front().string() + " matches"));
  series.steps = static_cast<int>(series.files.size());
  return series;
}

Result<TimeSeries> analyticSeries(AnalyticField field, Dims grid, int steps) {
  if (timePeriod(field) <= 0.0)
    return parameterError("time_steps",
                          "is for fields that change with time: " + std::string(enumName(field)) +
                              " does not (the tornado does)");
  if (steps < 2) return parameterError("time_steps", "must be at least 2 for a time series");
  TimeSeries series;
  series.analytic = field;
  series.grid = grid;
  series.steps = steps;
  series.period = timePeriod(field);
  return series;
}

Result<VectorField> interpolateFields(const VectorField& a, const VectorField& b, double weight) {
  if (a.dims != b.dims || !(a.geometry == b.geometry))
    return inputError("time steps must share their grid: " + gridText(a.dims) + " and " +
                      gridText(b.dims) + (a.dims == b.dims ? " differ in spacing or origin" : ""));
  const double w = std::clamp(weight, 0.0, 1.0);
  VectorField out;
  out.dims = a.dims;
  out.geometry = a.geometry;
  out.vectors.resize(a.vectors.size());
  for (std::size_t i = 0; i < a.vectors.size(); ++i)
    out.vectors[i] = glm::vec3((1.0 - w) * glm::dvec3(a.vectors[i]) + w * glm::dvec3(b.vectors[i]));
  return out;
}

}  // namespace lic3d
