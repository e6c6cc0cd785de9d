// SPDX-License-Identifier: BSD-3-Clause
#include "io/session_file.h"

#include <optional>
#include <string>
#include <system_error>

#include "io/file_util.h"
#include "io/png_writer.h"

namespace lic3d {

namespace {

namespace fs = std::filesystem;

// Whether a session string names a file: analytic fields and derived quantities are plain names,
// files (and series patterns) have an extension.
bool namesFile(const std::string& text) { return !text.empty() && fs::path(text).has_extension(); }

// Calls `change` on every file path the session names.
template <class Change>
Session changePaths(Session session, Change change) {
  for (std::string* path :
       {&session.field.field, &session.noise.file, &session.view.colorBy, &session.view.opacityBy})
    if (namesFile(*path)) *path = change(fs::path(*path)).string();
  return session;
}

fs::path absoluteNormal(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  return (ec ? path : absolute).lexically_normal();
}

// The session file's folder, as readSession and writeSession resolve paths from it.
fs::path folderOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

}  // namespace

Session sessionForFolder(Session session, const std::filesystem::path& folder) {
  const fs::path base = absoluteNormal(folder);
  return changePaths(std::move(session), [&](const fs::path& path) {
    const fs::path absolute = absoluteNormal(path);
    const fs::path relative = absolute.lexically_relative(base);
    return relative.empty() ? absolute : relative;
  });
}

Session sessionFromFolder(Session session, const std::filesystem::path& folder) {
  return changePaths(std::move(session), [&](const fs::path& path) {
    if (path.is_absolute()) return path;
    const fs::path there = (folder / path).lexically_normal();
    std::error_code ec;
    // A series pattern names no file itself: its folder must exist.
    const bool found = fs::exists(there, ec) || fs::exists(there.parent_path(), ec);
    return !found && fs::exists(path, ec) ? path : there;
  });
}

Result<Session> readSession(const std::filesystem::path& path) {
  std::string text;
  if (isPngFile(path)) {
    LIC3D_TRY_ASSIGN(const std::optional<std::string> carried,
                     readPngText(path, kPngSessionKey, kMaxSessionBytes));
    if (!carried)
      return fileError(path, "this PNG holds no lic3d session (text chunk lic3d-session)");
    text = *carried;
  } else {
    LIC3D_TRY_ASSIGN(text, readFile(path, kMaxSessionBytes));
  }
  LIC3D_TRY_ASSIGN(Session session, sessionFromJson(text, path.string()));
  return sessionFromFolder(std::move(session), folderOf(path));
}

Result<void> writeSession(const std::filesystem::path& path, const Session& session) {
  const std::string text = sessionToJson(sessionForFolder(session, folderOf(path)));
  // Only what reads back is written: a value the reader refuses (a NaN, which JSON writes as
  // null; a number out of its range) fails here, naming it, rather than in the next run.
  if (Result<Session> back = sessionFromJson(text, path.string()); !back) {
    Error error = back.error();
    error.message = "not saved: " + error.message;
    return error;
  }
  return writeFileAtomically(path, text);
}

Result<TransferFunction> readTransferFunction(const std::filesystem::path& path) {
  LIC3D_TRY_ASSIGN(const std::string text, readFile(path, kMaxPresetBytes));
  return transferFunctionFromJson(text, path.string());
}

Result<void> writeTransferFunction(const std::filesystem::path& path, const TransferFunction& tf) {
  return writeFileAtomically(path, transferFunctionToJson(tf));
}

}  // namespace lic3d
