// SPDX-License-Identifier: BSD-3-Clause
// Session files and colour-map presets, the JSON documents lic3d reads: any text gives a session
// (one that validate() accepts) or an InvalidInput error naming the file, never an exception, an
// abort or a wrapped number.

#include "core/session.h"
#include "core/transfer_function.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lic3d;
  const std::string text(fuzz::asText(data, size));
  const Result<Session> session = sessionFromJson(text, "fuzz.json");
  fuzz::check(session);
  // What the reader returns is a valid session, and it writes back to a session that reads the
  // same.
  if (session.ok()) {
    if (!validate(*session).ok()) std::abort();
    const Result<Session> again = sessionFromJson(sessionToJson(*session), "again.json");
    if (!again.ok() || !(*again == *session)) std::abort();
  }
  fuzz::check(transferFunctionFromJson(text, "fuzz.json"));
  return 0;
}
