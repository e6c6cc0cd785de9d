// SPDX-License-Identifier: BSD-3-Clause
// Parallel VTK XML ImageData (.pvti), the file ParaView and VTK write under MPI: a PImageData
// with the whole extent and a Piece (Extent, Source) per process, each a .vti of its own. The
// field is assembled from the pieces by their extents.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "io/file_util.h"
#include "io/vti.h"
#include "io/vti_file.h"

namespace lic3d {
namespace {

using Extent = std::array<int, 6>;

// The .vti reader's extent, each number within int.
bool parseExtent(const char* text, Extent& extent) {
  const std::optional<vti::Extent> parsed = vti::parseExtent(text);
  if (!parsed) return false;
  for (std::size_t i = 0; i < 6; ++i) {
    const std::int64_t bound = parsed->bounds[i];
    if (bound < std::numeric_limits<int>::min() || bound > std::numeric_limits<int>::max())
      return false;
    extent[i] = static_cast<int>(bound);
  }
  return true;
}

Dims pointsOf(const Extent& e) { return {e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1}; }

std::string extentText(const Extent& e) {
  std::string text;
  for (const int v : e) text += (text.empty() ? "" : " ") + std::to_string(v);
  return text;
}

struct PieceRef {
  Extent extent{};
  std::filesystem::path source;
};

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
  Extent whole{};
  if (!parseExtent(image.attribute("WholeExtent").as_string(), whole))
    return fileError(path, "PImageData needs a WholeExtent of six whole numbers, min <= max");
  std::vector<PieceRef> pieces;
  const std::filesystem::path folder = path.parent_path();
  for (const pugi::xml_node node : image.children("Piece")) {
    PieceRef piece;
    if (!parseExtent(node.attribute("Extent").as_string(), piece.extent))
      return fileError(path, "a Piece needs an Extent of six whole numbers, min <= max");
    for (int a = 0; a < 3; ++a)
      if (piece.extent[2 * a] < whole[2 * a] || piece.extent[2 * a + 1] > whole[2 * a + 1])
        return fileError(path, "the Piece extent " + extentText(piece.extent) +
                                   " leaves the whole extent " + extentText(whole));
    const std::string source = node.attribute("Source").as_string();
    if (source.empty()) return fileError(path, "a Piece has no Source file");
    piece.source = folder / source;
    pieces.push_back(std::move(piece));
  }
  if (pieces.empty()) return fileError(path, "no Piece: the file names no data");

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
    const Dims points = pointsOf(ref.extent);
    Dims cells = points;
    for (int a = 0; a < 3; ++a) cells[a] = points[a] > 1 ? points[a] - 1 : 1;
    const bool cellData = piece.dims != points && piece.dims == cells;
    if (piece.dims != points && !cellData)
      return fileError(ref.source, "holds a grid of " + gridText(piece.dims) + " but " +
                                       path.filename().string() + " gives it the extent " +
                                       extentText(ref.extent));
    Dims offset(ref.extent[0] - whole[0], ref.extent[2] - whole[2], ref.extent[4] - whole[4]);
    if (p == 0) {
      first = read;
      field.dims = pointsOf(whole);
      if (cellData)
        for (int a = 0; a < 3; ++a) field.dims[a] = field.dims[a] > 1 ? field.dims[a] - 1 : 1;
      field.geometry = piece.geometry;
      field.geometry.origin -= glm::dvec3(offset) * piece.geometry.spacing;
      field.unit = piece.unit;
      const std::uint64_t voxels = voxelCount(field.dims);
      LIC3D_TRY(checkHostCanHold(path, voxels * (sizeof(glm::vec3) + 1)));
      field.vectors.assign(voxels, glm::vec3(0.0f));
      covered.assign(voxels, 0);
    } else if (!(piece.geometry.spacing == field.geometry.spacing) ||
               (field.dims == pointsOf(whole)) == cellData) {
      return fileError(ref.source,
                       "its spacing or data (point or cell) differs from the first "
                       "piece's");
    }
    if (info) info->maskedVectors += read.maskedVectors;
    for (int k = 0; k < piece.dims.z; ++k)
      for (int j = 0; j < piece.dims.y; ++j)
        for (int i = 0; i < piece.dims.x; ++i) {
          const std::size_t at = voxelIndex(field.dims, offset.x + i, offset.y + j, offset.z + k);
          if (at >= field.vectors.size()) continue;  // a cell piece at the far end
          field.vectors[at] = piece.at(i, j, k);
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
