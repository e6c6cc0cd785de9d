// SPDX-License-Identifier: BSD-3-Clause
// Mitchell's best candidate (1991), the thesis' approximation of Poisson disk; grid and witness
// searches keep its m n^2 / 2 distance tests affordable without changing which points win.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lic/fixed_point.h"
#include "lic/point_sets.h"

namespace lic3d {
using namespace points;
namespace {

// A uniform grid of linked lists answers "is a point within d?" and "how far is the nearest
// point?" from nearby cells only. Its cell is the points' spacing (V / n)^(1/3), about the
// winning distance, so "within d" looks at 8 cells or fewer; it is rebuilt whenever n doubles.
// The grid only speeds the search up: distances are exact integers, so the points chosen do
// not depend on it.
class PointGrid {
 public:
  PointGrid(Dims dims, FixedExtent extent, std::size_t count) : dims_(dims), extent_(extent) {
    points_.reserve(count);
    next_.reserve(count);
  }

  const std::vector<FixedPoint>& points() const { return points_; }

  // The first point, with the grid built around it.
  void start(const FixedPoint& p) {
    points_.push_back(p);
    next_.push_back(-1);
    rebuild();
  }
  void add(const FixedPoint& p) {
    points_.push_back(p);
    next_.push_back(-1);
    insert(points_.size() - 1);
  }
  void rebuildIfDoubled() {
    if (points_.size() >= 2 * builtAt_) rebuild();
  }

  // Is a point within distance^2 <= limit2 of q (limit <= `within` along each axis)? The cell of
  // q first, where a close point most often is.
  bool anyWithin(const FixedPoint& q, std::int64_t limit2, std::int64_t within) const {
    const std::int64_t qx = cellAlong(q.x, cellsX_), qy = cellAlong(q.y, cellsY_),
                       qz = cellAlong(q.z, cellsZ_);
    if (anyIn(cellIndex(qx, qy, qz), q, limit2)) return true;
    const std::int64_t x0 = cellAlong(q.x - within, cellsX_), x1 = cellAlong(q.x + within, cellsX_);
    const std::int64_t y0 = cellAlong(q.y - within, cellsY_), y1 = cellAlong(q.y + within, cellsY_);
    const std::int64_t z0 = cellAlong(q.z - within, cellsZ_), z1 = cellAlong(q.z + within, cellsZ_);
    for (std::int64_t cz = z0; cz <= z1; ++cz)
      for (std::int64_t cy = y0; cy <= y1; ++cy)
        for (std::int64_t cx = x0; cx <= x1; ++cx)
          if ((cx != qx || cy != qy || cz != qz) && anyIn(cellIndex(cx, cy, cz), q, limit2))
            return true;
    return false;
  }

  // Exact squared distance to the nearest point: shells of cells around q's cell, until a
  // shell's nearest possible point ((shell - 1) * cell + 1 away along an axis) is no closer
  // than the best so far.
  std::int64_t nearest2(const FixedPoint& q) const {
    std::int64_t best = std::numeric_limits<std::int64_t>::max();
    const std::int64_t qx = cellAlong(q.x, cellsX_), qy = cellAlong(q.y, cellsY_),
                       qz = cellAlong(q.z, cellsZ_);
    const std::int64_t shells =
        std::max({qx, qy, qz, cellsX_ - 1 - qx, cellsY_ - 1 - qy, cellsZ_ - 1 - qz});
    for (std::int64_t shell = 0; shell <= shells; ++shell) {
      const std::int64_t gap = shell == 0 ? 0 : (shell - 1) * cell_ + 1;
      if (gap * gap >= best) break;
      for (std::int64_t cz = std::max<std::int64_t>(qz - shell, 0);
           cz <= std::min(qz + shell, cellsZ_ - 1); ++cz)
        for (std::int64_t cy = std::max<std::int64_t>(qy - shell, 0);
             cy <= std::min(qy + shell, cellsY_ - 1); ++cy) {
          // Rows inside the shell only contribute their two ends.
          const bool inside = std::abs(cz - qz) < shell && std::abs(cy - qy) < shell;
          const std::int64_t step = inside ? 2 * shell : 1;
          for (std::int64_t cx = qx - shell; cx <= qx + shell; cx += step) {
            if (cx < 0 || cx >= cellsX_) continue;
            for (std::int32_t i = heads_[cellIndex(cx, cy, cz)]; i >= 0;
                 i = next_[static_cast<std::size_t>(i)])
              best = std::min(best, distanceSquared(points_[static_cast<std::size_t>(i)], q));
          }
        }
    }
    return best;
  }

