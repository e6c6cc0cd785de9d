// SPDX-License-Identifier: BSD-3-Clause
#include "io/file_util.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <mutex>
#include <ostream>
#include <set>
#include <streambuf>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "core/text.h"

namespace lic3d {
namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

std::string systemError(int errorNumber) { return std::strerror(errorNumber); }

// A streambuf over a file descriptor that remembers errno of the first failed write, so the
// error message can say "No space left on device" instead of a bare stream failure.
class FdStreamBuf : public std::streambuf {
 public:
  explicit FdStreamBuf(int fd) : fd_(fd), buffer_(64 * 1024) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  FdStreamBuf(const FdStreamBuf&) = delete;
  FdStreamBuf& operator=(const FdStreamBuf&) = delete;

  int errorNumber() const { return errorNumber_; }

 protected:
  int_type overflow(int_type c) override {
    if (!flushBuffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }

  std::streamsize xsputn(const char* data, std::streamsize count) override {
    // Large blocks (volume payloads) bypass the buffer.
    if (count >= static_cast<std::streamsize>(buffer_.size())) {
      if (!flushBuffer() || !writeAll(data, static_cast<std::size_t>(count))) return 0;
      return count;
    }
    return std::streambuf::xsputn(data, count);
  }

  int sync() override { return flushBuffer() ? 0 : -1; }

 private:
  bool flushBuffer() {
    const std::size_t pending = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return writeAll(buffer_.data(), pending);
  }

  bool writeAll(const char* data, std::size_t count) {
    if (errorNumber_ != 0) return false;
    while (count > 0) {
      const ssize_t written =
          ::write(fd_, data, std::min<std::size_t>(count, std::size_t{1} << 30));
      if (written < 0) {
        if (errno == EINTR) continue;
        errorNumber_ = errno;
        return false;
      }
      data += written;
      count -= static_cast<std::size_t>(written);
    }
    return true;
  }

  int fd_;
  std::vector<char> buffer_;
  int errorNumber_ = 0;
};

// guardInputsFromWrites: whether writeFileAtomically refuses the process's inputs.
std::atomic<bool> guardInputs{false};

// The temporary files being written, for the signal handler below: slots of fixed size that
// it reads without locks or allocation (async-signal-safe). A slot is free (0), being filled (1)
// or holds a path (2).
constexpr int kTemporarySlots = 64;
struct TemporarySlot {
  std::atomic<int> state{0};
  char path[PATH_MAX]{};
};
TemporarySlot temporarySlots[kTemporarySlots];

int registerTemporary(const std::filesystem::path& path) {
  if (path.native().size() >= PATH_MAX) return -1;
  for (int i = 0; i < kTemporarySlots; ++i) {
    int expected = 0;
    if (!temporarySlots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(temporarySlots[i].path, path.c_str(), path.native().size() + 1);
    temporarySlots[i].state.store(2);
    return i;
  }
  return -1;  // all slots busy: this file is still removed on every path but a signal
}

void releaseTemporary(int slot) {
  if (slot >= 0) temporarySlots[slot].state.store(0);
}

struct sigaction previousActions[NSIG];

// SIGINT, SIGTERM, SIGHUP, SIGQUIT: the temporary files are removed, then the signal does what it
// did before (usually: end the process with it).
void removeTemporariesAndReraise(int signal) {
  for (TemporarySlot& slot : temporarySlots)
    if (slot.state.load() == 2) ::unlink(slot.path);
  ::sigaction(signal, &previousActions[signal], nullptr);
  ::raise(signal);
}

// Once per process, before the first temporary file: the handlers above, and SIGXFSZ ignored so
// that a file-size limit (ulimit -f) makes write() fail with EFBIG, an error the writer reports
// after removing its temporary file, instead of killing the process.
void installTemporaryCleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction action {};
    action.sa_handler = removeTemporariesAndReraise;
    sigemptyset(&action.sa_mask);
    for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
      struct sigaction previous {};
      ::sigaction(signal, nullptr, &previous);
      if (previous.sa_handler == SIG_IGN) continue;  // e.g. nohup: keep ignoring it
      previousActions[signal] = previous;
      ::sigaction(signal, &action, nullptr);
    }
    ::signal(SIGXFSZ, SIG_IGN);
  });
}

