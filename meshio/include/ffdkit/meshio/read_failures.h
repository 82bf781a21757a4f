#pragma once
// The one way a reader's entry point turns what may escape its body, a failed allocation or the
// budget's own ReadLimitError, into the reader's documented error type (MeshIoError,
// WidgetFileError, SceneFileError), with the file in front.

#include <new>
#include <string>
#include <string_view>

#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio {

/// What a reader says when an allocation fails although the budget allowed it (a limit set above
/// the memory there is): "out of memory while reading the scene (the read had charged 1.2 GiB of
/// its limit of 4.0 GiB; a lower --max-memory refuses such a file before it allocates)".
/// `what` names what was read ("the scene"), or is empty.
std::string outOfMemoryText(const ReadBudget& budget, std::string_view what);

/// Runs `read` (a reader's body, charging `budget`) and rethrows a failed allocation or a
/// ReadLimitError from it as `Error` with `source` in front.
template <class Error, class Read>
auto convertReadFailures(const std::string& source, std::string_view what, const ReadBudget& budget, Read&& read)
    -> decltype(read()) {
  try {
    return read();
  } catch (const std::bad_alloc&) {
    throw Error(source + ": " + outOfMemoryText(budget, what));
  } catch (const ReadLimitError& e) {
    throw Error(source + ": " + e.what());
  }
}

}  // namespace ffdkit::meshio