 private:
  std::int64_t cellAlong(std::int64_t v, std::int64_t cells) const {
    return std::clamp<std::int64_t>(toCell_(v), 0, cells - 1);
  }
  std::size_t cellIndex(std::int64_t cx, std::int64_t cy, std::int64_t cz) const {
    return static_cast<std::size_t>(cx + cellsX_ * (cy + cellsY_ * cz));
  }
  void insert(std::size_t index) {
    const FixedPoint& p = points_[index];
    const std::size_t c =
        cellIndex(cellAlong(p.x, cellsX_), cellAlong(p.y, cellsY_), cellAlong(p.z, cellsZ_));
    next_[index] = heads_[c];
    heads_[c] = static_cast<std::int32_t>(index);
  }
  void rebuild() {
    builtAt_ = points_.size();
    const double spacing =
        std::cbrt(static_cast<double>(voxelCount(dims_)) / static_cast<double>(builtAt_));
    cell_ = std::max<std::int64_t>(
        kFixedOne / 4, static_cast<std::int64_t>(spacing * static_cast<double>(kFixedOne)));
    toCell_ = CellDivider(cell_);
    cellsX_ = (extent_.x + cell_ - 1) / cell_;
    cellsY_ = (extent_.y + cell_ - 1) / cell_;
    cellsZ_ = (extent_.z + cell_ - 1) / cell_;
    heads_.assign(static_cast<std::size_t>(cellsX_ * cellsY_ * cellsZ_), -1);
    for (std::size_t i = 0; i < points_.size(); ++i) insert(i);
  }
  bool anyIn(std::size_t c, const FixedPoint& q, std::int64_t limit2) const {
    for (std::int32_t i = heads_[c]; i >= 0; i = next_[static_cast<std::size_t>(i)])
      if (distanceSquared(points_[static_cast<std::size_t>(i)], q) <= limit2) return true;
    return false;
  }

  Dims dims_;
  FixedExtent extent_;
  std::vector<FixedPoint> points_;
  std::vector<std::int32_t> next_;  // next point in the same cell, -1 ends a list
  std::vector<std::int32_t> heads_;
  std::int64_t cell_ = 1, cellsX_ = 1, cellsY_ = 1, cellsZ_ = 1;
  CellDivider toCell_{1};
  std::size_t builtAt_ = 0;
};

// Witnesses: per cell of a finer grid (half the final spacing), a point near the cell's
// centre, usually the nearest. A candidate whose witness is within the best distance is out
// after one distance; only the others need the grid search. Each new point takes over the
// cells whose centres it is closer to, found by a flood fill from its own cell.
class Witnesses {
 public:
  Witnesses(Dims dims, FixedExtent extent, std::size_t count)
      : fine_(fineCell(dims, count)),
        toFine_(fine_),
        fineX_((extent.x + fine_ - 1) / fine_),
        fineY_((extent.y + fine_ - 1) / fine_),
        fineZ_((extent.z + fine_ - 1) / fine_),
        witness_(static_cast<std::size_t>(fineX_ * fineY_ * fineZ_), 0),
        visited_(witness_.size(), std::numeric_limits<std::uint32_t>::max()) {}

  // The witness of q's cell.
  const FixedPoint& of(const std::vector<FixedPoint>& points, const FixedPoint& q) const {
    return points[static_cast<std::size_t>(
        witness_[fineIndex(std::min(toFine_(q.x), fineX_ - 1), std::min(toFine_(q.y), fineY_ - 1),
                           std::min(toFine_(q.z), fineZ_ - 1))])];
  }