// OutputGroup's files: each complete under its temporary name until the group commits.
struct PendingOutput {
  std::filesystem::path temporary;
  std::filesystem::path path;
  int slot;
};
std::mutex groupMutex;
bool groupOpen = false;
std::vector<PendingOutput> pendingOutputs;

// Makes the renames into `path`'s folder durable; failing loses nothing already visible.
void syncFolderOf(const std::filesystem::path& path) {
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  const int folderFd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folderFd >= 0) {
    ::fsync(folderFd);
    ::close(folderFd);
  }
}

Error writeError(ErrorKind kind, const std::filesystem::path& path, const std::string& reason) {
  return {kind, "cannot write '" + path.string() + "': " + reason};
}

}  // namespace

Error fileError(const std::filesystem::path& path, std::string_view problem) {
  std::string message = path.string();
  message += ": ";
  message += problem;
  return inputError(std::move(message));
}

Error readWholeError(const std::filesystem::path& path, const std::string& why) {
  return unsupportedError(path.string() + ": " + why +
                          ", so it cannot be read piece by piece and is read whole");
}

std::string lowerCaseExtension(const std::filesystem::path& path) {
  return asciiLowerCase(path.extension().string());
}

Result<std::string> readFile(const std::filesystem::path& path, std::uint64_t maxBytes, bool data) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path, data));
  if (reader.size() > maxBytes)
    return fileError(path, "file is too large (" + std::to_string(reader.size()) +
                               " bytes, the limit is " + std::to_string(maxBytes) + ")");
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(reader.size()));
  adviseHugePages(bytes.data(), bytes.capacity());
  bytes.resize(static_cast<std::size_t>(reader.size()));
  const std::size_t got = reader.read(bytes.data(), bytes.size());
  if (got != bytes.size()) return fileError(path, "cannot read: " + reader.failureReason());
  // The file may have grown since it was opened; the limit still holds.
  char extra = 0;
  if (reader.read(&extra, 1) != 0)
    return fileError(path, "file is too large (it grew while being read; the limit is " +
                               std::to_string(maxBytes) + " bytes)");
  return bytes;
}

Result<void> checkFreeSpace(const std::filesystem::path& path, std::uint64_t bytes) {
  return checkFreeSpace(std::vector<OutputBytes>{{path, bytes}});
}

Result<void> checkFreeSpace(const std::vector<OutputBytes>& outputs) {
  struct FileSystem {
    const OutputBytes* first = nullptr;
    std::size_t others = 0;
    std::uint64_t bytes = 0;
    std::uint64_t available = 0;
    bool atMost = false;
  };
  // By device number, in the order the outputs come, so the message names the first.
  std::vector<std::pair<dev_t, FileSystem>> fileSystems;
  for (const OutputBytes& output : outputs) {
    const std::filesystem::path folder =
        output.path.parent_path().empty() ? "." : output.path.parent_path();
    struct stat place {};
    struct statvfs info {};
    if (::stat(folder.c_str(), &place) != 0 || ::statvfs(folder.c_str(), &info) != 0) continue;
    auto found = std::find_if(fileSystems.begin(), fileSystems.end(),
                              [&](const auto& entry) { return entry.first == place.st_dev; });
    if (found == fileSystems.end()) {
      const std::uint64_t available =
          static_cast<std::uint64_t>(info.f_bavail) * static_cast<std::uint64_t>(info.f_frsize);
      fileSystems.push_back({place.st_dev, FileSystem{&output, 0, 0, available}});
      found = fileSystems.end() - 1;
    } else {
      ++found->second.others;
    }
    found->second.atMost = found->second.atMost || output.atMost;
    const std::uint64_t room = std::numeric_limits<std::uint64_t>::max() - found->second.bytes;
    found->second.bytes += std::min(output.bytes, room);
  }
  for (const auto& [device, system] : fileSystems) {
    if (system.bytes <= system.available) continue;
    const std::string what =
        (system.others == 0 ? std::string(": the output takes ")
                            : " and " + std::to_string(system.others) +
                                  " other output(s) on its file system: they take ") +
        (system.atMost ? "at most " : "");
    return resourceLimitError(system.first->path.string() + what + std::to_string(system.bytes) +
                              " bytes, but its file system has " +
                              std::to_string(system.available) +
                              " bytes free: free space or write elsewhere");
  }
  return {};
}

