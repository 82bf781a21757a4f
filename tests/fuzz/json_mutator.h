#pragma once
// Structure-aware mutation of JSON inputs for the fuzz targets that read JSON (widget files,
// scene files, generator parameters). Byte mutations mostly break the syntax, so the readers'
// content checks are rarely reached; these mutate a parsed document instead: numbers to boundary
// values (0, -1, int64 and uint64 limits, 1e308, 0.5 where a count is expected, text that is not
// JSON such as NaN or 1e999), array lengths (elements duplicated, dropped, repeated; small
// numeric arrays set to huge counts such as [1000, 1000, 100]), strings (paths like "../x",
// "/etc/passwd", long names, names taken from elsewhere in the document), keys (renamed,
// dropped, copied into other objects) and whole values (replaced by another part of the
// document or by a value of another type). Deterministic for a given seed, as libFuzzer needs.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ffdkit::fuzz {

/// One to four structural mutations of the JSON document `text`, written back as compact JSON
/// (with, at times, a number replaced by text that is not JSON). nullopt when `text` does not
/// parse as JSON or no mutation fits in `maxSize` bytes.
std::optional<std::string> mutateJson(std::string_view text, std::uint64_t seed, std::size_t maxSize);

/// `first` with one of its values replaced by a value of `second` (one with the same key when
/// there is one). nullopt when either does not parse or the result exceeds `maxSize` bytes.
std::optional<std::string> crossOverJson(std::string_view first, std::string_view second, std::uint64_t seed,
                                         std::size_t maxSize);

}  // namespace ffdkit::fuzz
