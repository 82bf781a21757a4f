// libFuzzer's custom mutator and cross-over for the targets that read JSON: most mutations are
// structural (json_mutator.h); one in eight, and every input that does not parse, gets
// libFuzzer's own byte mutations, so syntax errors stay covered. FFDKIT_FUZZ_JSON_PREFIX bytes
// in front of the JSON (the generator target's choice of generator) are mutated as bytes.
// FFDKIT_FUZZ_JSON_MAX_SIZE (0: none) caps the size of what they make, below libFuzzer's
// -max_len: libFuzzer does not control the length of inputs when a custom mutator is present, so
// without a cap a target's inputs grow toward -max_len, and a target whose cost grows with the
// input's size slows down. An input already over the cap (a sample file, an earlier campaign's
// corpus, read whole up to -max_len) is cut to fit by dropping values (shrinkJson), so its mutants
// start from what it holds.
// Linked only into the libFuzzer build: the corpus driver of the gcc build has no mutator.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "json_mutator.h"

#ifndef FFDKIT_FUZZ_JSON_PREFIX
#define FFDKIT_FUZZ_JSON_PREFIX 0
#endif
#ifndef FFDKIT_FUZZ_JSON_MAX_SIZE
#define FFDKIT_FUZZ_JSON_MAX_SIZE 0
#endif

namespace {

constexpr std::size_t kPrefix = FFDKIT_FUZZ_JSON_PREFIX;

// The most bytes a mutation or cross-over makes, given libFuzzer's limit.
std::size_t capped(std::size_t maxSize) {
  constexpr std::size_t cap = FFDKIT_FUZZ_JSON_MAX_SIZE;
  return cap > 0 && cap < maxSize ? cap : maxSize;
}

std::string_view jsonPart(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data) + kPrefix, size - kPrefix};
}

}  // namespace

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t maxSize,
                                               unsigned int seed) {
  maxSize = capped(maxSize);
  if (size > maxSize) {
    if (size > kPrefix && maxSize > kPrefix) {
      if (auto shrunk = ffdkit::fuzz::shrinkJson(jsonPart(data, size), seed, maxSize - kPrefix)) {
        std::memcpy(data + kPrefix, shrunk->data(), shrunk->size());
        return kPrefix + shrunk->size();
      }
    }
    size = maxSize;  // not JSON (or a root value that does not fit): its first bytes, then byte mutations
  }
  if (size > kPrefix && maxSize > kPrefix && seed % 8 != 0) {
    if (auto mutated = ffdkit::fuzz::mutateJson(jsonPart(data, size), seed, maxSize - kPrefix)) {
      if (kPrefix > 0 && seed % 5 == 0) data[0] = std::uint8_t(seed >> 8);
      std::memcpy(data + kPrefix, mutated->data(), mutated->size());
      return kPrefix + mutated->size();
    }
  }
  return LLVMFuzzerMutate(data, size, maxSize);
}

extern "C" std::size_t LLVMFuzzerCustomCrossOver(const std::uint8_t* first, std::size_t firstSize,
                                                 const std::uint8_t* second, std::size_t secondSize,
                                                 std::uint8_t* out, std::size_t maxOutSize, unsigned int seed) {
  maxOutSize = capped(maxOutSize);
  // The cross-over splices the texts (neither is parsed), so a second input of any size gives a
  // graft that fits; a first one over the cap is cut to fit instead (a sample file, a corpus input
  // read whole up to -max_len).
  if (firstSize > maxOutSize) {
    if (firstSize > kPrefix && maxOutSize > kPrefix) {
      if (auto shrunk = ffdkit::fuzz::shrinkJson(jsonPart(first, firstSize), seed, maxOutSize - kPrefix)) {
        std::memcpy(out, first, kPrefix);
        std::memcpy(out + kPrefix, shrunk->data(), shrunk->size());
        return kPrefix + shrunk->size();
      }
    }
  } else if (firstSize > kPrefix && secondSize > kPrefix && maxOutSize > kPrefix) {
    if (auto crossed = ffdkit::fuzz::crossOverJson(jsonPart(first, firstSize), jsonPart(second, secondSize), seed,
                                                   maxOutSize - kPrefix)) {
      std::memcpy(out, first, kPrefix);
      std::memcpy(out + kPrefix, crossed->data(), crossed->size());
      return kPrefix + crossed->size();
    }
  }
  // Not JSON: the first part of one and the rest of the other.
  const std::size_t head = firstSize == 0 ? 0 : seed % (firstSize + 1);
  const std::size_t tail = secondSize == 0 ? 0 : (seed / 7) % (secondSize + 1);
  std::size_t size = 0;
  for (std::size_t i = 0; i < head && size < maxOutSize; ++i) out[size++] = first[i];
  for (std::size_t i = tail; i < secondSize && size < maxOutSize; ++i) out[size++] = second[i];
  return size;
}
