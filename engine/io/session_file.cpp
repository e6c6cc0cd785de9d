// SPDX-License-Identifier: BSD-3-Clause
#include "io/session_file.h"

#include <string>

#include "io/file_util.h"

namespace lic3d {

Result<Session> readSession(const std::filesystem::path& path) {
  LIC3D_TRY_ASSIGN(const std::string text, readFile(path, 1 << 20, false));
  return sessionFromJson(text, path.string());
}

Result<void> writeSession(const std::filesystem::path& path, const Session& session) {
  const std::string text = sessionToJson(session);
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
  LIC3D_TRY_ASSIGN(const std::string text, readFile(path, 16 << 20, false));
  return transferFunctionFromJson(text, path.string());
}

Result<void> writeTransferFunction(const std::filesystem::path& path, const TransferFunction& tf) {
  return writeFileAtomically(path, transferFunctionToJson(tf));
}

}  // namespace lic3d
