#include "json_mutator_arena.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__)
#define FFDKIT_ARENA_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FFDKIT_ARENA_ASAN 1
#endif
#endif

#ifdef FFDKIT_ARENA_ASAN
#include <sanitizer/asan_interface.h>
#endif

namespace ffdkit::fuzz {

namespace {

constexpr std::size_t kMaxAlignment = alignof(std::max_align_t);

#ifdef FFDKIT_ARENA_ASAN
// Poisoned bytes after each allocation: a write past its end lands in them.
constexpr std::size_t kRedZone = 32;
void poison(const void* at, std::size_t bytes) { ASAN_POISON_MEMORY_REGION(at, bytes); }
void unpoison(const void* at, std::size_t bytes) { ASAN_UNPOISON_MEMORY_REGION(at, bytes); }
#else
constexpr std::size_t kRedZone = 0;
void poison(const void*, std::size_t) {}
void unpoison(const void*, std::size_t) {}
#endif

std::size_t alignUp(std::size_t offset, std::size_t alignment) { return (offset + alignment - 1) & ~(alignment - 1); }

}  // namespace

Arena::~Arena() {
  while (!blocks_.empty()) freeLastBlock();
}

Arena& Arena::ofThread() noexcept {
  thread_local Arena arena;
  return arena;
}

Arena& Arena::current() {
  Arena& arena = ofThread();
  if (arena.scopes_ == 0) throw std::logic_error("the JSON mutator's arena is used outside a call");
  return arena;
}

Arena::Scope::Scope() { ++ofThread().scopes_; }

Arena::Scope::~Scope() {
  Arena& arena = ofThread();
  if (--arena.scopes_ == 0) arena.release();
}

void Arena::addBlock(std::size_t atLeast) {
  const std::size_t previous = blocks_.empty() ? kFirstBlockBytes / 2 : blocks_.back().size;
  const std::size_t size = std::max(atLeast, 2 * previous);
  auto* data = static_cast<std::byte*>(std::malloc(size));
  if (!data) throw std::bad_alloc();
  poison(data, size);
  blocks_.push_back({data, size});
}

void Arena::freeLastBlock() noexcept {
  unpoison(blocks_.back().data, blocks_.back().size);
  std::free(blocks_.back().data);
  blocks_.pop_back();
}

void* Arena::allocate(std::size_t bytes, std::size_t alignment) {
  alignment = std::max(alignment, kRedZone > 0 ? kMaxAlignment : std::size_t(1));
  const std::size_t needed = bytes + kRedZone;
  if (needed < bytes) throw std::bad_alloc();
  for (;;) {
    if (block_ < blocks_.size()) {
      const std::size_t start = alignUp(offset_, alignment);
      if (start <= blocks_[block_].size && blocks_[block_].size - start >= needed) {
        offset_ = start + needed;
        std::byte* result = blocks_[block_].data + start;
        unpoison(result, bytes);
        return result;
      }
      if (block_ + 1 < blocks_.size() && blocks_[block_ + 1].size >= needed + kMaxAlignment) {
        ++block_;
        offset_ = 0;
        continue;
      }
    }
    // The blocks after this one are too small for the request: a new, larger one takes its place.
    while (blocks_.size() > block_ + 1) freeLastBlock();
    addBlock(needed + kMaxAlignment);
    block_ = blocks_.size() - 1;
    offset_ = 0;
  }
}

void Arena::deallocate(void* pointer, std::size_t bytes) noexcept { poison(pointer, bytes); }

void Arena::release() noexcept {
  std::size_t kept = 0;
  std::size_t count = 0;
  while (count < blocks_.size() && kept + blocks_[count].size <= kKeptBytes) kept += blocks_[count++].size;
  count = std::max<std::size_t>(count, 1);
  while (blocks_.size() > count) freeLastBlock();
  for (const Block& block : blocks_) poison(block.data, block.size);
  block_ = 0;
  offset_ = 0;
}

}  // namespace ffdkit::fuzz
