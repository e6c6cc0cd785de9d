#include "core/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/common.hpp>

namespace lic3d {
namespace {

constexpr std::array<glm::vec3, 3> kThesis = {
    glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f)};

// matplotlib's viridis at t = k/16.
constexpr std::array<glm::vec3, 17> kViridis = {
    glm::vec3(0.267004f, 0.004874f, 0.329415f), glm::vec3(0.282327f, 0.094955f, 0.417331f),
    glm::vec3(0.278826f, 0.175490f, 0.483397f), glm::vec3(0.258965f, 0.251537f, 0.524736f),
    glm::vec3(0.229739f, 0.322361f, 0.545706f), glm::vec3(0.199430f, 0.387607f, 0.554642f),
    glm::vec3(0.172719f, 0.448791f, 0.557885f), glm::vec3(0.149039f, 0.508051f, 0.557250f),
    glm::vec3(0.127568f, 0.566949f, 0.550556f), glm::vec3(0.120638f, 0.625828f, 0.533488f),
    glm::vec3(0.157851f, 0.683765f, 0.501686f), glm::vec3(0.246070f, 0.738910f, 0.452024f),
    glm::vec3(0.369214f, 0.788888f, 0.382914f), glm::vec3(0.515992f, 0.831158f, 0.294279f),
    glm::vec3(0.678489f, 0.863742f, 0.189503f), glm::vec3(0.845561f, 0.887322f, 0.099702f),
    glm::vec3(0.993248f, 0.906157f, 0.143936f)};

// Moreland's 33-stop cool-warm table, every second stop (t = k/16).
constexpr std::array<glm::vec3, 17> kCoolWarm = {
    glm::vec3(0.229806f, 0.298718f, 0.753683f), glm::vec3(0.303869f, 0.406535f, 0.844959f),
    glm::vec3(0.383013f, 0.509419f, 0.917388f), glm::vec3(0.466667f, 0.604563f, 0.968155f),
    glm::vec3(0.552953f, 0.688929f, 0.995376f), glm::vec3(0.639176f, 0.759600f, 0.998151f),
    glm::vec3(0.722193f, 0.813953f, 0.976575f), glm::vec3(0.798692f, 0.849786f, 0.931689f),
    glm::vec3(0.865395f, 0.865410f, 0.865396f), glm::vec3(0.924128f, 0.827385f, 0.774508f),
    glm::vec3(0.958853f, 0.769768f, 0.678008f), glm::vec3(0.969954f, 0.694267f, 0.579375f),
    glm::vec3(0.958003f, 0.602842f, 0.481776f), glm::vec3(0.923945f, 0.497309f, 0.387970f),
    glm::vec3(0.869187f, 0.378313f, 0.300267f), glm::vec3(0.795632f, 0.241284f, 0.220526f),
    glm::vec3(0.705673f, 0.015556f, 0.150233f)};

glm::vec3 interpolate(std::span<const glm::vec3> stops, float t) {
  const float position = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(stops.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(position), stops.size() - 2);
  return glm::mix(stops[i], stops[i + 1], position - static_cast<float>(i));
}

}  // namespace

glm::vec3 sampleColormap(Colormap map, float t) {
  switch (map) {
    case Colormap::Thesis: return interpolate(kThesis, t);
    case Colormap::Viridis: return interpolate(kViridis, t);
    case Colormap::CoolWarm: return interpolate(kCoolWarm, t);
  }
  return glm::vec3(t);
}

std::vector<std::uint8_t> colormapTable() {
  std::vector<std::uint8_t> texels(4 * kColormapWidth * kColormapCount);
  for (int row = 0; row < kColormapCount; ++row)
    for (int x = 0; x < kColormapWidth; ++x) {
      const glm::vec3 c =
          sampleColormap(static_cast<Colormap>(row), static_cast<float>(x) / (kColormapWidth - 1));
      std::uint8_t* texel = &texels[4 * (row * kColormapWidth + x)];
      for (int k = 0; k < 3; ++k) texel[k] = static_cast<std::uint8_t>(std::lround(c[k] * 255.0f));
      texel[3] = 255;
    }
  return texels;
}

}  // namespace lic3d
