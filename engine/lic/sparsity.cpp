#include "lic/sparsity.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <numeric>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>

#include "core/parallel.h"
#include "io/file_util.h"
#include "lic/noise.h"

namespace lic3d {
namespace {

// Random geometry runs on integers in units of 1/1024 voxel: coordinates below 16384 * 1024 =
// 2^24 convert to float exactly, and squared distances fit in int64 with room to spare.
constexpr int kFixedBits = 10;
constexpr std::int64_t kFixedOne = std::int64_t{1} << kFixedBits;
constexpr float kFixedToVoxels = 1.0f / static_cast<float>(kFixedOne);

// Streams of the seed, so distributions sharing a seed do not share random numbers.
constexpr std::uint64_t kPoissonStream = 0x506F6973736F6E31ull;
constexpr std::uint64_t kPoissonSlabStream = 0x506F69536C616230ull;  // plus the slab
constexpr std::uint64_t kPoissonBandStream = 0x506F6942616E6430ull;  // plus the band
constexpr std::uint64_t kBestCandidateStream = 0x4265737443616E64ull;
constexpr std::uint64_t kJitterStream = 0x4A69747465723031ull;
constexpr std::uint64_t kSubsetStream = 0x5375627365743031ull;

struct FixedPoint {
  std::int32_t x = 0, y = 0, z = 0;
};

std::int64_t distanceSquared(const FixedPoint& a, const FixedPoint& b) {
  const std::int64_t dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return dx * dx + dy * dy + dz * dz;
}

glm::vec3 toVoxels(const FixedPoint& p) {
  return {static_cast<float>(p.x) * kFixedToVoxels, static_cast<float>(p.y) * kFixedToVoxels,
          static_cast<float>(p.z) * kFixedToVoxels};
}

// SplitMix64 (Steele, Lea, Flood 2014), started from the project's noiseHash of (seed, stream).
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t stream) : state_(noiseHash(seed, stream)) {}

  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, n), n < 2^32: Lemire's multiply-shift, bias below n / 2^32.
  std::uint32_t below(std::size_t n) {
    return static_cast<std::uint32_t>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
  }

 private:
  std::uint64_t state_;
};

// One 64-bit random word gives three 21-bit fractions; each maps to [0, span) by multiply-shift.
// Spans above 2^21 units (grids over 2048 voxels) then land on a lattice of span / 2^21 units,
// finer than 1/128 voxel.
std::int64_t scaled21(std::uint64_t bits, int slot, std::int64_t span) {
  const std::int64_t fraction = static_cast<std::int64_t>((bits >> (21 * slot)) & 0x1FFFFF);
  return (fraction * span) >> 21;
}

std::int64_t isqrt(std::int64_t value) {
  if (value <= 0) return 0;
  auto root = static_cast<std::int64_t>(std::sqrt(static_cast<double>(value)));
  while (root * root > value) --root;
  while ((root + 1) * (root + 1) <= value) ++root;
  return root;
}

// floor(v / d) for 0 <= v < 2^27 by multiply and shift (Granlund, Montgomery 1994, "Division
// by invariant integers using multiplication"): the grid searches divide every candidate's
// coordinates by the cell size, and a 64-bit idiv costs 40-90 cycles.
class CellDivider {
 public:
  explicit CellDivider(std::int64_t divisor) {
    int log2Ceil = 0;
    while ((std::int64_t{1} << log2Ceil) < divisor) ++log2Ceil;
    shift_ = kValueBits + log2Ceil;
    multiplier_ = (std::int64_t{1} << shift_) / divisor + 1;
  }
  std::int64_t operator()(std::int64_t value) const { return (value * multiplier_) >> shift_; }

 private:
  static constexpr int kValueBits = 27;
  std::int64_t multiplier_ = 1;
  int shift_ = 0;
};

bool validDims(Dims dims) {
  return dims.x >= 1 && dims.y >= 1 && dims.z >= 1 && dims.x <= static_cast<int>(kMaxAxisSize) &&
         dims.y <= static_cast<int>(kMaxAxisSize) && dims.z <= static_cast<int>(kMaxAxisSize);
}

struct FixedExtent {
  std::int64_t x, y, z;
};
FixedExtent fixedExtent(Dims dims) {
  return {dims.x * kFixedOne, dims.y * kFixedOne, dims.z * kFixedOne};
}

// The radius in fixed point, rounded up so that integer distances >= it are >= the radius.
std::int64_t fixedRadius(float radius) {
  const double r = std::max(static_cast<double>(radius), static_cast<double>(kMinSparsityRadius));
  return static_cast<std::int64_t>(std::ceil(r * static_cast<double>(kFixedOne)));
}

std::size_t cellsAlong(std::int64_t extent, std::int64_t cell) {
  return static_cast<std::size_t>((extent + cell - 1) / cell);
}

// Bridson's background grid: the largest integer cell C with C * sqrt(3) <= R, so a cell (a cube
// of side C) holds at most one sample.
struct PoissonGridShape {
  std::int64_t cell = 1;
  int reach = 2;                       // a conflicting sample lies at most this many cells away
  std::size_t nx = 0, ny = 0, nz = 0;  // including `reach` empty cells of padding on each side
  std::size_t cells() const { return nx * ny * nz; }
};

PoissonGridShape poissonGridShape(Dims dims, std::int64_t fixedR) {
  PoissonGridShape shape;
  shape.cell = std::max<std::int64_t>(1, isqrt(fixedR * fixedR / 3));
  while (3 * shape.cell * shape.cell > fixedR * fixedR && shape.cell > 1) --shape.cell;
  shape.reach = static_cast<int>((fixedR + shape.cell - 1) / shape.cell);
  const FixedExtent e = fixedExtent(dims);
  const auto pad = static_cast<std::size_t>(2 * shape.reach);
  shape.nx = cellsAlong(e.x, shape.cell) + pad;
  shape.ny = cellsAlong(e.y, shape.cell) + pad;
  shape.nz = cellsAlong(e.z, shape.cell) + pad;
  return shape;
}

std::size_t jitterCells(Dims dims, std::int64_t fixedR) {
  const FixedExtent e = fixedExtent(dims);
  return cellsAlong(e.x, fixedR) * cellsAlong(e.y, fixedR) * cellsAlong(e.z, fixedR);
}

// The smallest radius in [kMinSparsityRadius, largest] for which fits(radius) holds (fits grows
// with the radius), rounded up to 0.01 voxel.
template <class Fits>
float smallestRadiusThatFits(Fits fits, float largest) {
  if (fits(kMinSparsityRadius)) return kMinSparsityRadius;
  float lo = kMinSparsityRadius, hi = largest;
  for (int i = 0; i < 40; ++i) {
    const float mid = 0.5f * (lo + hi);
    (fits(mid) ? hi : lo) = mid;
  }
  return std::ceil(hi * 100.0f) / 100.0f;
}

bool poissonFits(Dims dims, float radius) {
  return poissonGridShape(dims, fixedRadius(radius)).cells() <= kMaxPoissonGridCells;
}
bool jitterFits(Dims dims, float radius) {
  return jitterCells(dims, fixedRadius(radius)) <= kMaxSparsityPoints;
}

