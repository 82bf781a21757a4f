#pragma once
// One resource budget for every reader: what a file may make ffdkit allocate, counted before
// it is allocated. A mesh file, a widget file, a scene (with all its meshes, primitives and
// generators together) each read against one ReadBudget; the sizes a file can make a reader
// produce, directly or by reference (instancing, aliasing, repetition, resolution, samples,
// lattice counts), are charged to it first. docs/robustness.md lists what each reader charges.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ffdkit::meshio {

/// The limits of one read. The defaults leave room on a 24 GiB machine for the read and for the
/// work after it (an embedding and a deformation of what was read).
struct ReadLimits {
  /// Bytes a read may allocate for what the files describe (points, cells, decompressed data,
  /// control points, samples). Default 4 GiB.
  std::uint64_t maxMemoryBytes = std::uint64_t(4) << 30;
  /// Points (mesh vertices, generated samples, lattice control points) a read may produce.
  std::uint64_t maxPoints = 50'000'000;
};

/// A read that would exceed its ReadLimits. Readers catch it and throw their own documented
/// error type (MeshIoError, WidgetFileError, SceneFileError) with the file and location in front
/// of this message; it never escapes a reader's public entry point as itself.
class ReadLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What one read has charged so far against its limits. Not thread-safe: one read, one budget.
class ReadBudget {
 public:
  /// A budget for one read with these limits.
  explicit ReadBudget(ReadLimits limits = {}) : limits_(limits) {}

  /// The read's limits.
  const ReadLimits& limits() const { return limits_; }
  /// Bytes charged so far.
  std::uint64_t bytesCharged() const { return bytes_; }
  /// Points charged so far.
  std::uint64_t pointsCharged() const { return points_; }

  /// Charges `count` items of `bytesEach` bytes, before they are allocated. `what` names them
  /// for the message ("element 'vertex'", "accessor 3 instanced by 40000 nodes").
  /// @throws ReadLimitError "element 'vertex': 100000000 items of 24 bytes need 2.2 GiB; with
  /// what this read holds already (1.0 GiB) that is over its limit of 2.0 GiB (--max-memory)".
  void chargeBytes(std::uint64_t count, std::uint64_t bytesEach, std::string_view what);

  /// Charges `count` points (and their 24 bytes each of double coordinates) before they are
  /// allocated. @throws ReadLimitError naming --max-points or --max-memory.
  void chargePoints(std::uint64_t count, std::string_view what);

  /// Gives back bytes charged for temporary storage that has been freed (a decompressed block
  /// once its values are copied out).
  void releaseBytes(std::uint64_t bytes) { bytes_ = bytes > bytes_ ? 0 : bytes_ - bytes; }

  /// Gives back points charged for capacity a reader trimmed away (and their bytes).
  void releasePoints(std::uint64_t count) {
    points_ = count > points_ ? 0 : points_ - count;
    releaseBytes(count > (std::uint64_t(-1) / 24) ? std::uint64_t(-1) : 24 * count);
  }

 private:
  ReadLimits limits_;
  std::uint64_t bytes_ = 0;
  std::uint64_t points_ = 0;
};

/// "4.0 GiB", "512.0 MiB", "900 bytes": sizes in messages.
std::string byteSizeText(std::uint64_t bytes);

/// Parses a size as the CLI and the app's preferences take it: a number with an optional unit
/// K, M, G, T (powers of 1024, optionally followed by "iB" or "B"), e.g. "4G", "512MiB", "1e9".
/// @throws std::invalid_argument with a message naming `text`.
std::uint64_t parseByteSize(std::string_view text);

/// Parses a count as `--max-points` takes it: a whole number with an optional decimal unit
/// k, M, G (10^3, 10^6, 10^9), e.g. "50M", "2500000". @throws std::invalid_argument.
std::uint64_t parseCount(std::string_view text);

}  // namespace ffdkit::meshio
