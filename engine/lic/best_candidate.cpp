// SPDX-License-Identifier: BSD-3-Clause
// Mitchell's best candidate (1991), the thesis' approximation of Poisson disk; grid and witness
// searches keep its m n^2 / 2 distance tests affordable without changing which points win.

#include <algorithm>
#include <cmath>
#include <limits>

#include "lic/fixed_point.h"
#include "lic/point_sets.h"

namespace lic3d {
using namespace points;

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
    const std::uint64_t candidates =
        m * std::min<std::uint64_t>(points.size(), kBestCandidateHistory);
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

}  // namespace lic3d
