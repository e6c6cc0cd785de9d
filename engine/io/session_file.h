// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Session files (core/session.h) and transfer-function presets (core/transfer_function.h) on
// disk: read with a size limit, written atomically.

#include <filesystem>

#include "core/error.h"
#include "core/session.h"
#include "core/transfer_function.h"

namespace lic3d {

Result<Session> readSession(const std::filesystem::path& path);
Result<void> writeSession(const std::filesystem::path& path, const Session& session);

// A ParaView colour-map preset (.json) as a transfer function; errors name the file.
Result<TransferFunction> readTransferFunction(const std::filesystem::path& path);
Result<void> writeTransferFunction(const std::filesystem::path& path, const TransferFunction& tf);

}  // namespace lic3d
