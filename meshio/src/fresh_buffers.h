#pragma once
// Fresh memory for the large arrays a reader fills once (a file's bytes, its tags, its cells):
// reserved first and advised huge pages (ffd/huge_pages.h) before the first write, so that the
// zero fill of resize faults one 2 MiB page at a time instead of one 4 KiB page.

#include <cstddef>
#include <string>
#include <vector>

#include "ffdkit/ffd/huge_pages.h"

namespace ffdkit::meshio::detail {

/// Resizes `v` to `size` items of `value`; when that needs new memory, it is advised huge pages
/// before it is written.
template <class T>
void resizeFresh(std::vector<T>& v, std::size_t size, const T& value = T()) {
  if (size > v.capacity()) {
    v.reserve(size);
    ffd::adviseHugePages(v.data(), v.capacity() * sizeof(T));
  }
  v.resize(size, value);
}

/// Resizes `s` to `size` bytes; when that needs new memory, it is advised huge pages before the
/// zero fill writes it.
inline void resizeFresh(std::string& s, std::size_t size) {
  if (size > s.capacity()) {
    s.reserve(size);
    ffd::adviseHugePages(s.data(), s.capacity());
  }
  s.resize(size);
}

}  // namespace ffdkit::meshio::detail
