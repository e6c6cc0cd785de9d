#pragma once
// Session files (core/session.h) on disk: read with a size limit, written atomically.

#include <filesystem>

#include "core/error.h"
#include "core/session.h"

namespace lic3d {

Result<Session> readSession(const std::filesystem::path& path);
Result<void> writeSession(const std::filesystem::path& path, const Session& session);

}  // namespace lic3d
