// SPDX-License-Identifier: BSD-3-Clause
// The command line of lic3d: any arguments (random flags and values, NaN, infinities, huge,
// negative and empty ones, session files that name anything) give a command to run with a
// session that validates and writes back to itself, or help (status 0), or a refusal (status 2
// with a message), never an exception, an abort or a wrapped number. The input holds one
// argument per line.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/session.h"
#include "fuzz_support.h"
#include "options/command_line.h"

namespace {

using namespace lic3d;

// A command that parsed holds a session the engine accepts and that reads back the same.
void checkSession(const Session& session) {
  if (!validate(session).ok()) std::abort();
  const Result<Session> again = sessionFromJson(sessionToJson(session), "again.json");
  if (!again.ok() || !(*again == session)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lic3d::cli;
  const std::string text(fuzz::asText(data, size));
  std::vector<std::string> args{"lic3d"};
  for (std::size_t begin = 0; begin <= text.size() && args.size() < 64;) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    args.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);

  const std::unique_ptr<CommandLine> line = makeCommandLine();
  const std::optional<int> status =
      parseAndCheck(*line, static_cast<int>(args.size()), argv.data());
  if (status) {
    if (*status != 0 && *status != kExitBadInput) std::abort();
    return 0;
  }
  if (line->computeCommand->parsed()) checkSession(line->compute.inputs.session);
  if (line->renderCommand->parsed()) checkSession(line->render.inputs.session);
  if (line->render2dCommand->parsed()) checkSession(line->render2d.inputs.session);
  return 0;
}
