// SPDX-License-Identifier: BSD-3-Clause
// The ParaView filter's panel (paraview/filters/Lic3dFilter.xml) repeats the defaults and the
// names of lic3d's parameters, because ParaView reads them from XML. This holds the XML to the
// engine: every default equals the engine's, every enumeration lists the engine's names in
// order, and every range lies within the engine's (core/parameter_ranges.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <string>

#include "core/lic_params.h"
#include "core/parameter_ranges.h"
#include "core/session.h"
#include "test_support.h"

namespace lic3d {
namespace {

struct Expected {
  double value = 0.0;                   // the default
  std::size_t names = 0;                // an enumeration's count of names, else 0
  std::optional<ParameterRange> range;  // the engine's accepted range
};

std::map<std::string, Expected> expectations() {
  const LicParams lic;
  const SparsityParams& sparsity = lic.sparsity;
  const Session session;
  auto named = [](auto value) {
    return Expected{static_cast<double>(value), enumNames<decltype(value)>().size(), {}};
  };
  return {
      {"Length", {static_cast<double>(lic.length), 0, ranges::kLength}},
      {"Step", {lic.step, 0, ranges::kStep}},
      {"Bias", {static_cast<double>(lic.bias), 0, {}}},
      {"Integrator", named(lic.integrator)},
      {"Scheme", named(lic.scheme)},
      {"Kernel", named(lic.kernel)},
      {"NoiseFilter", named(lic.noiseFilter)},
      {"Direction", named(lic.direction)},
      {"NoiseSeed", {static_cast<double>(session.noise.seed), 0, {}}},
      {"SparsityDistribution", named(sparsity.distribution)},
      {"SparsityPoints", {static_cast<double>(sparsity.points), 0, ranges::kSparsityPoints}},
      {"SparsityRadius", {sparsity.radius, 0, ranges::kSparsityRadius}},
      {"SparsityRatio", {sparsity.ratio, 0, ranges::kSparsityRatio}},
      {"SparsitySeed", {static_cast<double>(sparsity.seed), 0, {}}},
      {"FieldPrecision", named(session.precision)},
      {"CpuReference", {0.0, 0, {}}},
  };
}

TEST(ParaViewXml, DefaultsNamesAndRangesAreTheEngines) {
  const std::filesystem::path xml =
      test::dataFolder().parent_path().parent_path() / "paraview/filters/Lic3dFilter.xml";
  pugi::xml_document document;
  ASSERT_TRUE(document.load_file(xml.c_str())) << xml;
  const std::map<std::string, Expected> expected = expectations();
  std::size_t checked = 0;
  for (const pugi::xpath_node& node :
       document.select_nodes("//IntVectorProperty | //DoubleVectorProperty")) {
    const pugi::xml_node property = node.node();
    const std::string name = property.attribute("name").value();
    const auto it = expected.find(name);
    ASSERT_NE(it, expected.end()) << name << ": a property this test does not know";
    const Expected& e = it->second;
    ++checked;
    // As the engine's floats hold them.
    EXPECT_EQ(
        static_cast<float>(std::strtod(property.attribute("default_values").value(), nullptr)),
        static_cast<float>(e.value))
        << name;
    if (e.names > 0) {
      std::size_t entries = 0;
      for (const pugi::xml_node entry : property.child("EnumerationDomain").children("Entry"))
        EXPECT_EQ(entry.attribute("value").as_int(-1), static_cast<int>(entries++)) << name;
      EXPECT_EQ(entries, e.names) << name;
    }
    for (const char* domain : {"IntRangeDomain", "DoubleRangeDomain"}) {
      const pugi::xml_node range = property.child(domain);
      if (!range || !e.range) continue;
      if (range.attribute("min")) {
        EXPECT_GE(range.attribute("min").as_double(), e.range->min) << name;
      }
      if (range.attribute("max")) {
        EXPECT_LE(range.attribute("max").as_double(), e.range->max) << name;
      }
    }
  }
  EXPECT_EQ(checked, expected.size()) << "a parameter is missing from the XML";
}

}  // namespace
}  // namespace lic3d