float largestAxis(Dims dims) { return static_cast<float>(std::max({dims.x, dims.y, dims.z})); }

// The radius r (a multiple of 1/1024 voxel, rounded up) with r^3 >= volumePerPoint: an integer
// cube root, since std::cbrt may round differently from one C library to another and the
// automatic radius must be the same everywhere.
float radiusForVolume(double volumePerPoint) {
  const double limit = std::ldexp(1.0, 60);  // (2^20 units)^3: a 1024-voxel radius
  const double scaled = std::ceil(volumePerPoint * std::ldexp(1.0, 3 * kFixedBits));
  const auto target = static_cast<std::uint64_t>(std::min(scaled, limit));
  std::uint64_t lo = 0, hi = std::uint64_t{1} << 20;  // lo^3 < target <= hi^3
  while (hi - lo > 1) {
    const std::uint64_t mid = (lo + hi) / 2;
    (mid * mid * mid >= target ? hi : lo) = mid;
  }
  return static_cast<float>(hi) * kFixedToVoxels;
}

std::size_t automaticPointCount(Dims dims) {
  const double points = std::round(kDefaultBlackFraction * static_cast<double>(voxelCount(dims)));
  return std::clamp<std::size_t>(static_cast<std::size_t>(points), 1, kMaxSparsityPoints);
}

// What makeSparsityMask runs: the automatic values resolved (see kDefaultBlackFraction). On
// grids so large that an automatic value would break a memory limit, the value is moved to the
// limit (fewer points, a larger radius) rather than failing.
struct ResolvedParams {
  std::size_t points = 0;  // poisson: how many of the maximal set to keep, 0 = all
  float radius = 0.0f;
  bool radiusFromPoints = false;  // poisson: radius derived from --sparsity-points
};

// Poisson with a point count: a radius whose maximal set has about this many times more points,
// of which a random subset of exactly the count is kept. Stopping the sampling at the count
// instead would leave the last part of the volume (in the order it grows) empty.
constexpr double kPoissonSurplus = 1.1;

ResolvedParams resolve(const SparsityParams& params, Dims dims) {
  ResolvedParams resolved;
  const auto voxels = static_cast<double>(voxelCount(dims));
  const auto given = static_cast<std::size_t>(std::max(params.points, 0));
  switch (params.distribution) {
    case SparsityDistribution::None:
    case SparsityDistribution::Checkerboard: break;
    case SparsityDistribution::Halton:
    case SparsityDistribution::Hammersley:
      resolved.points = given > 0 ? given : automaticPointCount(dims);
      break;
    case SparsityDistribution::PoissonApprox:
      resolved.points =
          given > 0 ? given : std::min(automaticPointCount(dims), kAutomaticBestCandidatePoints);
      break;
    case SparsityDistribution::Poisson:
      resolved.points = given;
      if (params.radius > 0.0f) {
        resolved.radius = params.radius;
        break;
      }
      if (given == 0) resolved.points = automaticPointCount(dims);
      resolved.radius =
          std::max(radiusForVolume(kPoissonDensity * voxels /
                                   (kPoissonSurplus * static_cast<double>(resolved.points))),
                   kMinSparsityRadius);
      resolved.radiusFromPoints = given > 0;
      if (given == 0 && !poissonFits(dims, resolved.radius))
        resolved.radius = smallestRadiusThatFits([&](float r) { return poissonFits(dims, r); },
                                                 largestAxis(dims));
      break;
    case SparsityDistribution::Jitter:
      resolved.radius = params.radius;
      if (params.radius > 0.0f) break;
      resolved.radius = radiusForVolume(kJitterDensity / kDefaultBlackFraction);
      if (!jitterFits(dims, resolved.radius))
        resolved.radius =
            smallestRadiusThatFits([&](float r) { return jitterFits(dims, r); }, largestAxis(dims));
      break;
  }
  return resolved;
}

// Keeps `count` of the points, chosen uniformly at random (a partial Fisher-Yates shuffle).
void keepRandomSubset(std::vector<glm::vec3>& points, std::size_t count, std::uint64_t seed) {
  if (count == 0 || points.size() <= count) return;
  Random random(seed, kSubsetStream);
  for (std::size_t i = 0; i < count; ++i)
    std::swap(points[i], points[i + random.below(points.size() - i)]);
  points.resize(count);
}

// phi_b(i) as one integer (the mirrored digits) over base^digits: a single rounding at the end,
// so the value is the same on every machine (no running floating-point sum to contract or
// reorder). Digits past a 64-bit denominator are worth less than base * 2^-64 and dropped.
// Halton and Hammersley call it with constant bases, where division becomes multiplication.
template <class Base>
double mirroredDigitsIn(Base base, std::uint64_t index) {
  std::uint64_t mirrored = 0, denominator = 1;
  const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() / base;
  while (index > 0 && denominator <= limit) {
    mirrored = mirrored * base + index % base;
    denominator *= base;
    index /= base;
  }
  return static_cast<double>(mirrored) / static_cast<double>(denominator);
}
template <std::uint64_t kBase>
double mirroredDigits(std::uint64_t index) {
  return mirroredDigitsIn(std::integral_constant<std::uint64_t, kBase>{}, index);
}
double mirroredDigits(std::uint64_t base, std::uint64_t index) {
  return mirroredDigitsIn(base, index);
}

// phi_b(1), phi_b(2), ... in order, for Halton and Hammersley: the mirrored digits of i as one
// integer over base^K (K digits hold every i <= count), updated like an odometer, O(1) per step
// on average. Both integers stay below 2^53, so the quotient is the same double as
// radicalInverse(b, i): the same rational, rounded once.
class MirroredCounter {
 public:
  MirroredCounter(std::uint64_t base, std::uint64_t count) : base_(base) {
    while (denominator_ <= count &&
           denominator_ <= std::numeric_limits<std::uint64_t>::max() / base) {
      denominator_ *= base;
      ++digits_;
    }
    std::uint64_t weight = denominator_;
    for (int j = 0; j < digits_; ++j) weights_[static_cast<std::size_t>(j)] = weight /= base;
  }

  double next() {
    for (std::size_t j = 0; j < static_cast<std::size_t>(digits_); ++j) {
      if (++indexDigits_[j] < base_) {
        mirrored_ += weights_[j];
        break;
      }
      indexDigits_[j] = 0;
      mirrored_ -= (base_ - 1) * weights_[j];
    }
    return static_cast<double>(mirrored_) / static_cast<double>(denominator_);
  }

 private:
  static constexpr int kMaxDigits = 64;
  std::uint64_t base_;
  std::uint64_t denominator_ = 1;
  std::uint64_t mirrored_ = 0;
  int digits_ = 0;
  std::array<std::uint64_t, kMaxDigits> weights_{};
  std::array<std::uint64_t, kMaxDigits> indexDigits_{};
};

