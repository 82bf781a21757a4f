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

// The functions the mutator's shared library exports in the libFuzzer build, where it is built with
// hidden visibility (tests/fuzz/CMakeLists.txt).
#define FFDKIT_FUZZ_JSON_API [[gnu::visibility("default")]]

namespace ffdkit::fuzz {

/// One to four structural mutations of the JSON document `text`, written back as compact JSON
/// (with, at times, a number replaced by text that is not JSON). nullopt when `text` does not
/// parse as JSON or no mutation fits in `maxSize` bytes.
FFDKIT_FUZZ_JSON_API std::optional<std::string> mutateJson(std::string_view text, std::uint64_t seed,
                                                           std::size_t maxSize);

/// `text` cut down to at most `maxSize` bytes of compact JSON by dropping runs of consecutive
/// members or elements (each run at least an eighth of the excess; where, `seed` chooses) until it
/// fits: how a fuzz target whose inputs cost more the longer they are keeps long documents (sample
/// files, an earlier campaign's corpus) as parents of short mutants. nullopt when `text` does not
/// parse, fits already, or cannot be cut to fit (a root string that is too long).
FFDKIT_FUZZ_JSON_API std::optional<std::string> shrinkJson(std::string_view text, std::uint64_t seed,
                                                           std::size_t maxSize);

/// `first` with one of its values replaced by a value of `second` (one with the same key when
/// there is one), by splicing the texts: neither is parsed, so the rest of `first` keeps its bytes
/// (spaces, number text that is not JSON) and the graft is the bytes of `second`'s value. nullopt
/// when the brackets, strings and separators of either are not JSON's (json_value_spans.h) or the
/// result exceeds `maxSize` bytes.
FFDKIT_FUZZ_JSON_API std::optional<std::string> crossOverJson(std::string_view first, std::string_view second,
                                                              std::uint64_t seed, std::size_t maxSize);

}  // namespace ffdkit::fuzz