  // Point `index` becomes the witness of the cells whose centres it is closer to.
  void claim(const std::vector<FixedPoint>& points, std::size_t index) {
    const FixedPoint& p = points[index];
    const auto stamp = static_cast<std::uint32_t>(index);
    seedAround(p, stamp);
    while (!flood_.empty()) {
      const std::size_t f = flood_.back();
      flood_.pop_back();
      const auto fx = static_cast<std::int64_t>(f) % fineX_,
                 fy = static_cast<std::int64_t>(f) / fineX_ % fineY_,
                 fz = static_cast<std::int64_t>(f) / (fineX_ * fineY_);
      const FixedPoint centre{static_cast<std::int32_t>(fineCentre(fx)),
                              static_cast<std::int32_t>(fineCentre(fy)),
                              static_cast<std::int32_t>(fineCentre(fz))};
      if (distanceSquared(p, centre) >=
          distanceSquared(points[static_cast<std::size_t>(witness_[f])], centre))
        continue;
      witness_[f] = static_cast<std::int32_t>(index);
      const std::int64_t around[6][3] = {{-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                         {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
      for (const auto& d : around) {
        const std::int64_t nx = fx + d[0], ny = fy + d[1], nz = fz + d[2];
        if (!inside(nx, ny, nz)) continue;
        const std::size_t n = fineIndex(nx, ny, nz);
        if (visited_[n] == stamp) continue;
        visited_[n] = stamp;
        flood_.push_back(n);
      }
    }
  }

 private:
  static std::int64_t fineCell(Dims dims, std::size_t count) {
    const double finalSpacing =
        std::cbrt(static_cast<double>(voxelCount(dims)) / static_cast<double>(count));
    return std::max<std::int64_t>(
        kFixedOne / 4,
        static_cast<std::int64_t>(0.5 * finalSpacing * static_cast<double>(kFixedOne)));
  }
  std::size_t fineIndex(std::int64_t fx, std::int64_t fy, std::int64_t fz) const {
    return static_cast<std::size_t>(fx + fineX_ * (fy + fineY_ * fz));
  }
  std::int64_t fineCentre(std::int64_t f) const { return f * fine_ + fine_ / 2; }
  bool inside(std::int64_t fx, std::int64_t fy, std::int64_t fz) const {
    return fx >= 0 && fy >= 0 && fz >= 0 && fx < fineX_ && fy < fineY_ && fz < fineZ_;
  }
  // The flood starts from the 27 cells around p's own.
  void seedAround(const FixedPoint& p, std::uint32_t stamp) {
    const std::int64_t px = std::min(toFine_(p.x), fineX_ - 1),
                       py = std::min(toFine_(p.y), fineY_ - 1),
                       pz = std::min(toFine_(p.z), fineZ_ - 1);
    flood_.clear();
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const std::int64_t fx = px + dx, fy = py + dy, fz = pz + dz;
          if (!inside(fx, fy, fz)) continue;
          const std::size_t f = fineIndex(fx, fy, fz);
          visited_[f] = stamp;
          flood_.push_back(f);
        }
  }

  std::int64_t fine_;
  CellDivider toFine_;
  std::int64_t fineX_, fineY_, fineZ_;
  std::vector<std::int32_t> witness_;
  std::vector<std::uint32_t> visited_;
  std::vector<std::size_t> flood_;
};

}  // namespace

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
  PointGrid grid(dims, extent, count);
  Witnesses witnesses(dims, extent, count);
  const std::vector<FixedPoint>& points = grid.points();

  // With no points yet all m candidates are equally (infinitely) far and the first wins.
  grid.start(candidate());
  while (points.size() < count) {
    grid.rebuildIfDoubled();
    // Of m * n candidates, the farthest from the points so far; ties keep the earlier one. A
    // candidate with a point within the best distance so far cannot win, which is cheap to see.
    FixedPoint best = candidate();
    std::int64_t best2 = grid.nearest2(best);
    std::int64_t within = isqrt(best2);
    const std::uint64_t candidates =
        m * std::min<std::uint64_t>(points.size(), kBestCandidateHistory);
    for (std::uint64_t c = 1; c < candidates; ++c) {
      const FixedPoint q = candidate();
      if (distanceSquared(witnesses.of(points, q), q) <= best2 || grid.anyWithin(q, best2, within))
        continue;
      best = q;  // nothing within the best distance: q is farther
      best2 = grid.nearest2(q);
      within = isqrt(best2);
    }
    grid.add(best);
    witnesses.claim(points, points.size() - 1);
  }

  result.reserve(points.size());
  for (const FixedPoint& p : points) result.push_back(toVoxels(p));
  return result;
}

}  // namespace lic3d