// Voxel containing a point; points are inside the volume by construction, the clamp only guards
// the floor of a coordinate that rounded up to the far face.
std::size_t voxelOf(Dims dims, const glm::vec3& p) {
  const auto axis = [](float v, int n) { return std::clamp(static_cast<int>(v), 0, n - 1); };
  return voxelIndex(dims, axis(p.x, dims.x), axis(p.y, dims.y), axis(p.z, dims.z));
}

// A coordinate t * n with t in [0, 1], moved inside [0, n) if rounding (or t = 1) put it on the
// far face.
float insideAxis(double t, int n) {
  const auto v = static_cast<float>(t * static_cast<double>(n));
  const float limit = static_cast<float>(n);
  return v < limit ? v : std::nextafter(limit, 0.0f);
}

// Number of voxels on each diagonal plane i + j + k = s of the grid.
std::vector<std::uint64_t> diagonalPlaneCounts(Dims dims) {
  const std::size_t planes = static_cast<std::size_t>(dims.x + dims.y + dims.z - 2);
  // Voxels of the xy-plane with i + j = t, then summed over k by a running window.
  std::vector<std::uint64_t> xy(planes, 0);
  for (int t = 0; t <= dims.x + dims.y - 2; ++t)
    xy[static_cast<std::size_t>(t)] =
        static_cast<std::uint64_t>(std::min(dims.x - 1, t) - std::max(0, t - dims.y + 1) + 1);
  std::vector<std::uint64_t> counts(planes, 0);
  std::uint64_t window = 0;
  for (std::size_t s = 0; s < planes; ++s) {
    window += xy[s];
    if (s >= static_cast<std::size_t>(dims.z)) window -= xy[s - static_cast<std::size_t>(dims.z)];
    counts[s] = window;
  }
  return counts;
}

bool isBlack(const CheckerboardPattern& pattern, std::uint64_t s) {
  return (s * static_cast<std::uint64_t>(pattern.black)) %
             static_cast<std::uint64_t>(pattern.period) <
         static_cast<std::uint64_t>(pattern.black);
}

// ---- Exact Poisson disk (Bridson 2007)
// -----------------------------------------------------------
//
// The volume is sampled in regions: slabs of grid cell layers along z, sampled concurrently, then
// the bands between them. A region has its own background grid (the same x and y as the whole
// volume's, its own layers along z plus padding), random stream and active list, so threads
// share nothing they write, and the samples are the same whatever the thread timing or count.

// A sample closer than r to a candidate lies in one of these rows of cells along x: for each
// (dy, dz) the cells dx = -w..w, an index offset from the candidate's cell and 2w + 1 low bits.
struct PoissonRow {
  std::int64_t nearest2;
  std::ptrdiff_t start;  // index offset of the cell (-w, dy, dz)
  std::uint64_t mask;
};

// What every region of one sampling shares, read-only once made.
struct PoissonSetup {
  PoissonSetup(Dims dims, float radius)
      : extent(fixedExtent(dims)),
        r(fixedRadius(radius)),
        r2(r * r),
        shape(poissonGridShape(dims, r)),
        layers(shape.nz - 2 * static_cast<std::size_t>(shape.reach)),
        toCell(shape.cell) {
    // A cell d away along an axis is at least (|d| - 1) * C + 1 units away along it (cells are
    // half-open integer ranges). Rows are sorted nearest first: three quarters of the conflicts
    // are found in the first five.
    const auto gap = [&](int d) -> std::int64_t {
      return d == 0 ? 0 : (std::abs(d) - 1) * shape.cell + 1;
    };
    const int reach = shape.reach;
    for (int dz = -reach; dz <= reach; ++dz)
      for (int dy = -reach; dy <= reach; ++dy) {
        const std::int64_t nearest2 = gap(dy) * gap(dy) + gap(dz) * gap(dz);
        if (nearest2 >= r2) continue;
        int w = 0;
        while (w < reach && nearest2 + gap(w + 1) * gap(w + 1) < r2) ++w;
        const auto start =
            static_cast<std::ptrdiff_t>(-w) +
            static_cast<std::ptrdiff_t>(shape.nx) *
                (static_cast<std::ptrdiff_t>(dy) + static_cast<std::ptrdiff_t>(shape.ny) * dz);
        rows.push_back({nearest2, start, (std::uint64_t{1} << (2 * w + 1)) - 1});
      }
    std::stable_sort(rows.begin(), rows.end(), [](const PoissonRow& a, const PoissonRow& b) {
      return a.nearest2 < b.nearest2;
    });
  }

  FixedExtent extent;
  std::int64_t r, r2;
  PoissonGridShape shape;  // of the whole volume; regions take cell layers of it along z
  std::size_t layers;  // cell layers along z, without padding: layer l holds z in [l C, l C + C)
  CellDivider toCell;
  std::vector<PoissonRow> rows;  // offsets in any grid with shape.nx by shape.ny cells per layer
};

