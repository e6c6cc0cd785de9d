// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading and writing files safely: whole-file reads with a size limit, a buffered front-to-back
// reader for the volume parsers, and writes that never leave a half-written file under the real
// name; plus errors that name a file and file names' extensions. POSIX only
// (open/read/fsync/rename), like the rest of the project. The text the parsers read is core/text.h.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace lic3d {

// Files are read and written piece by piece in chunks of this size: a multiple of every value
// size, so chunks never split a value.
inline constexpr std::size_t kFileChunkBytes = std::size_t{1} << 20;

// Limits on grids read from untrusted files: each axis and the voxel count.
inline constexpr std::uint64_t kMaxAxisSize = 16384;
inline constexpr std::uint64_t kMaxVoxels = std::uint64_t{1} << 31;
// Streams (FieldStream, ScalarVolumeStream) hold only pieces of a grid, so theirs may be larger:
// each axis still at most kMaxAxisSize.
inline constexpr std::uint64_t kMaxStreamedVoxels = std::uint64_t{1} << 40;

// An InvalidInput error about a file, worded "<path>: <problem>".
Error fileError(const std::filesystem::path& path, std::string_view problem);

// Unsupported, naming the file and why it cannot be read piece by piece (FieldStream): the caller
// reads it whole instead.
Error readWholeError(const std::filesystem::path& path, const std::string& why);

// The extension in lower case, dot included (".nrrd"), or empty: how readers and writers choose
// a format.
std::string lowerCaseExtension(const std::filesystem::path& path);

// A file opened for reading (O_RDONLY, close-on-exec), refused unless it is a regular file: a
// FIFO, a device or a folder is named as "not a regular file" (InvalidInput) without waiting for
// a writer, since open() itself is non-blocking. Every reader of a file goes through here
// (FileReader, readFile, the PNG readers), so no input can hang a run. The caller closes it.
Result<int> openRegularFile(const std::filesystem::path& path);

// The whole file, or an error naming it: missing, unreadable, not a regular file, or larger than
// maxBytes (refused from its size before anything is read).
// `data`: the file is an input of the run that no output may replace (checkNotAnInput): every
// file a run reads (fields, noise, scalars, sessions, colour-map presets). False for a file read
// only to decide whether to replace it (a frame --skip-existing checks).
Result<std::string> readFile(const std::filesystem::path& path, std::uint64_t maxBytes,
                             bool data = true);

// Writes to a temporary file in the same folder (`.<name>.tmp-<pid>-<n>`, so the rename cannot
// cross file systems), flushes it to disk and renames it over `path`. On any failure the
// temporary file is removed, `path` keeps its old content (or stays absent) and the error names
// the path and the reason. A path that cannot be written (missing folder, no permission, a folder
// in the way) is InvalidInput; a failure while writing (disk full, I/O error, a writer returning
// false) is Runtime.
// No output may be an input of the same run: every regular file a FileReader opens is noted by
// device and inode, and this refuses (InvalidInput, naming the path) a path that resolves to
// one, whatever its spelling (./sub/../x, a hard link). A path that does not exist passes.
// Front ends check their outputs with it before the work.
Result<void> checkNotAnInput(const std::filesystem::path& path);
// With the guard on, writeFileAtomically also refuses a path that checkNotAnInput refuses: the CLI
// turns it on for its runs. Off by default: a program that reads a file and then saves it again
// (a test's round trip, a script) may.
void guardInputsFromWrites(bool on);
// Notes `path` (when it is a regular file) as an input of this run, as FileReader does, for a
// file read by other means or kept as it is (a frame --skip-existing leaves).
void noteInput(const std::filesystem::path& path);

// Whether the file system that will hold `path` has `bytes` free for an unprivileged writer
// (statvfs's f_bavail): ResourceLimit (exit status 3) naming the path with both numbers when it
// has not, so a run stops before its work rather than at its last write. A folder that cannot
// be asked passes (the write itself still reports a full disk).
Result<void> checkFreeSpace(const std::filesystem::path& path, std::uint64_t bytes);
// The bytes one output of a run will take, or at most will (a PNG: compression decides).
struct OutputBytes {
  std::filesystem::path path;
  std::uint64_t bytes = 0;
  bool atMost = false;
};
// The same for all the outputs of a run at once: those whose folders share a file system are
// summed, and the message names the first of them, how many more share it, and both numbers.
Result<void> checkFreeSpace(const std::vector<OutputBytes>& outputs);