Result<void> writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
  return writeFileAtomically(path, [bytes](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return static_cast<bool>(out);
  });
}

Result<void> writeFileAtomically(const std::filesystem::path& path,
                                 const std::function<bool(std::ostream&)>& writer) {
  // The temporary file is removed on every path out of here but success, including an exception
  // thrown by the writer.
  LIC3D_TRY_ASSIGN(TemporaryOutput temporary, TemporaryOutput::create(path));
  FdStreamBuf buffer(temporary.fd());
  std::ostream out(&buffer);
  const bool produced = writer(out);
  out.flush();
  if (buffer.errorNumber() != 0)
    return writeError(ErrorKind::Runtime, path, systemError(buffer.errorNumber()));
  if (!produced || !out)
    return writeError(ErrorKind::Runtime, path, "producing the content failed");
  return temporary.commit();
}

Result<TemporaryOutput> TemporaryOutput::create(const std::filesystem::path& path) {
  const std::filesystem::path name = path.filename();
  if (name.empty() || name == "." || name == "..")
    return writeError(ErrorKind::InvalidInput, path, "the path does not name a file");
  if (guardInputs) LIC3D_TRY(checkNotAnInput(path));

  static std::atomic<unsigned> counter{0};
  const std::string suffix =
      ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  // ".name.tmp-PID-N" shows what is being written; a name near the file system's limit gets a
  // short temporary name instead, so every name that may exist may be written.
  std::string temporaryName = "." + name.string() + suffix;
  if (temporaryName.size() > NAME_MAX) temporaryName = ".lic3d" + suffix;
  installTemporaryCleanup();
  std::filesystem::path temporaryPath = path.parent_path() / temporaryName;
  const int fd = ::open(temporaryPath.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) return writeError(ErrorKind::InvalidInput, path, systemError(errno));
  return TemporaryOutput(path, std::move(temporaryPath), fd);
}

TemporaryOutput::TemporaryOutput(std::filesystem::path path, std::filesystem::path temporary,
                                 int fd)
    : path_(std::move(path)),
      temporary_(std::move(temporary)),
      fd_(fd),
      slot_(registerTemporary(temporary_)) {}

TemporaryOutput::TemporaryOutput(TemporaryOutput&& other) noexcept
    : path_(std::move(other.path_)),
      temporary_(std::move(other.temporary_)),
      fd_(std::exchange(other.fd_, -1)),
      slot_(std::exchange(other.slot_, -1)),
      pending_(std::exchange(other.pending_, false)) {}

TemporaryOutput& TemporaryOutput::operator=(TemporaryOutput&& other) noexcept {
  if (this != &other) {
    discard();
    path_ = std::move(other.path_);
    temporary_ = std::move(other.temporary_);
    fd_ = std::exchange(other.fd_, -1);
    slot_ = std::exchange(other.slot_, -1);
    pending_ = std::exchange(other.pending_, false);
  }
  return *this;
}

TemporaryOutput::~TemporaryOutput() { discard(); }

void TemporaryOutput::discard() {
  if (fd_ >= 0) ::close(fd_);
  if (pending_) ::unlink(temporary_.c_str());
  releaseTemporary(slot_);
  fd_ = -1;
  slot_ = -1;
  pending_ = false;
}

Result<void> TemporaryOutput::commit() {
  if (!pending_) return writeError(ErrorKind::Runtime, path_, "the file was already committed");
  // Without fsync a crash shortly after the rename can leave an empty file under the real name.
  if (::fsync(fd_) != 0) return writeError(ErrorKind::Runtime, path_, systemError(errno));
  // close() reports delayed write errors (NFS, quotas), so its result matters.
  const int closed = ::close(std::exchange(fd_, -1));
  if (closed != 0) return writeError(ErrorKind::Runtime, path_, systemError(errno));
  {
    const std::lock_guard lock(groupMutex);
    if (groupOpen) {
      // The group renames or removes it; the signal slot goes with it.
      pendingOutputs.push_back({temporary_, path_, std::exchange(slot_, -1)});
      pending_ = false;
      return {};
    }
  }
  // Renaming fails for reasons the user can fix: a folder in the way, no permission.
  if (::rename(temporary_.c_str(), path_.c_str()) != 0)
    return writeError(ErrorKind::InvalidInput, path_, systemError(errno));
  pending_ = false;
  releaseTemporary(std::exchange(slot_, -1));
  syncFolderOf(path_);
  return {};
}