// Bridson's sampling of the cell layers [first, last) along z, clipped to the volume: new samples
// go only there, and a candidate outside counts as a failed attempt, like one outside the volume.
// `around` holds samples placed before (the slabs on either side of a band): those near enough
// to conflict are in the region's grid, and those whose annulus [r, 2r] reaches into the region
// are active from the start, so each gets k attempts inside it; the slab sampling could not try
// there. With nothing around, the first sample is uniform in the region. Returns the new samples,
// at most maxNew, in the order made.
std::vector<FixedPoint> sampleRegion(const PoissonSetup& setup, std::size_t first, std::size_t last,
                                     std::span<const std::vector<FixedPoint>> around,
                                     Random& random, std::size_t maxNew) {
  const FixedExtent& extent = setup.extent;
  const std::int64_t r = setup.r, r2 = setup.r2;
  const PoissonGridShape& shape = setup.shape;
  const int reach = shape.reach;
  const std::int64_t zLow = static_cast<std::int64_t>(first) * shape.cell;
  const std::int64_t zHigh = std::min(static_cast<std::int64_t>(last) * shape.cell, extent.z);
  // Padding along z: `reach` layers of conflicts, and for samples placed around the region also
  // the layers up to 2r away, whose annulus reaches in. Along x and y the grid is padded by
  // `reach` empty cells, so the rows need no bounds checks.
  const auto pad = static_cast<std::size_t>(around.empty() ? reach : 2 * reach);
  const std::size_t nx = shape.nx, ny = shape.ny, nz = last - first + 2 * pad;

  // Bridson's grid: sample index + 1 per cell (0 = empty). An occupancy bit per cell (1/32 of
  // the grid's memory) answers a row with one load; only occupied cells touch the grid and the
  // samples.
  std::vector<std::uint32_t> grid(nx * ny * nz, 0);
  std::vector<std::uint8_t> occupied(grid.size() / 8 + 16, 0);
  std::vector<FixedPoint> samples;
  struct Cell {
    std::size_t x, y, z, index;
  };
  const auto cellOf = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    Cell c{static_cast<std::size_t>(setup.toCell(x) + reach),
           static_cast<std::size_t>(setup.toCell(y) + reach),
           static_cast<std::size_t>(setup.toCell(z)) + pad - first, 0};
    c.index = c.x + nx * (c.y + ny * c.z);
    return c;
  };
  const auto conflicts = [&](std::int64_t x, std::int64_t y, std::int64_t z, std::size_t cell) {
    for (const PoissonRow& row : setup.rows) {
      const auto begin = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(cell) + row.start);
      std::uint64_t bits;
      std::memcpy(&bits, occupied.data() + begin / 8, sizeof bits);
      for (bits = (bits >> (begin % 8)) & row.mask; bits != 0; bits &= bits - 1) {
        const FixedPoint& other =
            samples[grid[begin + static_cast<std::size_t>(std::countr_zero(bits))] - 1];
        const std::int64_t dx = other.x - x, dy = other.y - y, dz = other.z - z;
        if (dx * dx + dy * dy + dz * dz < r2) return true;
      }
    }
    return false;
  };

  // The active list, bucketed by tiles of the grid. Bridson draws the next active sample
  // uniformly from all of them; drawing it uniformly from the first non-empty tile (z, y, x
  // order) instead keeps the grid around the draws in cache, which halves the time at 256^3
  // where the grid is tens of MB. What the algorithm guarantees is unchanged: the minimum
  // distance, and a sample leaves the active list only after k candidates around it failed.
  constexpr std::size_t kTileCellsXY = 16, kTileCellsZ = 8;
  const std::size_t tilesX = nx / kTileCellsXY + 1, tilesY = ny / kTileCellsXY + 1;
  std::vector<std::vector<std::uint32_t>> tiles(tilesX * tilesY * (nz / kTileCellsZ + 1));
  std::size_t firstTile = tiles.size();
  const auto activate = [&](const Cell& cell) {
    const std::size_t tile =
        cell.x / kTileCellsXY + tilesX * (cell.y / kTileCellsXY + tilesY * (cell.z / kTileCellsZ));
    tiles[tile].push_back(static_cast<std::uint32_t>(samples.size() - 1));
    firstTile = std::min(firstTile, tile);
  };
  const auto add = [&](std::int64_t x, std::int64_t y, std::int64_t z, const Cell& cell) {
    samples.push_back(
        {static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), static_cast<std::int32_t>(z)});
    grid[cell.index] = static_cast<std::uint32_t>(samples.size());
    occupied[cell.index / 8] =
        static_cast<std::uint8_t>(occupied[cell.index / 8] | (1u << (cell.index % 8)));
  };

  for (const std::vector<FixedPoint>& placed : around)
    for (const FixedPoint& p : placed) {
      const auto layer = static_cast<std::size_t>(setup.toCell(p.z));
      if (layer + pad < first || layer >= last + pad) continue;
      const Cell cell = cellOf(p.x, p.y, p.z);
      add(p.x, p.y, p.z, cell);
      if (p.z + 2 * r >= zLow && p.z - 2 * r < zHigh) activate(cell);
    }
  const std::size_t placedCount = samples.size();
  if (around.empty()) {
    const std::uint64_t bits = random.next();
    const std::int64_t x = scaled21(bits, 0, extent.x), y = scaled21(bits, 1, extent.y),
                       z = zLow + scaled21(bits, 2, zHigh - zLow);
    const Cell cell = cellOf(x, y, z);
    add(x, y, z, cell);
    activate(cell);
  }

  // Candidate offsets, uniform in the spherical annulus [r, 2r] (Bridson 2007) by rejection from
  // the cube [-2r, 2r]^3 (46 % accepted), made in batches without a branch per try.
  constexpr int kTries = 32;
  std::array<FixedPoint, kTries> offsets;
  int offsetCount = 0, offsetNext = 0;
  const std::int64_t span = 4 * r + 1;
  const auto nextOffset = [&]() -> const FixedPoint& {
    while (offsetNext == offsetCount) {
      offsetNext = offsetCount = 0;
      for (int i = 0; i < kTries; ++i) {
        const std::uint64_t bits = random.next();
        const std::int64_t dx = scaled21(bits, 0, span) - 2 * r;
        const std::int64_t dy = scaled21(bits, 1, span) - 2 * r;
        const std::int64_t dz = scaled21(bits, 2, span) - 2 * r;
        const std::int64_t d2 = dx * dx + dy * dy + dz * dz;
        offsets[static_cast<std::size_t>(offsetCount)] = {static_cast<std::int32_t>(dx),
                                                          static_cast<std::int32_t>(dy),
                                                          static_cast<std::int32_t>(dz)};
        offsetCount += static_cast<std::uint64_t>(d2 - r2) <= static_cast<std::uint64_t>(3 * r2);
      }
    }
    return offsets[static_cast<std::size_t>(offsetNext++)];
  };

  while (samples.size() - placedCount < maxNew) {
    while (firstTile < tiles.size() && tiles[firstTile].empty()) ++firstTile;
    if (firstTile == tiles.size()) break;
    // A reference to the tile's vector stays valid while activate() appends to it or to others.
    std::vector<std::uint32_t>& active = tiles[firstTile];
    const std::size_t slot = random.below(active.size());
    const FixedPoint centre = samples[active[slot]];
    // A sample placed below or above a band tries only the half of its annulus that faces the
    // band: the other half lies in its own slab, where every attempt would fail. Mirroring those
    // attempts (dz -> |dz| towards the band) keeps the candidates uniform on the facing half.
    // Without it, twice as many random probes in a band as elsewhere were r from every sample
    // (1.8 % against 0.9 %); with it, as many (0.8-0.9 %).
    const int towards = centre.z < zLow ? 1 : centre.z >= zHigh ? -1 : 0;
    bool emitted = false;
    for (int attempt = 0; attempt < kPoissonAttempts && !emitted; ++attempt) {
      const FixedPoint& offset = nextOffset();
      const std::int64_t dz = towards == 0 ? offset.z : towards * std::abs(offset.z);
      const std::int64_t x = centre.x + offset.x, y = centre.y + offset.y, z = centre.z + dz;
      if ((static_cast<std::uint64_t>(x) >= static_cast<std::uint64_t>(extent.x)) |
          (static_cast<std::uint64_t>(y) >= static_cast<std::uint64_t>(extent.y)) |
          (static_cast<std::uint64_t>(z - zLow) >= static_cast<std::uint64_t>(zHigh - zLow)))
        continue;
      const Cell cell = cellOf(x, y, z);
      if (!conflicts(x, y, z, cell.index)) {
        add(x, y, z, cell);
        activate(cell);
        emitted = true;
      }
    }
    if (!emitted) {
      active[slot] = active.back();
      active.pop_back();
    }
  }
  samples.erase(samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(placedCount));
  return samples;
}

// Slabs of at least this many cell layers (about 55 r, so the bands of about 1.2 r between them
// add little work: 3 % of the time at 256^3), and at most kMaxPoissonSlabs of them, a power of
// two so that 2 or 4 hardware threads get equal shares. The count follows from the volume and
// radius alone, never from the machine, and so do the samples. 256^3 with a radius of 1.7 to 2
// voxels (1M points) has 2 slabs; 4 start at about 275 voxels along z.
constexpr std::size_t kMinPoissonSlabLayers = 64;
constexpr std::size_t kMaxPoissonSlabs = 4;

