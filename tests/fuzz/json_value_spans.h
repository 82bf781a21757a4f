#pragma once
// The values of a JSON text found by scanning its brackets, strings and separators, without
// parsing it into a document: how the mutator's cross-over grafts a value of one input into
// another by splicing their texts (json_mutator.h), at a fraction of what parsing both costs.

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "json_mutator_arena.h"

namespace ffdkit::fuzz {

/// One value of a JSON text: the bytes [begin, end) of the text.
struct ValueSpan {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::string_view key;  ///< its key as written (escapes kept) when an object's member; else empty
};

/// Every value of `text`, the root first and then in the order they start (a container before the
/// values it holds), in the current arena (Arena::Scope). nullopt when the text's structure is not
/// JSON's (a bracket not closed or closed by the other kind, a string not closed, a member without
/// a key string or colon, a missing comma, anything after the root) or a value is nested deeper
/// than `maxDepth` containers. Scalars are not checked: `NaN` or `01` is a value like any other.
std::optional<std::vector<ValueSpan, ArenaAllocator<ValueSpan>>> valueSpans(std::string_view text, std::size_t maxDepth);

}  // namespace ffdkit::fuzz