OutputGroup::OutputGroup() {
  const std::lock_guard lock(groupMutex);
  if (groupOpen) {  // a programming error: groups do not nest
    std::fputs("lic3d: OutputGroup opened while another is open\n", stderr);
    std::abort();
  }
  groupOpen = true;
}

OutputGroup::~OutputGroup() {
  const std::lock_guard lock(groupMutex);
  for (const PendingOutput& pending : pendingOutputs) {
    ::unlink(pending.temporary.c_str());
    releaseTemporary(pending.slot);
  }
  pendingOutputs.clear();
  groupOpen = false;
}

Result<void> OutputGroup::commit() {
  const std::lock_guard lock(groupMutex);
  Result<void> result;
  for (const PendingOutput& pending : pendingOutputs) {
    if (result && ::rename(pending.temporary.c_str(), pending.path.c_str()) == 0) {
      syncFolderOf(pending.path);
    } else {
      if (result) result = writeError(ErrorKind::InvalidInput, pending.path, systemError(errno));
      ::unlink(pending.temporary.c_str());
    }
    releaseTemporary(pending.slot);
  }
  pendingOutputs.clear();
  groupOpen = false;
  return result;
}

FileReader::FileReader(std::filesystem::path path, int fd, std::uint64_t size)
    : path_(std::move(path)), fd_(fd), size_(size) {}

FileReader::FileReader(FileReader&& other) noexcept
    : path_(std::move(other.path_)),
      fd_(std::exchange(other.fd_, -1)),
      size_(other.size_),
      position_(other.position_),
      buffer_(std::move(other.buffer_)),
      begin_(other.begin_),
      end_(other.end_),
      errorNumber_(other.errorNumber_) {}

FileReader& FileReader::operator=(FileReader&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    size_ = other.size_;
    position_ = other.position_;
    buffer_ = std::move(other.buffer_);
    begin_ = other.begin_;
    end_ = other.end_;
    errorNumber_ = other.errorNumber_;
  }
  return *this;
}

FileReader::~FileReader() {
  if (fd_ >= 0) ::close(fd_);
}

namespace {

// The files this process has opened for reading, by device and inode (checkNotAnInput).
struct InputFiles {
  std::mutex mutex;
  std::set<std::pair<dev_t, ino_t>> files;
};
InputFiles& inputFiles() {
  static InputFiles inputs;
  return inputs;
}

}  // namespace

void guardInputsFromWrites(bool on) { guardInputs = on; }

Result<void> checkNotAnInput(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return {};
  InputFiles& inputs = inputFiles();
  const std::scoped_lock lock(inputs.mutex);
  if (inputs.files.count({info.st_dev, info.st_ino}) == 0) return {};
  return fileError(path,
                   "is an input of this run; writing it would destroy it: choose another output");
}