// Slab s covers the cell layers [bounds[2s], bounds[2s + 1]), the band above it
// [bounds[2s + 1], bounds[2s + 2]). A band is `reach` layers thick (reach C >= r), so samples of
// two slabs are always at least r apart, and the slabs can be sampled independently.
std::vector<std::size_t> poissonSlabBounds(const PoissonSetup& setup) {
  const auto band = static_cast<std::size_t>(setup.shape.reach);
  std::size_t slabs = 1;
  while (2 * slabs <= kMaxPoissonSlabs &&
         2 * slabs * kMinPoissonSlabLayers + (2 * slabs - 1) * band <= setup.layers)
    slabs *= 2;
  const std::size_t slabLayers = setup.layers - (slabs - 1) * band;
  std::vector<std::size_t> bounds;
  for (std::size_t s = 0; s < slabs; ++s) {
    bounds.push_back(s * band + s * slabLayers / slabs);
    bounds.push_back(s * band + (s + 1) * slabLayers / slabs);
  }
  return bounds;
}

}  // namespace

Result<void> validate(const SparsityParams& params, Dims dims) {
  if (!validDims(dims) || voxelCount(dims) > kMaxVoxels)
    return inputError("sparsity mask: grid " + gridText(dims) + " must have 1.." +
                      std::to_string(kMaxAxisSize) + " voxels per axis and at most " +
                      std::to_string(kMaxVoxels) + " voxels");
  const std::size_t voxels = voxelCount(dims);
  if (params.points < 0 || static_cast<std::size_t>(params.points) > voxels)
    return parameterError("lic.sparsity.points", "must be in [0, " + std::to_string(voxels) +
                                                     "] (0 = automatic, at most one per voxel of " +
                                                     gridText(dims) + "), got " +
                                                     std::to_string(params.points));
  const float largest = largestAxis(dims);
  if (!(params.radius == 0.0f || (params.radius >= kMinSparsityRadius && params.radius <= largest)))
    return parameterError("lic.sparsity.radius", "must be 0 (automatic) or in [" +
                                                     formatNumber(kMinSparsityRadius) + ", " +
                                                     formatNumber(largest) + "] voxels, got " +
                                                     formatNumber(params.radius));
  if (!(params.ratio > 0.0f && params.ratio < 1.0f))
    return parameterError("lic.sparsity.ratio",
                          "must be in (0, 1), got " + formatNumber(params.ratio));

  const ResolvedParams resolved = resolve(params, dims);
  const std::size_t pointLimit = params.distribution == SparsityDistribution::PoissonApprox
                                     ? kMaxBestCandidatePoints
                                     : kMaxSparsityPoints;
  if (resolved.points > pointLimit)
    return parameterError("lic.sparsity.points",
                          "must be at most " + std::to_string(pointLimit) + " for " +
                              std::string(enumName(params.distribution)) +
                              (params.distribution == SparsityDistribution::PoissonApprox
                                   ? " (its time grows with the square of the points)"
                                   : "") +
                              ", got " + std::to_string(params.points));
  if (params.distribution == SparsityDistribution::Poisson && !poissonFits(dims, resolved.radius)) {
    const float smallest =
        smallestRadiusThatFits([&](float r) { return poissonFits(dims, r); }, largest);
    const std::string problem = " for poisson on " + gridText(dims) +
                                ": its search grid would exceed " +
                                std::to_string(kMaxPoissonGridCells) + " cells; ";
    if (resolved.radiusFromPoints)
      return parameterError("lic.sparsity.points", std::to_string(params.points) + " is too many" +
                                                       problem + "give lic.sparsity.radius " +
                                                       formatNumber(smallest) + " or more");
    return parameterError("lic.sparsity.radius", formatNumber(resolved.radius) + " is too small" +
                                                     problem + "use " + formatNumber(smallest) +
                                                     " or more");
  }
  if (params.distribution == SparsityDistribution::Jitter && !jitterFits(dims, resolved.radius))
    return parameterError("lic.sparsity.radius",
                          formatNumber(resolved.radius) + " is too small for jitter on " +
                              gridText(dims) + ": more than " + std::to_string(kMaxSparsityPoints) +
                              " cells; use " +
                              formatNumber(smallestRadiusThatFits(
                                  [&](float r) { return jitterFits(dims, r); }, largest)) +
                              " or more");
  return {};
}

double radicalInverse(std::uint32_t base, std::uint64_t index) {
  double value = 0.0;
  switch (base) {
    case 0:
    case 1: return 0.0;
    case 2: value = mirroredDigits<2>(index); break;
    case 3: value = mirroredDigits<3>(index); break;
    case 5: value = mirroredDigits<5>(index); break;
    default: value = mirroredDigits(base, index); break;
  }
  // Only indices near 2^64 round up to 1.
  return std::min(value, std::nextafter(1.0, 0.0));
}

std::vector<glm::vec3> haltonPoints(Dims dims, std::size_t count) {
  std::vector<glm::vec3> points;
  if (!validDims(dims)) return points;
  points.reserve(count);
  MirroredCounter phi2(2, count), phi3(3, count), phi5(5, count);
  for (std::size_t i = 1; i <= count; ++i)
    points.emplace_back(insideAxis(phi2.next(), dims.x), insideAxis(phi3.next(), dims.y),
                        insideAxis(phi5.next(), dims.z));
  return points;
}

std::vector<glm::vec3> hammersleyPoints(Dims dims, std::size_t count) {
  std::vector<glm::vec3> points;
  if (!validDims(dims)) return points;
  points.reserve(count);
  MirroredCounter phi2(2, count), phi3(3, count);
  for (std::size_t i = 1; i <= count; ++i)
    points.emplace_back(insideAxis(static_cast<double>(i) / static_cast<double>(count), dims.x),
                        insideAxis(phi2.next(), dims.y), insideAxis(phi3.next(), dims.z));
  return points;
}

