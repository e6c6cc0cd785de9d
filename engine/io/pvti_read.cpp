// SPDX-License-Identifier: BSD-3-Clause
// Parallel VTK XML ImageData (.pvti), the file ParaView and VTK write under MPI: a PImageData
// with the whole extent and a Piece (Extent, Source) per process, each a .vti of its own. The
// field is assembled from the pieces by their extents.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "core/text.h"
#include "io/file_util.h"
#include "io/vti.h"
#include "io/vti_file.h"

namespace lic3d {
namespace {

using vti::Extent;

// Every extent is read as 64-bit numbers (vti::parseExtent: each within 2^40 of zero), so a value
// beyond int cannot wrap to a small grid; the error names the file, the element and the attribute.
Result<Extent> readExtent(const std::filesystem::path& path, const pugi::xml_node& node,
                          const char* name) {
  const pugi::xml_attribute attribute = node.attribute(name);
  const std::optional<Extent> extent = vti::parseExtent(attribute.value());
  if (!extent)
    return fileError(path, std::string(node.name()) + " " + name +
                               ": expected 6 whole numbers x0 x1 y0 y1 z0 z1 (each within 2^40 "
                               "of zero) with each first <= last, found " +
                               quoteForMessage(attribute.value()));
  return *extent;
}

std::uint64_t pointsAlong(const Extent& e, std::size_t axis) {
  return static_cast<std::uint64_t>(e.bounds[2 * axis + 1] - e.bounds[2 * axis]) + 1;
}

std::string extentText(const Extent& e) {
  std::string text;
  for (const std::int64_t v : e.bounds) text += (text.empty() ? "" : " ") + std::to_string(v);
  return text;
}

struct PieceRef {
  Extent extent{};
  std::filesystem::path source;
};

// Whether the pieces' points cover every point of `whole`, decided before anything the size of
// the grid is allocated: along each axis the pieces' bounds cut the whole into slabs, and every
// cell of that cut grid must lie in a piece. The cut grid has at most one cell per point of the
// whole (which is within kMaxVoxels) and at most (2 * pieces + 1) cells along each axis.
bool piecesCover(const Extent& whole, const std::vector<PieceRef>& pieces) {
  std::array<std::vector<std::int64_t>, 3> cuts;
  for (std::size_t a = 0; a < 3; ++a) {
    std::vector<std::int64_t>& cut = cuts[a];
    cut = {whole.bounds[2 * a], whole.bounds[2 * a + 1] + 1};
    for (const PieceRef& piece : pieces) {
      cut.push_back(piece.extent.bounds[2 * a]);
      cut.push_back(piece.extent.bounds[2 * a + 1] + 1);
    }
    std::sort(cut.begin(), cut.end());
    cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
  }
  const auto index = [&](std::size_t a, std::int64_t bound) {
    return static_cast<std::size_t>(std::lower_bound(cuts[a].begin(), cuts[a].end(), bound) -
                                    cuts[a].begin());
  };
  const std::size_t nx = cuts[0].size() - 1, ny = cuts[1].size() - 1, nz = cuts[2].size() - 1;
  std::vector<std::uint8_t> covered(nx * ny * nz, 0);
  for (const PieceRef& piece : pieces) {
    const Extent& e = piece.extent;
    const std::size_t x0 = index(0, e.bounds[0]), x1 = index(0, e.bounds[1] + 1);
    const std::size_t y0 = index(1, e.bounds[2]), y1 = index(1, e.bounds[3] + 1);
    const std::size_t z0 = index(2, e.bounds[4]), z1 = index(2, e.bounds[5] + 1);
    for (std::size_t z = z0; z < z1; ++z)
      for (std::size_t y = y0; y < y1; ++y)
        std::fill_n(covered.begin() + static_cast<std::ptrdiff_t>((z * ny + y) * nx + x0), x1 - x0,
                    std::uint8_t{1});
  }
  return std::find(covered.begin(), covered.end(), 0) == covered.end();
}

bool nearlyEqual(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& scale) {
  for (glm::length_t i = 0; i < 3; ++i)
    if (std::abs(a[i] - b[i]) > 1e-6 * std::max({std::abs(a[i]), std::abs(b[i]), scale[i]}))
      return false;
  return true;
}

// Overlapping points hold the same vectors (NaN matching NaN).
bool sameVector(const glm::vec3& a, const glm::vec3& b) {
  for (glm::length_t i = 0; i < 3; ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

}  // namespace

Result<VectorField> readVectorFieldPvti(const std::filesystem::path& path,
                                        std::string_view arrayName, FieldReadInfo* info) {
  LIC3D_TRY_ASSIGN(const std::string text, readFile(path, 64 << 20, false));
  pugi::xml_document document;
  if (!document.load_buffer(text.data(), text.size()))
    return fileError(path, "not a valid XML file");
  const pugi::xml_node root = document.child("VTKFile");
  const pugi::xml_node image = root.child("PImageData");
  if (!root || std::string(root.attribute("type").as_string()) != "PImageData" || !image)
    return fileError(path, "not a parallel VTK image data file (VTKFile type=\"PImageData\")");
  LIC3D_TRY_ASSIGN(const Extent whole, readExtent(path, image, "WholeExtent"));
  if (const std::string problem =
          gridLimitProblem(pointsAlong(whole, 0), pointsAlong(whole, 1), pointsAlong(whole, 2));
      !problem.empty())
    return fileError(
        path, "PImageData WholeExtent " + quoteForMessage(extentText(whole)) + ": " + problem);
  const bool originGiven = static_cast<bool>(image.attribute("Origin"));
  const bool spacingGiven = static_cast<bool>(image.attribute("Spacing"));
  LIC3D_TRY_ASSIGN(const glm::dvec3 wholeOrigin,
                   vti::parseTriple(path, image, "Origin", 0.0, false));
  LIC3D_TRY_ASSIGN(const glm::dvec3 wholeSpacing,
                   vti::parseTriple(path, image, "Spacing", 1.0, true));
  std::vector<PieceRef> pieces;
  const std::filesystem::path folder = path.parent_path();
  for (const pugi::xml_node node : image.children("Piece")) {
    PieceRef piece;
    LIC3D_TRY_ASSIGN(piece.extent, readExtent(path, node, "Extent"));
    for (std::size_t a = 0; a < 3; ++a)
      if (piece.extent.bounds[2 * a] < whole.bounds[2 * a] ||
          piece.extent.bounds[2 * a + 1] > whole.bounds[2 * a + 1])
        return fileError(path, "the Piece Extent " + quoteForMessage(extentText(piece.extent)) +
                                   " leaves the WholeExtent " + quoteForMessage(extentText(whole)));
    const std::string source = node.attribute("Source").as_string();
    if (source.empty()) return fileError(path, "a Piece has no Source file");
    piece.source = folder / source;
    pieces.push_back(std::move(piece));
  }
  if (pieces.empty()) return fileError(path, "no Piece: the file names no data");
  // Before any piece is read or the grid allocated: a small file must not claim a grid its
  // pieces do not fill, nor one the host cannot hold.
  const Dims wholePoints(static_cast<int>(pointsAlong(whole, 0)),
                         static_cast<int>(pointsAlong(whole, 1)),
                         static_cast<int>(pointsAlong(whole, 2)));
  // The cut grid of piecesCover is at most one byte a point of the whole: checked first.
  LIC3D_TRY(checkHostCanHold(path, voxelCount(wholePoints) * (sizeof(glm::vec3) + 1)));
  std::uint64_t piecePoints = 0;  // each piece within the whole, so no overflow
  for (const PieceRef& piece : pieces)
    piecePoints =
        std::min(piecePoints + pointsAlong(piece.extent, 0) * pointsAlong(piece.extent, 1) *
                                   pointsAlong(piece.extent, 2),
                 voxelCount(wholePoints));
  if (piecePoints < voxelCount(wholePoints) || !piecesCover(whole, pieces))
    return fileError(path, "its pieces leave points of the whole extent " + extentText(whole) +
                               " without data (a missing piece?)");

  // The pieces' grids decide point data (a piece of N points) or cell data (N - 1 cells along
  // each axis longer than one point), as the .vti reader reads them.
  VectorField field;
  std::vector<std::uint8_t> covered;
  FieldReadInfo first;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const PieceRef& ref = pieces[p];
    FieldReadInfo read;
    LIC3D_TRY_ASSIGN(
        const VectorField piece,
        readVectorFieldVtiPiece(
            ref.source, arrayName.empty() && p > 0 ? std::string_view(first.arrayName) : arrayName,
            &read));
    const Dims points(static_cast<int>(pointsAlong(ref.extent, 0)),
                      static_cast<int>(pointsAlong(ref.extent, 1)),
                      static_cast<int>(pointsAlong(ref.extent, 2)));
    Dims cells = points;
    for (int a = 0; a < 3; ++a) cells[a] = points[a] > 1 ? points[a] - 1 : 1;
    const bool cellData = piece.dims != points && piece.dims == cells;
    if (piece.dims != points && !cellData)
      return fileError(ref.source, "holds a grid of " + gridText(piece.dims) + " but " +
                                       path.filename().string() + " gives it the extent " +
                                       extentText(ref.extent));
    const Dims offset(static_cast<int>(ref.extent.bounds[0] - whole.bounds[0]),
                      static_cast<int>(ref.extent.bounds[2] - whole.bounds[2]),
                      static_cast<int>(ref.extent.bounds[4] - whole.bounds[4]));
    // Where the piece puts the whole grid's first voxel: every piece must agree with the first,
    // and the first with PImageData's Origin and Spacing where they are given.
    const glm::dvec3 impliedOrigin =
        piece.geometry.origin - glm::dvec3(offset) * piece.geometry.spacing;
    if (spacingGiven && !nearlyEqual(piece.geometry.spacing, wholeSpacing, wholeSpacing))
      return fileError(ref.source, "its Spacing " + tripleText(piece.geometry.spacing, " ") +
                                       " differs from " + path.filename().string() + "'s Spacing " +
                                       tripleText(wholeSpacing, " "));
    if (p == 0) {
      first = read;
      field.dims = wholePoints;
      if (cellData)
        for (int a = 0; a < 3; ++a) field.dims[a] = field.dims[a] > 1 ? field.dims[a] - 1 : 1;
      field.geometry = piece.geometry;
      field.geometry.origin = impliedOrigin;
      field.unit = piece.unit;
      if (originGiven) {
        glm::dvec3 expected =
            wholeOrigin +
            glm::dvec3(whole.bounds[0], whole.bounds[2], whole.bounds[4]) * piece.geometry.spacing;
        if (cellData)
          for (glm::length_t a = 0; a < 3; ++a)
            if (wholePoints[a] > 1) expected[a] += 0.5 * piece.geometry.spacing[a];
        if (!nearlyEqual(impliedOrigin, expected, piece.geometry.spacing))
          return fileError(ref.source, "its Origin puts the whole grid's first " +
                                           std::string(cellData ? "cell centre" : "point") +
                                           " at " + tripleText(impliedOrigin, " ") + ", not at " +
                                           tripleText(expected, " ") + " as " +
                                           path.filename().string() + "'s Origin does");
      }
      const std::uint64_t voxels = voxelCount(field.dims);
      field.vectors.assign(voxels, glm::vec3(0.0f));
      covered.assign(voxels, 0);
    } else if (!nearlyEqual(piece.geometry.spacing, field.geometry.spacing,
                            field.geometry.spacing) ||
               (field.dims == wholePoints) == cellData) {
      return fileError(ref.source,
                       "its spacing or data (point or cell) differs from the first "
                       "piece's");
    } else if (!nearlyEqual(impliedOrigin, field.geometry.origin, field.geometry.spacing)) {
      return fileError(ref.source, "its Origin puts the whole grid's first point at " +
                                       tripleText(impliedOrigin, " ") + ", the first piece at " +
                                       tripleText(field.geometry.origin, " "));
    }
    if (info) info->maskedVectors += read.maskedVectors;
    for (int k = 0; k < piece.dims.z; ++k)
      for (int j = 0; j < piece.dims.y; ++j)
        for (int i = 0; i < piece.dims.x; ++i) {
          const std::size_t at = voxelIndex(field.dims, offset.x + i, offset.y + j, offset.z + k);
          if (at >= field.vectors.size()) continue;  // a cell piece at the far end
          const glm::vec3 value = piece.at(i, j, k);
          if (covered[at] && !sameVector(field.vectors[at], value))
            return fileError(ref.source, "overlaps an earlier piece at point (" +
                                             std::to_string(offset.x + i + whole.bounds[0]) + ", " +
                                             std::to_string(offset.y + j + whole.bounds[2]) + ", " +
                                             std::to_string(offset.z + k + whole.bounds[4]) +
                                             ") with a different vector (which one is meant?)");
          field.vectors[at] = value;
          covered[at] = 1;
        }
  }
  for (std::size_t i = 0; i < covered.size(); ++i)
    if (!covered[i])
      return fileError(path, "its pieces leave points of the whole extent " + extentText(whole) +
                                 " without data (a missing piece?)");
  if (info) {
    info->arrayName = first.arrayName;
    info->arrayNames = first.arrayNames;
    info->scalarNames = first.scalarNames;
  }
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

}  // namespace lic3d
