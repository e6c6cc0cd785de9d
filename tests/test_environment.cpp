// SPDX-License-Identifier: BSD-3-Clause
// Linked into every test binary: before any test runs, pin the Vulkan driver to lavapipe, turn
// validation on and point TMPDIR into the build folder (so no test leaves scratch in /tmp), for
// this process and every lic3d process a test starts. Tests that need another setting (no driver
// at all) change it in their own process; ctest runs each test separately.
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace {

const bool kEnvironmentSet = [] {
  setenv("VK_DRIVER_FILES", LIC3D_LAVAPIPE_ICD, 1);
  setenv("LIC3D_VALIDATION", "1", 1);
  setenv("LIC3D_TEST_DATA", LIC3D_TEST_DATA_DIR, 0);
  std::error_code ignored;
  std::filesystem::create_directories(LIC3D_TEST_TMPDIR, ignored);
  setenv("TMPDIR", LIC3D_TEST_TMPDIR, 1);
  return true;
}();

}  // namespace