std::vector<glm::vec3> poissonDiskPoints(Dims dims, float radius, std::uint64_t seed,
                                         std::size_t maxPoints, unsigned threads) {
  std::vector<glm::vec3> result;
  if (!validDims(dims) || maxPoints == 0) return result;
  const PoissonSetup setup(dims, radius);
  const std::vector<std::size_t> bounds = poissonSlabBounds(setup);
  const std::size_t slabs = bounds.size() / 2;

  std::vector<std::vector<FixedPoint>> slabSamples(slabs), bandSamples(slabs - 1);
  if (slabs == 1) {
    Random random(seed, kPoissonStream);
    slabSamples[0] = sampleRegion(setup, 0, setup.layers, {}, random, maxPoints);
  } else {
    // The slabs at once, each from its own stream of the seed.
    parallelFor(slabs, threads, [&](std::size_t s) {
      Random random(seed, kPoissonSlabStream + s);
      slabSamples[s] = sampleRegion(setup, bounds[2 * s], bounds[2 * s + 1], {}, random, maxPoints);
    });
    // Then the bands, each started from the samples of the slabs on either side. Bands are a
    // slab apart and read the slabs only, so they too can be sampled at once. The points are
    // listed in z order (slab, band, slab, ...) up to maxPoints, so a band above slabs that hold
    // maxPoints already is not needed.
    std::size_t bands = 0, below = slabSamples[0].size();
    while (bands + 1 < slabs && below < maxPoints) below += slabSamples[++bands].size();
    parallelFor(bands, threads, [&](std::size_t b) {
      Random random(seed, kPoissonBandStream + b);
      bandSamples[b] = sampleRegion(setup, bounds[2 * b + 1], bounds[2 * b + 2],
                                    std::span(slabSamples).subspan(b, 2), random, maxPoints);
    });
  }

  std::size_t total = 0;
  for (std::size_t s = 0; s < slabs; ++s)
    total += slabSamples[s].size() + (s < bandSamples.size() ? bandSamples[s].size() : 0);
  result.reserve(std::min(total, maxPoints));
  const auto append = [&](const std::vector<FixedPoint>& samples) {
    for (const FixedPoint& p : samples) {
      if (result.size() == maxPoints) return;
      result.push_back(toVoxels(p));
    }
  };
  for (std::size_t s = 0; s < slabs; ++s) {
    append(slabSamples[s]);
    if (s < bandSamples.size()) append(bandSamples[s]);
  }
  return result;
}

std::vector<std::pair<float, float>> poissonDiskBands(Dims dims, float radius) {
  std::vector<std::pair<float, float>> bands;
  if (!validDims(dims)) return bands;
  const PoissonSetup setup(dims, radius);
  const std::vector<std::size_t> bounds = poissonSlabBounds(setup);
  const auto z = [&](std::size_t layer) {
    return static_cast<float>(static_cast<std::int64_t>(layer) * setup.shape.cell) * kFixedToVoxels;
  };
  for (std::size_t b = 1; b + 1 < bounds.size(); b += 2)
    bands.emplace_back(z(bounds[b]), z(bounds[b + 1]));
  return bands;
}

