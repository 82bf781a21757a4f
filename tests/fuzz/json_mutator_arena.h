#pragma once
// The memory of the JSON mutator (json_mutator.cpp): a monotonic arena that one exported call
// allocates from and that is emptied when the call returns. In the libFuzzer build the mutator is
// built without sanitizers, but its allocations would still go through ASan's allocator (it
// replaces malloc for the whole process), and perf put most of the mutator's time there: parsing
// two inputs, copying a document, writing it back are hundreds of small allocations per input.
// The arena takes its blocks once and keeps them from call to call, so a call allocates by moving
// a pointer and frees nothing. In a build where the mutator itself is under ASan (the sanitizer
// build), the arena poisons what it has not handed out, what was given back and a gap after every
// allocation, so overflows and uses after free inside the mutator are still reported there.

#include <cstddef>
#include <memory>
#include <new>
#include <vector>

#include "json_mutator.h"

namespace ffdkit::fuzz {

class FFDKIT_FUZZ_JSON_API Arena {
 public:
  Arena() = default;
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;
  ~Arena();

  /// `bytes` bytes aligned to `alignment` (a power of two, at most alignof(std::max_align_t)),
  /// valid until release(). Throws std::bad_alloc when no block can be had.
  void* allocate(std::size_t bytes, std::size_t alignment);
  /// Nothing is reused before release(); in a sanitizer build the bytes become unaddressable.
  void deallocate(void* pointer, std::size_t bytes) noexcept;
  /// Everything handed out is given back at once. Blocks up to kKeptBytes stay for the next call.
  void release() noexcept;

  /// The arena of this thread, to allocate from while a Scope is open on it; allocating with none
  /// open is a bug (memory that would outlive its call) and throws std::logic_error.
  static Arena& current();
  /// The arena of this thread, to give memory back to (open or not).
  static Arena& ofThread() noexcept;

  /// Opens the thread's arena for one call of the mutator; the outermost scope's end releases it.
  class Scope {
   public:
    Scope();
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
  };

 private:
  struct Block {
    std::byte* data;
    std::size_t size;
  };
  static constexpr std::size_t kFirstBlockBytes = std::size_t(1) << 20;
  static constexpr std::size_t kKeptBytes = std::size_t(16) << 20;

  void addBlock(std::size_t atLeast);
  void freeLastBlock() noexcept;

  std::vector<Block> blocks_;
  std::size_t block_ = 0;   // the block allocated from
  std::size_t offset_ = 0;  // its first free byte
  int scopes_ = 0;
};

/// A standard allocator on Arena::current(): the mutator's strings, vectors and JSON values.
template <class T>
struct ArenaAllocator {
  using value_type = T;

  ArenaAllocator() = default;
  template <class U>
  ArenaAllocator(const ArenaAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(Arena::current().allocate(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* pointer, std::size_t n) noexcept { Arena::ofThread().deallocate(pointer, n * sizeof(T)); }

  template <class U>
  bool operator==(const ArenaAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace ffdkit::fuzz
