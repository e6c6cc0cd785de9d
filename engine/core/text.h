#pragma once
// Numbers as messages and files print them.

#include <string>

namespace lic3d {

// The shortest text that reads back as the same double ("0.1", "1e-07", "nan"): for files.
std::string formatDouble(double value);
// Six significant digits ("%g": "0.1", "1.7", "4096"): for messages about parameters.
std::string formatNumber(double value);

}  // namespace lic3d
