// SPDX-License-Identifier: BSD-3-Clause
// Exact Poisson disk sampling (Bridson 2007): slabs sampled at once, then the bands between them,
// so the points never depend on the threads; plus the evenly spread subset that seed noise takes.

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "lic/fixed_point.h"
#include "lic/point_sets.h"
#include "lic/sparsity_automatic.h"

namespace lic3d {
using namespace points;
namespace {

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

// Candidate offsets, uniform in the spherical annulus [r, 2r] (Bridson 2007) by rejection from
// the cube [-2r, 2r]^3 (46 % accepted), made in batches without a branch per try.
class AnnulusOffsets {
 public:
  AnnulusOffsets(std::int64_t r, std::int64_t r2) : r_(r), r2_(r2), span_(4 * r + 1) {}

  const FixedPoint& next(Random& random) {
    while (next_ == count_) {
      next_ = count_ = 0;
      for (int i = 0; i < kTries; ++i) {
        const std::uint64_t bits = random.next();
        const std::int64_t dx = scaled21(bits, 0, span_) - 2 * r_;
        const std::int64_t dy = scaled21(bits, 1, span_) - 2 * r_;
        const std::int64_t dz = scaled21(bits, 2, span_) - 2 * r_;
        const std::int64_t d2 = dx * dx + dy * dy + dz * dz;
        offsets_[static_cast<std::size_t>(count_)] = {static_cast<std::int32_t>(dx),
                                                      static_cast<std::int32_t>(dy),
                                                      static_cast<std::int32_t>(dz)};
        count_ += static_cast<std::uint64_t>(d2 - r2_) <= static_cast<std::uint64_t>(3 * r2_);
      }
    }
    return offsets_[static_cast<std::size_t>(next_++)];
  }

 private:
  static constexpr int kTries = 32;
  std::int64_t r_, r2_, span_;
  std::array<FixedPoint, kTries> offsets_;
  int count_ = 0, next_ = 0;
};

// Bridson's sampling of the cell layers [first, last) along z, clipped to the volume (see
// sampleRegion): the region's grid, its samples and its active list.
class RegionSampler {
 public:
  RegionSampler(const PoissonSetup& setup, std::size_t first, std::size_t last, bool surrounded)
      : setup_(setup),
        first_(first),
        last_(last),
        zLow_(static_cast<std::int64_t>(first) * setup.shape.cell),
        zHigh_(std::min(static_cast<std::int64_t>(last) * setup.shape.cell, setup.extent.z)),
        // Padding along z: `reach` layers of conflicts, and for samples placed around the region
        // also the layers up to 2r away, whose annulus reaches in. Along x and y the grid is
        // padded by `reach` empty cells, so the rows need no bounds checks.
        pad_(static_cast<std::size_t>(surrounded ? 2 * setup.shape.reach : setup.shape.reach)),
        nx_(setup.shape.nx),
        ny_(setup.shape.ny),
        nz_(last - first + 2 * pad_),
        grid_(nx_ * ny_ * nz_, 0),
        occupied_(grid_.size() / 8 + 16, 0),
        tilesX_(nx_ / kTileCellsXY + 1),
        tilesY_(ny_ / kTileCellsXY + 1),
        tiles_(tilesX_ * tilesY_ * (nz_ / kTileCellsZ + 1)),
        firstTile_(tiles_.size()) {}

  // The samples placed before that lie near enough to conflict; those whose annulus reaches into
  // the region are active.
  void placeAround(std::span<const std::vector<FixedPoint>> around) {
    const std::int64_t r = setup_.r;
    for (const std::vector<FixedPoint>& placed : around)
      for (const FixedPoint& p : placed) {
        const auto layer = static_cast<std::size_t>(setup_.toCell(p.z));
        if (layer + pad_ < first_ || layer >= last_ + pad_) continue;
        const Cell cell = cellOf(p.x, p.y, p.z);
        add(p.x, p.y, p.z, cell);
        if (p.z + 2 * r >= zLow_ && p.z - 2 * r < zHigh_) activate(cell);
      }
    placedCount_ = samples_.size();
  }

  // A first sample uniform in the region.
  void placeFirst(Random& random) {
    const std::uint64_t bits = random.next();
    const std::int64_t x = scaled21(bits, 0, setup_.extent.x),
                       y = scaled21(bits, 1, setup_.extent.y),
                       z = zLow_ + scaled21(bits, 2, zHigh_ - zLow_);
    const Cell cell = cellOf(x, y, z);
    add(x, y, z, cell);
    activate(cell);
  }

  // New samples around active ones until none is active or `maxNew` are made.
  void grow(Random& random, std::size_t maxNew) {
    AnnulusOffsets offsets(setup_.r, setup_.r2);
    while (samples_.size() - placedCount_ < maxNew) {
      while (firstTile_ < tiles_.size() && tiles_[firstTile_].empty()) ++firstTile_;
      if (firstTile_ == tiles_.size()) break;
      // A reference to the tile's vector stays valid while activate() appends to it or to others.
      std::vector<std::uint32_t>& active = tiles_[firstTile_];
      const std::size_t slot = random.below(active.size());
      const FixedPoint centre = samples_[active[slot]];
      if (!tryAround(centre, offsets, random)) {
        active[slot] = active.back();
        active.pop_back();
      }
    }
  }

