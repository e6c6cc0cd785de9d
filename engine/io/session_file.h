// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Session files (core/session.h) and transfer-function presets (core/transfer_function.h) on
// disk: read with a size limit, written atomically.

#include <filesystem>

#include "core/error.h"
#include "core/session.h"
#include "core/transfer_function.h"

namespace lic3d {

// A session file (JSON), or the session a PNG lic3d wrote carries (its text chunk
// kPngSessionKey). Its relative file paths are resolved from the file's folder (sessionFromFolder).
Result<Session> readSession(const std::filesystem::path& path);
// Writes the session with its file paths relative to the file's folder (sessionForFolder).
Result<void> writeSession(const std::filesystem::path& path, const Session& session);

// The text chunk of a PNG that holds the session that made it.
inline constexpr char kPngSessionKey[] = "lic3d-session";

// Sessions travel with their files: the file paths a session names (a field file or series
// pattern, the noise file, scalar files that colour or opacity follow) are stored relative to the
// folder of the file that holds the session, and read back from there, so a folder of results and
// inputs can move, and a session can be used from any working folder. A path on another root stays
// absolute.
Session sessionForFolder(Session session, const std::filesystem::path& folder);
// The inverse: relative paths taken from `folder`. A relative path that names nothing there but
// exists from the working folder (a session written before paths were stored relative) is kept.
Session sessionFromFolder(Session session, const std::filesystem::path& folder);

// A ParaView colour-map preset (.json) as a transfer function; errors name the file.
Result<TransferFunction> readTransferFunction(const std::filesystem::path& path);
Result<void> writeTransferFunction(const std::filesystem::path& path, const TransferFunction& tf);

}  // namespace lic3d
