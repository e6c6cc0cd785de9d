// SPDX-License-Identifier: BSD-3-Clause
// Linked into every test binary: before any test runs, pin the Vulkan driver to lavapipe and turn
// validation on, for this process and every lic3d process a test starts. Tests that need another
// setting (no driver at all) change it in their own process; ctest runs each test separately.
#include <cstdlib>

namespace {

const bool kEnvironmentSet = [] {
  setenv("VK_DRIVER_FILES", LIC3D_LAVAPIPE_ICD, 1);
  setenv("LIC3D_VALIDATION", "1", 1);
  setenv("LIC3D_TEST_DATA", LIC3D_TEST_DATA_DIR, 0);
  return true;
}();

}  // namespace