Result<int> openRegularFile(const std::filesystem::path& path) {
  // O_NONBLOCK keeps open() from waiting for a writer when the path is a FIFO; it is cleared
  // again for the reads of a regular file.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return fileError(path, "cannot open: " + systemError(errno));
  struct stat info {};
  if (::fstat(fd, &info) != 0) {
    const int error = errno;
    ::close(fd);
    return fileError(path, "cannot open: " + systemError(error));
  }
  // Pipes and devices have no size to check payloads against, and may never end.
  if (!S_ISREG(info.st_mode)) {
    ::close(fd);
    return fileError(path, std::string("not a regular file (") +
                               (S_ISFIFO(info.st_mode)  ? "a FIFO"
                                : S_ISDIR(info.st_mode) ? "a folder"
                                                        : "a device or socket") +
                               "): give a file");
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

void noteInput(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return;
  InputFiles& inputs = inputFiles();
  const std::scoped_lock lock(inputs.mutex);
  inputs.files.emplace(info.st_dev, info.st_ino);
}

Result<FileReader> FileReader::open(const std::filesystem::path& path, bool data) {
  LIC3D_TRY_ASSIGN(const int fd, openRegularFile(path));
  FileReader reader(path, fd, 0);
  struct stat info {};
  if (::fstat(fd, &info) != 0) return fileError(path, "cannot open: " + systemError(errno));
  if (data) {
    InputFiles& inputs = inputFiles();
    const std::scoped_lock lock(inputs.mutex);
    inputs.files.emplace(info.st_dev, info.st_ino);
  }
  reader.size_ = static_cast<std::uint64_t>(info.st_size);
  reader.buffer_.resize(
      static_cast<std::size_t>(std::clamp<std::uint64_t>(reader.size_ + 1, 4096, kBufferBytes)));
  return reader;
}

bool FileReader::fill() {
  if (fd_ < 0 || errorNumber_ != 0) return false;
  begin_ = 0;
  end_ = 0;
  for (;;) {
    const ssize_t got = ::read(fd_, buffer_.data(), buffer_.size());
    if (got < 0) {
      if (errno == EINTR) continue;
      errorNumber_ = errno;
      return false;
    }
    end_ = static_cast<std::size_t>(got);
    return got > 0;
  }
}

int FileReader::get() {
  if (begin_ == end_ && !fill()) return -1;
  ++position_;
  return static_cast<unsigned char>(buffer_[begin_++]);
}

int FileReader::peek() {
  if (begin_ == end_ && !fill()) return -1;
  return static_cast<unsigned char>(buffer_[begin_]);
}

std::size_t FileReader::read(void* data, std::size_t count) {
  char* out = static_cast<char*>(data);
  std::size_t done = std::min(count, end_ - begin_);
  std::memcpy(out, buffer_.data() + begin_, done);
  begin_ += done;
  while (done < count) {
    const std::size_t wanted = count - done;
    if (wanted < buffer_.size()) {
      if (!fill()) break;
      const std::size_t take = std::min(wanted, end_ - begin_);
      std::memcpy(out + done, buffer_.data() + begin_, take);
      begin_ += take;
      done += take;
      continue;
    }
    if (fd_ < 0 || errorNumber_ != 0) break;
    const ssize_t got =
        ::read(fd_, out + done, std::min<std::size_t>(wanted, std::size_t{1} << 30));
    if (got < 0) {
      if (errno == EINTR) continue;
      errorNumber_ = errno;
      break;
    }
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  position_ += done;
  return done;
}

std::uint64_t FileReader::skip(std::uint64_t count) {
  count = std::min(count, remaining());
  const std::size_t buffered =
      static_cast<std::size_t>(std::min<std::uint64_t>(count, end_ - begin_));
  begin_ += buffered;
  position_ += buffered;
  const std::uint64_t rest = count - buffered;
  if (rest == 0) return count;
  if (fd_ < 0 || errorNumber_ != 0) return buffered;
  if (::lseek(fd_, static_cast<off_t>(position_ + rest), SEEK_SET) < 0) {
    errorNumber_ = errno;
    return buffered;
  }
  position_ += rest;
  return count;
}

std::string FileReader::failureReason() const {
  return errorNumber_ != 0 ? systemError(errorNumber_) : std::string("unexpected end of file");
}

Result<void> FileReader::readAt(std::uint64_t offset, void* data, std::size_t count,
                                std::string_view what) const {
  char* out = static_cast<char*>(data);
  for (std::size_t done = 0; done < count;) {
    const ssize_t got =
        ::pread(fd_, out + done, std::min<std::size_t>(count - done, std::size_t{1} << 30),
                static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0)
      return fileError(path_, "cannot read " + std::string(what) + ": " + systemError(errno));
    if (got == 0)
      return fileError(path_, std::string(what) + " is truncated: the file ends at byte " +
                                  std::to_string(offset + done) + ", " +
                                  std::to_string(count - done) + " bytes short");
    done += static_cast<std::size_t>(got);
  }
  return {};
}

}  // namespace lic3d
