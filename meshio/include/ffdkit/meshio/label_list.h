#pragma once
// A list of 32-bit labels (the point or cell indices of a polyMesh): held in memory, or read where
// it lies in a file the reader mapped (or inflated), so that a 600 MB `faces` file is not copied
// into fresh memory. A binary OpenFOAM list starts at any byte offset of its file, so the labels
// are loaded with memcpy, never through a pointer to std::int32_t.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

namespace ffdkit::meshio {

namespace detail {

// LabelList's iterator: the labels at 4-byte steps from `at`, each loaded with memcpy.
class LabelIterator {
 public:
  using iterator_category = std::random_access_iterator_tag;
  using value_type = std::int32_t;
  using difference_type = std::ptrdiff_t;
  using pointer = void;
  using reference = std::int32_t;
  LabelIterator() = default;
  LabelIterator(const char* at) : at_(at) {}  // NOLINT
  std::int32_t operator*() const {
    std::int32_t label;
    std::memcpy(&label, at_, sizeof label);
    return label;
  }
  std::int32_t operator[](difference_type i) const { return *(*this + i); }
  LabelIterator& operator++() { return at_ += sizeof(std::int32_t), *this; }
  LabelIterator operator++(int) { LabelIterator old = *this; ++*this; return old; }
  LabelIterator& operator--() { return at_ -= sizeof(std::int32_t), *this; }
  LabelIterator operator--(int) { LabelIterator old = *this; --*this; return old; }
  LabelIterator& operator+=(difference_type n) { return at_ += n * difference_type(sizeof(std::int32_t)), *this; }
  LabelIterator& operator-=(difference_type n) { return *this += -n; }
  friend LabelIterator operator+(LabelIterator i, difference_type n) { return i += n; }
  friend LabelIterator operator+(difference_type n, LabelIterator i) { return i += n; }
  friend LabelIterator operator-(LabelIterator i, difference_type n) { return i -= n; }
  friend difference_type operator-(LabelIterator a, LabelIterator b) {
    return (a.at_ - b.at_) / difference_type(sizeof(std::int32_t));
  }
  friend bool operator==(LabelIterator a, LabelIterator b) { return a.at_ == b.at_; }
  friend auto operator<=>(LabelIterator a, LabelIterator b) { return a.at_ <=> b.at_; }

 private:
  const char* at_ = nullptr;
};

}  // namespace detail

/// The labels of one polyMesh list (faces, owner, neighbour, ...), held in memory or read where
/// they lie in a file's bytes.
class LabelList {
 public:
  /// An empty list.
  LabelList() = default;
  /// The labels given, held in memory.
  LabelList(std::initializer_list<std::int32_t> labels) : held_(labels) {}
  /// The labels of `labels`, held in memory.
  LabelList(std::vector<std::int32_t> labels) : held_(std::move(labels)) {}  // NOLINT: implicit, as a vector
  /// The `count` labels at `bytes` (native byte order, any alignment), which stay readable for as
  /// long as `keeper` lives (a mapped file, an inflated buffer): nothing is copied.
  static LabelList inPlace(std::shared_ptr<const void> keeper, const char* bytes, std::size_t count) {
    LabelList list;
    list.keeper_ = std::move(keeper);
    list.bytes_ = bytes;
    list.count_ = count;
    return list;
  }

  /// How many labels.
  std::size_t size() const { return keeper_ ? count_ : held_.size(); }
  /// Whether there are none.
  bool empty() const { return size() == 0; }
  /// Label i (i < size()).
  std::int32_t operator[](std::size_t i) const {
    std::int32_t label;
    std::memcpy(&label, bytes() + i * sizeof(std::int32_t), sizeof label);
    return label;
  }
  /// The first label (the list not empty).
  std::int32_t front() const { return (*this)[0]; }
  /// The last label (the list not empty).
  std::int32_t back() const { return (*this)[size() - 1]; }
  /// The labels' bytes: 4 per label, native byte order, any alignment (load them with memcpy).
  const char* bytes() const { return keeper_ ? bytes_ : reinterpret_cast<const char*>(held_.data()); }
  /// Whether the labels are read where they lie in a file's bytes (not held in memory).
  bool readInPlace() const { return keeper_ != nullptr; }

  /// The labels held in memory, to build or change the list; a list read in place is copied into
  /// memory first.
  std::vector<std::int32_t>& held() {
    if (keeper_) {
      std::vector<std::int32_t> copy(count_);
      if (count_ > 0) std::memcpy(copy.data(), bytes_, count_ * sizeof(std::int32_t));
      *this = LabelList(std::move(copy));
    }
    return held_;
  }
  /// Room for `count` labels in memory (held in memory first).
  void reserve(std::size_t count) { held().reserve(count); }
  /// Appends `label` (held in memory first).
  void push_back(std::int32_t label) { held().push_back(label); }

  /// Reads the labels in order, as values: a random-access iterator.
  using const_iterator = detail::LabelIterator;
  /// The iterator (read only, as the labels are values).
  using iterator = const_iterator;
  /// A label.
  using value_type = std::int32_t;
  /// A count of labels.
  using size_type = std::size_t;
  /// At the first label.
  const_iterator begin() const { return bytes(); }
  /// Past the last label.
  const_iterator end() const { return bytes() + size() * sizeof(std::int32_t); }
  /// Inserts [first, last) before `at` (held in memory first).
  template <class InputIt>
  void insert(const_iterator at, InputIt first, InputIt last) {
    const std::ptrdiff_t index = at - begin();
    std::vector<std::int32_t>& labels = held();
    labels.insert(labels.begin() + index, first, last);
  }
  /// Inserts `labels` before `at` (held in memory first).
  void insert(const_iterator at, std::initializer_list<std::int32_t> labels) { insert(at, labels.begin(), labels.end()); }

  /// The same labels in the same order.
  friend bool operator==(const LabelList& a, const LabelList& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.bytes(), b.bytes(), a.size() * sizeof(std::int32_t)) == 0);
  }

 private:
  std::vector<std::int32_t> held_;
  std::shared_ptr<const void> keeper_;  // set: the labels are read in place, at bytes_
  const char* bytes_ = nullptr;
  std::size_t count_ = 0;
};

}  // namespace ffdkit::meshio
