// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// NRRD files (teem.sourceforge.net/nrrd/format.html): vector fields, noise, scalar volumes and
// scalars to colour by in; vector fields, noise, LIC results and RGBA volumes out.
//
// Readers accept NRRD0001..NRRD0005, `raw` and `gzip` encodings, either byte order, every NRRD
// spelling of the types they take, comments, `key:=value` lines and unknown fields. A detached
// header (`.nhdr`) names its data file in `data file` (relative to the header's folder, or
// absolute); `line skip` and `byte skip` (-1: the data ends the file; for gzip the skip counts
// decompressed bytes, as teem reads it) apply to attached and detached data alike. The multi-file
// forms of `data file` (LIST, or a numbered pattern) are refused. Inputs are untrusted: header
// numbers are checked against limits (header <= 64 KiB, each size in [1, 16384], at most 2^31
// voxels) and the payload against the bytes in the file before anything is allocated. Every error
// is InvalidInput and its message names the file (and a detached header's data file) and the
// field.

#include <filesystem>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"

namespace lic3d {

// `dimension: 4`, `sizes: 3 NX NY NZ`, type float or double (converted to float). The grid comes
// from `space directions` (the length of each axis vector is its spacing: lic3d grids are axis
// aligned, so a rotation or flip is dropped) or else from `spacings`; `space origin` sets the
// origin. Vectors with a NaN or infinite component become zero and are counted (finishVectorField).
// `info->unit` gets `sample units` (quotes removed) where the header has it. A 2D grid (one layer
// along z) is also read: `dimension: 3`, `sizes: C NX NY` with C = 3 or 2 (vectors (x, y, 0)),
// `space dimension` 2 or 3 (directions and origin of 2 or 3 numbers).
Result<VectorField> readVectorFieldNrrd(const std::filesystem::path& path,
                                        FieldReadInfo* info = nullptr);

// `dimension: 3`, `sizes: NX NY NZ`, type uchar, ushort or float; integer noise keeps its type.
// Float noise must be finite. Float values that stray outside [0,1] are mapped linearly onto
// [0,1] through the volume's own min and max (a constant volume outside [0,1] is an error);
// float values already inside [0,1] are kept exactly.
Result<NoiseVolume> readNoiseNrrd(const std::filesystem::path& path);

// `dimension: 3`, type float or double (converted to float; NaN is kept: lic3d writes it for
// voxels hidden by sparsity), with the geometry read as for vector fields. Reads what
// writeScalarNrrd writes.
Result<ScalarVolume> readScalarNrrd(const std::filesystem::path& path);

// A scalar to colour a field by, or to set its opacity: `dimension: 3` (or 2: a 2D grid, one
// layer along z), any integer type, float or double (converted to float; NaN is kept), with the
// geometry read as for vector fields. Its name is the file name's stem (a NRRD file holds one
// unnamed array) and its unit the header's `sample units` (quotes removed), where given.
Result<PointScalars> readPointScalarsNrrd(const std::filesystem::path& path);

// `dimension: 4`, `sizes: 4 NX NY NZ`, type uchar: what writeRgbaNrrd writes.
Result<RgbaVolume> readRgbaNrrd(const std::filesystem::path& path);

// Float32, raw, little endian, with `space directions` and `space origin` from the geometry, and
// `labels` whose first names the array in ParaView (`name`). No writer leaves a partial file: the
// others go through writeFileAtomically, this one through a ScalarVolumeStream, written by every
// thread at once (writeScalarVolumeFile).
Result<void> writeScalarNrrd(const std::filesystem::path& path, const ScalarVolume& volume,
                             std::string_view name = kLicArrayName);
// Float32, raw, little endian: what readVectorFieldNrrd reads back unchanged.
Result<void> writeVectorFieldNrrd(const std::filesystem::path& path, const VectorField& field);
// Keeps the noise's type (uchar, ushort or float); raw, little endian.
Result<void> writeNoiseNrrd(const std::filesystem::path& path, const NoiseVolume& noise);
// uchar, `sizes: 4 NX NY NZ`, `kinds: RGBA-color domain domain domain`, with the geometry: 3D
// Slicer and ParaView show it as a colour volume.
Result<void> writeRgbaNrrd(const std::filesystem::path& path, const RgbaVolume& volume);

}  // namespace lic3d
