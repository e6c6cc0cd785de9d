// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// VTK XML ImageData files (.vti, "VTK File Formats", XML section): vector fields and scalar arrays
// in, LIC and RGBA volumes out (and back in, so users and tests can check what was written).
//
// Readers take one Piece covering WholeExtent, Origin and Spacing (the Direction matrix is
// dropped: lic3d grids are axis aligned), arrays in PointData or CellData, in every encoding VTK
// writes: `ascii`, `binary` (base64, each block with its UInt32 or UInt64 size header, plain or
// vtkZLibDataCompressor blocks) and `appended` (raw or base64), in either byte order. Inputs are
// untrusted: the grid is limited (each axis in [1, 16384], at most 2^31 points), and block
// headers, block tables, base64 and zlib sizes are checked against the expected byte count and
// the bytes present before anything is allocated. Every error is InvalidInput and names the file,
// the array and the problem. XML is parsed by pugixml and zlib blocks are inflated by zlib.

#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"

namespace lic3d {

// The 3-component DataArray named `arrayName`, or when `arrayName` is empty PointData's active
// `Vectors`, else its first 3-component array, else the same in CellData. On a 2D grid (one
// layer along z) a 2-component array is taken too, as vectors (x, y, 0). Point data wins over
// cell data of the same name. Cell data on a grid of N cells becomes a field of N voxels at the
// cell centres, its origin moved by half a spacing (cellCentredGrid). Any numeric type is read as
// float; vectors with a NaN or infinite component become zero and are counted
// (finishVectorField). Where a 1-component PointData array named vtkValidPointMask is 0,
// point-data vectors are set to zero first and counted in `info->maskedVectors`
// (kValidPointMaskName). When the array is missing the error lists the 3-component arrays found;
// `info` also gets their names and those of the 1-component PointData arrays (the mask left out).
Result<VectorField> readVectorFieldVti(const std::filesystem::path& path,
                                       std::string_view arrayName = {},
                                       FieldReadInfo* info = nullptr);
// The same without finishVectorField (non-finite vectors kept, no flow allowed): one piece of a
// .pvti, which is checked as a whole.
Result<VectorField> readVectorFieldVtiPiece(const std::filesystem::path& path,
                                            std::string_view arrayName, FieldReadInfo* info);

// A parallel .pvti (what ParaView and VTK write under MPI): its pieces' .vti files (Source,
// relative to the .pvti's folder) read as readVectorFieldVti reads one and placed by their
// Extent in the WholeExtent. Extents are 64-bit (never wrapped to int); the whole extent is held
// to the grid limits, the pieces' coverage and the host's memory before any piece is read.
// Overlapping points (pieces share their boundaries) must hold the same vectors, and every piece
// must lie where PImageData's Origin and Spacing (and the first piece) put it. The array is
// chosen in the first piece. Errors name the .pvti or the piece.
Result<VectorField> readVectorFieldPvti(const std::filesystem::path& path,
                                        std::string_view arrayName = {},
                                        FieldReadInfo* info = nullptr);

// The 1-component DataArray (NumberOfComponents 1 or absent) named `name`, or when `name` is empty
// PointData's active `Scalars`, else its first 1-component array, else the same in CellData; the
// validity mask is read only by name. Cell data lies at the cell centres (cellCentredGrid). Any
// numeric type is read as float; NaN is kept. When the array is missing the error lists the
// 1-component arrays found.
Result<PointScalars> readPointScalarsVti(const std::filesystem::path& path, std::string_view name);

// PointData's active `Scalars`, else its first 1-component array (then CellData's, centred as
// above), as float; NaN is kept (lic3d writes it for voxels hidden by sparsity).
Result<ScalarVolume> readScalarVti(const std::filesystem::path& path);

// PointData's active `Scalars` if it is a 4-component UInt8 array, else the first such array.
Result<RgbaVolume> readRgbaVti(const std::filesystem::path& path);

// One Float32 point-data array named `arrayName` (the active Scalars), appended raw with a UInt64
// size header in the host's byte order, with Origin and Spacing from the geometry; NaN values are
// written as they are. Through a ScalarVolumeStream, written by every thread at once
// (writeScalarVolumeFile), so a failed write leaves no partial file.
Result<void> writeScalarVti(const std::filesystem::path& path, const ScalarVolume& volume,
                            std::string_view arrayName = kLicArrayName);

// The same layout with one 4-component UInt8 array named "rgba": ParaView shows it as colours
// with "Map Scalars" off.
Result<void> writeRgbaVti(const std::filesystem::path& path, const RgbaVolume& volume);

}  // namespace lic3d