Result<void> writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);
// The same, for content streamed by `writer`; a writer that returns false fails the write.
Result<void> writeFileAtomically(const std::filesystem::path& path,
                                 const std::function<bool(std::ostream&)>& writer);

// A file written in place, piece by piece, under writeFileAtomically's temporary name beside
// `path` (removed like its files when a signal ends the process), for outputs too large to
// produce front to back. commit() flushes it to disk and renames it over `path`, or hands it to
// the open OutputGroup; destroyed without a commit, the temporary file is removed. Errors as for
// writeFileAtomically, input guard included. Move-only.
class TemporaryOutput {
 public:
  static Result<TemporaryOutput> create(const std::filesystem::path& path);

  TemporaryOutput(TemporaryOutput&& other) noexcept;
  TemporaryOutput& operator=(TemporaryOutput&& other) noexcept;
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;
  ~TemporaryOutput();

  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }
  int fd() const { return fd_; }  // open for writing until commit()
  Result<void> commit();

 private:
  TemporaryOutput(std::filesystem::path path, std::filesystem::path temporary, int fd);
  void discard();

  std::filesystem::path path_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  int slot_ = -1;        // the signal handler's record of the temporary file
  bool pending_ = true;  // the temporary file exists and is this object's to remove
};

// Outputs that appear together or not at all. While a group is open, writeFileAtomically (from
// any thread) leaves each complete file under its temporary name, still removed if a signal ends
// the process; commit() renames them into place in the order they were written, and a group
// destroyed without a commit removes them, so every name keeps its old file (or stays absent).
// One group at a time in a process.
class OutputGroup {
 public:
  OutputGroup();
  OutputGroup(const OutputGroup&) = delete;
  OutputGroup& operator=(const OutputGroup&) = delete;
  ~OutputGroup();
  // Renames every file written since the group opened into place and closes the group. A rename
  // that fails (the folder changed since the write) is returned; the files before it stay in
  // place, the temporaries after it are removed.
  Result<void> commit();
};

// Reads a regular file front to back through a buffer. The volume parsers use it so that a
// payload's size is checked against the bytes left in the file before anything is allocated,
// and so that a large volume is never held in memory twice.
class FileReader {
 public:
  // `data` as for readFile.
  static Result<FileReader> open(const std::filesystem::path& path, bool data = true);

  FileReader(FileReader&& other) noexcept;
  FileReader& operator=(FileReader&& other) noexcept;
  FileReader(const FileReader&) = delete;
  FileReader& operator=(const FileReader&) = delete;
  ~FileReader();

  const std::filesystem::path& path() const { return path_; }
  std::uint64_t size() const { return size_; }  // when opened
  std::uint64_t position() const { return position_; }
  std::uint64_t remaining() const { return position_ < size_ ? size_ - position_ : 0; }

  // The next byte (0..255), or -1 at the end of the file or after a read error.
  int get();
  int peek();
  // Reads up to `count` bytes; fewer only at the end of the file or after a read error.
  std::size_t read(void* data, std::size_t count);
  // Skips up to `count` bytes, never past the size the file had when opened.
  std::uint64_t skip(std::uint64_t count);
  // Why reading stopped early: the system's error text or "unexpected end of file".
  std::string failureReason() const;
  // Exactly `count` bytes at `offset` with pread, apart from the front-to-back position: safe
  // from several threads at once. An error names the file: a read error, or the file ending
  // early (`what` names the data read).
  Result<void> readAt(std::uint64_t offset, void* data, std::size_t count,
                      std::string_view what) const;

 private:
  FileReader(std::filesystem::path path, int fd, std::uint64_t size);
  bool fill();

  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::uint64_t position_ = 0;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;  // unread bytes are buffer_[begin_, end_)
  std::size_t end_ = 0;
  int errorNumber_ = 0;
};

}  // namespace lic3d