  // The new samples, in the order made.
  std::vector<FixedPoint> take() {
    samples_.erase(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(placedCount_));
    return std::move(samples_);
  }

 private:
  struct Cell {
    std::size_t x, y, z, index;
  };

  // The active list, bucketed by tiles of the grid. Bridson draws the next active sample
  // uniformly from all of them; drawing it uniformly from the first non-empty tile (z, y, x
  // order) instead keeps the grid around the draws in cache, which halves the time at 256^3
  // where the grid is tens of MB. What the algorithm guarantees is unchanged: the minimum
  // distance, and a sample leaves the active list only after k candidates around it failed.
  static constexpr std::size_t kTileCellsXY = 16, kTileCellsZ = 8;

  Cell cellOf(std::int64_t x, std::int64_t y, std::int64_t z) const {
    const int reach = setup_.shape.reach;
    Cell c{static_cast<std::size_t>(setup_.toCell(x) + reach),
           static_cast<std::size_t>(setup_.toCell(y) + reach),
           static_cast<std::size_t>(setup_.toCell(z)) + pad_ - first_, 0};
    c.index = c.x + nx_ * (c.y + ny_ * c.z);
    return c;
  }

  bool conflicts(std::int64_t x, std::int64_t y, std::int64_t z, std::size_t cell) const {
    for (const PoissonRow& row : setup_.rows) {
      const auto begin = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(cell) + row.start);
      std::uint64_t bits;
      std::memcpy(&bits, occupied_.data() + begin / 8, sizeof bits);
      for (bits = (bits >> (begin % 8)) & row.mask; bits != 0; bits &= bits - 1) {
        const FixedPoint& other =
            samples_[grid_[begin + static_cast<std::size_t>(std::countr_zero(bits))] - 1];
        const std::int64_t dx = other.x - x, dy = other.y - y, dz = other.z - z;
        if (dx * dx + dy * dy + dz * dz < setup_.r2) return true;
      }
    }
    return false;
  }

  void activate(const Cell& cell) {
    const std::size_t tile = cell.x / kTileCellsXY +
                             tilesX_ * (cell.y / kTileCellsXY + tilesY_ * (cell.z / kTileCellsZ));
    tiles_[tile].push_back(static_cast<std::uint32_t>(samples_.size() - 1));
    firstTile_ = std::min(firstTile_, tile);
  }

  void add(std::int64_t x, std::int64_t y, std::int64_t z, const Cell& cell) {
    samples_.push_back(
        {static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), static_cast<std::int32_t>(z)});
    grid_[cell.index] = static_cast<std::uint32_t>(samples_.size());
    occupied_[cell.index / 8] =
        static_cast<std::uint8_t>(occupied_[cell.index / 8] | (1u << (cell.index % 8)));
  }

  // Up to k candidates around `centre`; true when one was placed (and made active).
  bool tryAround(const FixedPoint& centre, AnnulusOffsets& offsets, Random& random) {
    const FixedExtent& extent = setup_.extent;
    // A sample placed below or above a band tries only the half of its annulus that faces the
    // band: the other half lies in its own slab, where every attempt would fail. Mirroring those
    // attempts (dz -> |dz| towards the band) keeps the candidates uniform on the facing half.
    // Without it, twice as many random probes in a band as elsewhere were r from every sample
    // (1.8 % against 0.9 %); with it, as many (0.8-0.9 %).
    const int towards = centre.z < zLow_ ? 1 : centre.z >= zHigh_ ? -1 : 0;
    for (int attempt = 0; attempt < kPoissonAttempts; ++attempt) {
      const FixedPoint& offset = offsets.next(random);
      const std::int64_t dz = towards == 0 ? offset.z : towards * std::abs(offset.z);
      const std::int64_t x = centre.x + offset.x, y = centre.y + offset.y, z = centre.z + dz;
      if ((static_cast<std::uint64_t>(x) >= static_cast<std::uint64_t>(extent.x)) |
          (static_cast<std::uint64_t>(y) >= static_cast<std::uint64_t>(extent.y)) |
          (static_cast<std::uint64_t>(z - zLow_) >= static_cast<std::uint64_t>(zHigh_ - zLow_)))
        continue;
      const Cell cell = cellOf(x, y, z);
      if (!conflicts(x, y, z, cell.index)) {
        add(x, y, z, cell);
        activate(cell);
        return true;
      }
    }
    return false;
  }

  const PoissonSetup& setup_;
  std::size_t first_, last_;
  std::int64_t zLow_, zHigh_;
  std::size_t pad_;
  std::size_t nx_, ny_, nz_;
  // Bridson's grid: sample index + 1 per cell (0 = empty). An occupancy bit per cell (1/32 of
  // the grid's memory) answers a row with one load; only occupied cells touch the grid and the
  // samples.
  std::vector<std::uint32_t> grid_;
  std::vector<std::uint8_t> occupied_;
  std::vector<FixedPoint> samples_;
  std::size_t tilesX_, tilesY_;
  std::vector<std::vector<std::uint32_t>> tiles_;
  std::size_t firstTile_;
  std::size_t placedCount_ = 0;
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
  RegionSampler sampler(setup, first, last, !around.empty());
  sampler.placeAround(around);
  if (around.empty()) sampler.placeFirst(random);
  sampler.grow(random, maxNew);
  return sampler.take();
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

}  // namespace lic3d
