#pragma once
// Private to scenes: canonical JSON text for the files ffdkit writes.

#include <string>

#include <nlohmann/json.hpp>

namespace ffdkit::scenes::detail {

/// 2-space indentation, keys in insertion order, arrays of scalars (or of short arrays of
/// scalars) on one line when they fit in ~100 columns, shortest round-trip numbers, and a
/// trailing newline: human-readable, and deterministic, so that reading a file ffdkit wrote
/// and writing it again gives the same bytes.
std::string canonicalJsonText(const nlohmann::ordered_json& value);

/// "line:column" (1-based) of byte offset `byte` in `text`, for parse-error messages.
std::string lineColumn(const std::string& text, std::size_t byte);

}  // namespace ffdkit::scenes::detail