std::vector<glm::vec3> bestCandidatePoints(Dims dims, std::size_t count, int candidatesPerPoint,
                                           std::uint64_t seed) {
  std::vector<glm::vec3> result;
  if (!validDims(dims) || count == 0) return result;
  const FixedExtent extent = fixedExtent(dims);
  const auto m = static_cast<std::uint64_t>(std::max(candidatesPerPoint, 1));
  Random random(seed, kBestCandidateStream);
  const auto candidate = [&] {
    const std::uint64_t bits = random.next();
    return FixedPoint{static_cast<std::int32_t>(scaled21(bits, 0, extent.x)),
                      static_cast<std::int32_t>(scaled21(bits, 1, extent.y)),
                      static_cast<std::int32_t>(scaled21(bits, 2, extent.z))};
  };

  // A uniform grid of linked lists answers "is a point within d?" and "how far is the nearest
  // point?" from nearby cells only. Its cell is the points' spacing (V / n)^(1/3), about the
  // winning distance, so "within d" looks at 8 cells or fewer; it is rebuilt whenever n doubles.
  // The grid only speeds the search up: distances are exact integers, so the points chosen do
  // not depend on it.
  std::vector<FixedPoint> points;
  points.reserve(count);
  std::vector<std::int32_t> next;  // next point in the same cell, -1 ends a list
  next.reserve(count);
  std::vector<std::int32_t> heads;
  std::int64_t cell = 1, cellsX = 1, cellsY = 1, cellsZ = 1;
  CellDivider toCell(1);
  std::size_t builtAt = 0;
  const auto cellAlong = [&](std::int64_t v, std::int64_t cells) {
    return std::clamp<std::int64_t>(toCell(v), 0, cells - 1);
  };
  const auto cellIndex = [&](std::int64_t cx, std::int64_t cy, std::int64_t cz) {
    return static_cast<std::size_t>(cx + cellsX * (cy + cellsY * cz));
  };
  const auto insert = [&](std::size_t index) {
    const FixedPoint& p = points[index];
    const std::size_t c =
        cellIndex(cellAlong(p.x, cellsX), cellAlong(p.y, cellsY), cellAlong(p.z, cellsZ));
    next[index] = heads[c];
    heads[c] = static_cast<std::int32_t>(index);
  };
  const auto rebuild = [&] {
    builtAt = points.size();
    const double spacing =
        std::cbrt(static_cast<double>(voxelCount(dims)) / static_cast<double>(builtAt));
    cell = std::max<std::int64_t>(
        kFixedOne / 4, static_cast<std::int64_t>(spacing * static_cast<double>(kFixedOne)));
    toCell = CellDivider(cell);
    cellsX = (extent.x + cell - 1) / cell;
    cellsY = (extent.y + cell - 1) / cell;
    cellsZ = (extent.z + cell - 1) / cell;
    heads.assign(static_cast<std::size_t>(cellsX * cellsY * cellsZ), -1);
    for (std::size_t i = 0; i < points.size(); ++i) insert(i);
  };
  const auto anyIn = [&](std::size_t c, const FixedPoint& q, std::int64_t limit2) {
    for (std::int32_t i = heads[c]; i >= 0; i = next[static_cast<std::size_t>(i)])
      if (distanceSquared(points[static_cast<std::size_t>(i)], q) <= limit2) return true;
    return false;
  };
  // Is a point within distance^2 <= limit2 of q (limit <= `within` along each axis)? The cell of
  // q first, where a close point most often is.
  const auto anyWithin = [&](const FixedPoint& q, std::int64_t limit2, std::int64_t within) {
    const std::int64_t qx = cellAlong(q.x, cellsX), qy = cellAlong(q.y, cellsY),
                       qz = cellAlong(q.z, cellsZ);
    if (anyIn(cellIndex(qx, qy, qz), q, limit2)) return true;
    const std::int64_t x0 = cellAlong(q.x - within, cellsX), x1 = cellAlong(q.x + within, cellsX);
    const std::int64_t y0 = cellAlong(q.y - within, cellsY), y1 = cellAlong(q.y + within, cellsY);
    const std::int64_t z0 = cellAlong(q.z - within, cellsZ), z1 = cellAlong(q.z + within, cellsZ);
    for (std::int64_t cz = z0; cz <= z1; ++cz)
      for (std::int64_t cy = y0; cy <= y1; ++cy)
        for (std::int64_t cx = x0; cx <= x1; ++cx)
          if ((cx != qx || cy != qy || cz != qz) && anyIn(cellIndex(cx, cy, cz), q, limit2))
            return true;
    return false;
  };
  // Exact squared distance to the nearest point: shells of cells around q's cell, until a
  // shell's nearest possible point ((shell - 1) * cell + 1 away along an axis) is no closer
  // than the best so far.
  const auto nearest2 = [&](const FixedPoint& q) {
    std::int64_t best = std::numeric_limits<std::int64_t>::max();
    const std::int64_t qx = cellAlong(q.x, cellsX), qy = cellAlong(q.y, cellsY),
                       qz = cellAlong(q.z, cellsZ);
    const std::int64_t shells =
        std::max({qx, qy, qz, cellsX - 1 - qx, cellsY - 1 - qy, cellsZ - 1 - qz});
    for (std::int64_t shell = 0; shell <= shells; ++shell) {
      const std::int64_t gap = shell == 0 ? 0 : (shell - 1) * cell + 1;
      if (gap * gap >= best) break;
      for (std::int64_t cz = std::max<std::int64_t>(qz - shell, 0);
           cz <= std::min(qz + shell, cellsZ - 1); ++cz)
        for (std::int64_t cy = std::max<std::int64_t>(qy - shell, 0);
             cy <= std::min(qy + shell, cellsY - 1); ++cy) {
          // Rows inside the shell only contribute their two ends.
          const bool inside = std::abs(cz - qz) < shell && std::abs(cy - qy) < shell;
          const std::int64_t step = inside ? 2 * shell : 1;
          for (std::int64_t cx = qx - shell; cx <= qx + shell; cx += step) {
            if (cx < 0 || cx >= cellsX) continue;
            for (std::int32_t i = heads[cellIndex(cx, cy, cz)]; i >= 0;
                 i = next[static_cast<std::size_t>(i)])
              best = std::min(best, distanceSquared(points[static_cast<std::size_t>(i)], q));
          }
        }
    }
    return best;
  };

  // Witnesses: per cell of a finer grid (half the final spacing), a point near the cell's
  // centre, usually the nearest. A candidate whose witness is within the best distance is out
  // after one distance; only the others need the grid search. Each new point takes over the
  // cells whose centres it is closer to, found by a flood fill from its own cell.
  const double finalSpacing =
      std::cbrt(static_cast<double>(voxelCount(dims)) / static_cast<double>(count));
  const std::int64_t fine = std::max<std::int64_t>(
      kFixedOne / 4,
      static_cast<std::int64_t>(0.5 * finalSpacing * static_cast<double>(kFixedOne)));
  const CellDivider toFine(fine);
  const std::int64_t fineX = (extent.x + fine - 1) / fine, fineY = (extent.y + fine - 1) / fine,
                     fineZ = (extent.z + fine - 1) / fine;
  const auto fineIndex = [&](std::int64_t fx, std::int64_t fy, std::int64_t fz) {
    return static_cast<std::size_t>(fx + fineX * (fy + fineY * fz));
  };
  std::vector<std::int32_t> witness(static_cast<std::size_t>(fineX * fineY * fineZ), 0);
  std::vector<std::uint32_t> visited(witness.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<std::size_t> flood;
  const auto fineCentre = [&](std::int64_t f) { return f * fine + fine / 2; };
  const auto claim = [&](std::size_t index) {
    const FixedPoint& p = points[index];
    const auto stamp = static_cast<std::uint32_t>(index);
    const std::int64_t px = std::min(toFine(p.x), fineX - 1), py = std::min(toFine(p.y), fineY - 1),
                       pz = std::min(toFine(p.z), fineZ - 1);
    flood.clear();
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const std::int64_t fx = px + dx, fy = py + dy, fz = pz + dz;
          if (fx < 0 || fy < 0 || fz < 0 || fx >= fineX || fy >= fineY || fz >= fineZ) continue;
          const std::size_t f = fineIndex(fx, fy, fz);
          visited[f] = stamp;
          flood.push_back(f);
        }
    while (!flood.empty()) {
      const std::size_t f = flood.back();
      flood.pop_back();
      const auto fx = static_cast<std::int64_t>(f) % fineX,
                 fy = static_cast<std::int64_t>(f) / fineX % fineY,
                 fz = static_cast<std::int64_t>(f) / (fineX * fineY);
      const FixedPoint centre{static_cast<std::int32_t>(fineCentre(fx)),
                              static_cast<std::int32_t>(fineCentre(fy)),
                              static_cast<std::int32_t>(fineCentre(fz))};
      if (distanceSquared(p, centre) >=
          distanceSquared(points[static_cast<std::size_t>(witness[f])], centre))
        continue;
      witness[f] = static_cast<std::int32_t>(index);
      const std::int64_t around[6][3] = {{-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                         {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
      for (const auto& d : around) {
        const std::int64_t nx = fx + d[0], ny = fy + d[1], nz = fz + d[2];
        if (nx < 0 || ny < 0 || nz < 0 || nx >= fineX || ny >= fineY || nz >= fineZ) continue;
        const std::size_t n = fineIndex(nx, ny, nz);
        if (visited[n] == stamp) continue;
        visited[n] = stamp;
        flood.push_back(n);
      }
    }
  };
  const auto witnessOf = [&](const FixedPoint& q) -> const FixedPoint& {
    return points[static_cast<std::size_t>(
        witness[fineIndex(std::min(toFine(q.x), fineX - 1), std::min(toFine(q.y), fineY - 1),
                          std::min(toFine(q.z), fineZ - 1))])];
  };

  // With no points yet all m candidates are equally (infinitely) far and the first wins.
  points.push_back(candidate());
  next.push_back(-1);
  rebuild();
  while (points.size() < count) {
    if (points.size() >= 2 * builtAt) rebuild();
    // Of m * n candidates, the farthest from the points so far; ties keep the earlier one. A
    // candidate with a point within the best distance so far cannot win, which is cheap to see.
    FixedPoint best = candidate();
    std::int64_t best2 = nearest2(best);
    std::int64_t within = isqrt(best2);
    const std::uint64_t candidates = m * points.size();
    for (std::uint64_t c = 1; c < candidates; ++c) {
      const FixedPoint q = candidate();
      if (distanceSquared(witnessOf(q), q) <= best2 || anyWithin(q, best2, within)) continue;
      best = q;  // nothing within the best distance: q is farther
      best2 = nearest2(q);
      within = isqrt(best2);
    }
    points.push_back(best);
    next.push_back(-1);
    insert(points.size() - 1);
    claim(points.size() - 1);
  }

  result.reserve(points.size());
  for (const FixedPoint& p : points) result.push_back(toVoxels(p));
  return result;
}

std::vector<glm::vec3> jitteredPoints(Dims dims, float radius, std::uint64_t seed) {
  std::vector<glm::vec3> result;
  if (!validDims(dims)) return result;
  const FixedExtent extent = fixedExtent(dims);
  const std::int64_t r = fixedRadius(radius);
  const std::int64_t r2 = r * r;
  const std::size_t nx = cellsAlong(extent.x, r), ny = cellsAlong(extent.y, r),
                    nz = cellsAlong(extent.z, r);
  // Cells have side r, so a kept point closer than r sits in one of the 26 neighbouring cells;
  // of those, the 13 before this one in scan order can hold kept points. Two z-layers suffice.
  struct Slot {
    FixedPoint p;
    bool kept = false;
  };
  std::vector<Slot> layers(2 * nx * ny);
  const auto slot = [&](std::size_t cx, std::size_t cy, std::size_t cz) -> Slot& {
    return layers[cx + nx * (cy + ny * (cz & 1))];
  };
  // Counter-based: cell c's point depends only on (seed, c).
  const std::uint64_t key = noiseHash(seed, kJitterStream);
  for (std::size_t cz = 0; cz < nz; ++cz)
    for (std::size_t cy = 0; cy < ny; ++cy)
      for (std::size_t cx = 0; cx < nx; ++cx) {
        const std::uint64_t bits = noiseHash(key, cx + nx * (cy + ny * cz));
        // Uniform in the cell, clipped to the volume at the far faces.
        const auto jitter = [&](std::size_t c, std::int64_t axisExtent, int bitSlot) {
          const std::int64_t lo = static_cast<std::int64_t>(c) * r;
          return static_cast<std::int32_t>(lo +
                                           scaled21(bits, bitSlot, std::min(r, axisExtent - lo)));
        };
        Slot& here = slot(cx, cy, cz);
        here.p = {jitter(cx, extent.x, 0), jitter(cy, extent.y, 1), jitter(cz, extent.z, 2)};
        here.kept = true;
        for (int dz = -1; dz <= 0 && here.kept; ++dz)
          for (int dy = -1; dy <= 1 && here.kept; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              if (dz == 0 && (dy > 0 || (dy == 0 && dx >= 0))) break;  // not yet visited
              if ((dz < 0 && cz == 0) || (dy < 0 && cy == 0) || (dx < 0 && cx == 0) ||
                  (dx > 0 && cx + 1 == nx) || (dy > 0 && cy + 1 == ny))
                continue;
              const Slot& other =
                  slot(cx + static_cast<std::size_t>(dx), cy + static_cast<std::size_t>(dy),
                       cz + static_cast<std::size_t>(dz));
              if (other.kept && distanceSquared(other.p, here.p) < r2) {
                here.kept = false;
                break;
              }
            }
        if (here.kept) result.push_back(toVoxels(here.p));
      }
  return result;
}

CheckerboardPattern checkerboardPattern(float ratio, Dims dims) {
  const double target = std::clamp(static_cast<double>(ratio), 0.0, 1.0);
  if (!validDims(dims)) return {};
  const std::vector<std::uint64_t> counts = diagonalPlaneCounts(dims);
  const auto voxels = static_cast<double>(voxelCount(dims));
  struct Choice {
    CheckerboardPattern pattern;
    double error;
  };
  std::vector<Choice> choices;
  std::vector<std::uint64_t> perResidue;
  for (int period = 2; period <= kMaxCheckerboardPeriod; ++period) {
    perResidue.assign(static_cast<std::size_t>(period), 0);
    for (std::size_t s = 0; s < counts.size(); ++s)
      perResidue[s % static_cast<std::size_t>(period)] += counts[s];
    for (int black = 1; black < period; ++black) {
      if (std::gcd(black, period) != 1) continue;  // same fraction as a shorter period
      const CheckerboardPattern pattern{black, period};
      std::uint64_t blackVoxels = 0;
      for (std::size_t residue = 0; residue < perResidue.size(); ++residue)
        if (isBlack(pattern, residue)) blackVoxels += perResidue[residue];
      choices.push_back({pattern, std::abs(static_cast<double>(blackVoxels) / voxels - target)});
    }
  }
  double closest = std::numeric_limits<double>::max();
  for (const Choice& c : choices) closest = std::min(closest, c.error);
  // Periods are visited shortest first: the first choice near enough wins.
  const double enough = std::max(closest, 0.01 * std::min(target, 1.0 - target));
  for (const Choice& c : choices)
    if (c.error <= enough) return c.pattern;
  return {};
}

std::vector<glm::vec3> poissonDiskPointsByCount(Dims dims, std::size_t count, std::uint64_t seed) {
  SparsityParams params;
  params.distribution = SparsityDistribution::Poisson;
  params.points = static_cast<int>(std::min<std::size_t>(count, kMaxSparsityPoints));
  params.seed = seed;
  const ResolvedParams resolved = resolve(params, dims);
  std::vector<glm::vec3> points =
      poissonDiskPoints(dims, resolved.radius, seed, kMaxSparsityPoints);
  keepRandomSubset(points, resolved.points, seed);
  return points;
}

Result<SparsityMask> makeSparsityMask(const SparsityParams& params, Dims dims) {
  LIC3D_TRY(validate(params, dims));
  SparsityMask mask;
  mask.dims = dims;
  mask.black.assign(voxelCount(dims), 0);
  const ResolvedParams resolved = resolve(params, dims);
  std::vector<glm::vec3> points;
  switch (params.distribution) {
    case SparsityDistribution::None: return mask;
    case SparsityDistribution::Checkerboard: {
      const CheckerboardPattern pattern = checkerboardPattern(params.ratio, dims);
      std::vector<std::uint8_t> planeIsBlack(static_cast<std::size_t>(dims.x + dims.y + dims.z));
      for (std::size_t s = 0; s < planeIsBlack.size(); ++s) planeIsBlack[s] = isBlack(pattern, s);
      for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
          for (int i = 0; i < dims.x; ++i) {
            const std::uint8_t black = planeIsBlack[static_cast<std::size_t>(i + j + k)];
            mask.black[voxelIndex(dims, i, j, k)] = black;
            mask.blackCount += black;
          }
      return mask;
    }
    case SparsityDistribution::Poisson:
      points = poissonDiskPoints(dims, resolved.radius, params.seed, kMaxSparsityPoints);
      keepRandomSubset(points, resolved.points, params.seed);
      break;
    case SparsityDistribution::PoissonApprox:
      points = bestCandidatePoints(dims, resolved.points, kBestCandidateFactor, params.seed);
      break;
    case SparsityDistribution::Jitter:
      points = jitteredPoints(dims, resolved.radius, params.seed);
      break;
    case SparsityDistribution::Halton: points = haltonPoints(dims, resolved.points); break;
    case SparsityDistribution::Hammersley: points = hammersleyPoints(dims, resolved.points); break;
  }
  for (const glm::vec3& p : points) {
    std::uint8_t& voxel = mask.black[voxelOf(dims, p)];
    mask.blackCount += voxel == 0;
    voxel = 1;
  }
  return mask;
}

Result<SparsityMask> makeSparsityMaskPiece(const SparsityParams& params, const FieldPiece& piece,
                                           Dims dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || piece.offset[a] < 0 || piece.offset[a] + dims[a] > piece.wholeDims[a])
      return inputError("a piece of a field must lie inside the whole grid");
  LIC3D_TRY_ASSIGN(const SparsityMask whole, makeSparsityMask(params, piece.wholeDims));
  SparsityMask mask;
  mask.dims = dims;
  mask.black.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const std::uint8_t black = whole.black[voxelIndex(piece.wholeDims, piece.offset.x + i,
                                                          piece.offset.y + j, piece.offset.z + k)];
        mask.black[voxelIndex(dims, i, j, k)] = black;
        mask.blackCount += black;
      }
  return mask;
}

}  // namespace lic3d
