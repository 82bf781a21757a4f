#pragma once

// Shared pieces of the built-in generators (scenes/src/generators/*_generators.cpp): typed
// reads of JSON-friendly parameters into the geometry topics' types, density scaling, and the
// conversion of the topics' polylines and triangle meshes into MeshData. Private to scenes.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/tessellation.h"
#include "ffdkit/scenes/generator.h"
#include "../json_text.h"

namespace ffdkit::scenes::generators {

/// round(base * density), at least `minimum`: the sampling of a generator at `density`.
/// @throws GeneratorError for a density outside (0, 64] (GeneratorRegistry::generate checks it
///   too; the profile path relies on this check).
inline int scaledCount(int base, double density, int minimum) {
  if (!(density > 0.0 && density <= 64.0))
    throw GeneratorError("density must be in (0, 64], got " + std::to_string(density));
  const double scaled = std::round(static_cast<double>(base) * density);
  return std::max(minimum, static_cast<int>(std::min(scaled, 1e8)));
}

/// The ranges of the built-ins' integer parameters. Sample counts go as high as the read's budget
/// lets them (pointBound is charged before generating); iterations are time, not memory.
inline constexpr int kMaxSamples = 100'000'000;
inline constexpr int kMaxCount = 100'000'000;  ///< indices, sizes, grid columns
inline constexpr int kMaxIterations = 100'000;
inline constexpr int kMaxHalfWidth = 10'000;
inline constexpr int kMaxDegree = 99;

/// a * b, or the largest value when it does not fit: a bound that overflows is over any budget.
inline std::uint64_t boundProduct(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) return std::numeric_limits<std::uint64_t>::max();
  return a * b;
}

/// The samples along a direction of `spans` spans at `perSpan` samples each, end included.
inline std::uint64_t samplesAlong(std::uint64_t spans, int perSpan) {
  return std::min(boundProduct(spans, std::uint64_t(perSpan)), std::numeric_limits<std::uint64_t>::max() - 1) + 1;
}

/// A name from a fixed list, mapped to an enum value; the error lists the known names.
template <class E>
E choice(const GeneratorParameters& p, const std::string& name, E fallback,
         const std::vector<std::pair<std::string, E>>& options) {
  if (!p.has(name)) return fallback;
  const std::string value = p.text(name, "");
  for (const auto& [key, e] : options)
    if (key == value) return e;
  std::string list;
  for (const auto& [key, e] : options) list += (list.empty() ? "" : ", ") + key;
  throw GeneratorError("parameter '" + name + "': unknown value '" + value + "' (known: " + list + ")");
}

/// The name of an enum value in `options` (for documentation and tests).
template <class E>
std::string choiceName(E value, const std::vector<std::pair<std::string, E>>& options) {
  for (const auto& [key, e] : options)
    if (e == value) return key;
  return {};
}

/// A list of exactly `size` numbers as a vector, or nullopt when absent.
inline std::optional<Eigen::VectorXd> fixedNumbers(const GeneratorParameters& p, const std::string& name, int size) {
  if (!p.has(name)) return std::nullopt;
  const std::vector<double> values = p.numbers(name);
  if (static_cast<int>(values.size()) != size)
    throw GeneratorError("parameter '" + name + "': expected " + std::to_string(size) + " numbers, got " +
                         std::to_string(values.size()));
  return Eigen::Map<const Eigen::VectorXd>(values.data(), size);
}

inline std::optional<Eigen::Vector3d> optionalVector3(const GeneratorParameters& p, const std::string& name) {
  if (auto v = fixedNumbers(p, name, 3)) return Eigen::Vector3d(*v);
  return std::nullopt;
}

inline Eigen::Vector3d vector3(const GeneratorParameters& p, const std::string& name, const Eigen::Vector3d& fallback) {
  return optionalVector3(p, name).value_or(fallback);
}

/// A list of numbers (any length) as an Eigen vector; empty when absent.
inline Eigen::VectorXd vectorX(const GeneratorParameters& p, const std::string& name) {
  const std::vector<double> values = p.numbers(name);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// A whole number in [lo, hi] read from a list or row entry; `where` names it in the error.
inline int wholeNumber(double x, const std::string& where, int lo, int hi) {
  if (const std::string problem = detail::integerProblem(x, lo, hi); !problem.empty()) throw GeneratorError(where + ": " + problem);
  return static_cast<int>(x);
}

/// A list of whole numbers in [lo, hi] (indices, counts); empty when absent.
inline std::vector<int> integers(const GeneratorParameters& p, const std::string& name, int lo, int hi) {
  std::vector<int> result;
  const std::vector<double> values = p.numbers(name);
  for (std::size_t i = 0; i < values.size(); ++i)
    result.push_back(wholeNumber(values[i], "parameter '" + name + "' entry " + std::to_string(i), lo, hi));
  return result;
}

/// Points as rows of 3 numbers, at least `minimum` of them. @throws when absent.
inline Eigen::MatrixX3d points3(const GeneratorParameters& p, const std::string& name, int minimum) {
  Eigen::MatrixX3d points = p.rows(name, 3);
  if (points.rows() < minimum)
    throw GeneratorError("parameter '" + name + "': expected at least " + std::to_string(minimum) +
                         " points, got " + std::to_string(points.rows()));
  return points;
}

/// Rows of any length (e.g. polygon faces), or empty when absent.
inline std::vector<std::vector<double>> raggedRows(const GeneratorParameters& p, const std::string& name) {
  auto it = p.values().find(name);
  if (it == p.values().end()) return {};
  if (const auto* rows = std::get_if<std::vector<std::vector<double>>>(&it->second)) return *rows;
  // a single row written as a flat list is not a list of rows: say so
  throw GeneratorError("parameter '" + name + "': expected a list of rows");
}

/// A polyline as points + segments; a closed polyline gets its closing segment.
inline MeshData polylineMesh(const geometry::Polyline& polyline) {
  MeshData mesh;
  mesh.points = polyline.points;
  const int n = static_cast<int>(polyline.points.rows());
  const int segments = n < 2 ? 0 : (polyline.closed && n >= 3 ? n : n - 1);
  mesh.segments.resize(segments, 2);
  for (int i = 0; i < segments; ++i) mesh.segments.row(i) << i, (i + 1) % n;
  return mesh;
}

/// A triangle mesh as points + triangles; writers recompute normals (hasNormals).
inline MeshData triangleMesh(const geometry::TriangleMesh& surface) {
  MeshData mesh;
  mesh.points = surface.vertices;
  mesh.triangles = surface.triangles;
  mesh.hasNormals = true;
  return mesh;
}

void addQuaternionGenerators(GeneratorRegistry& registry);
void addG3Generators(GeneratorRegistry& registry);
void addCardinalGenerators(GeneratorRegistry& registry);
void addPolyhedronGenerators(GeneratorRegistry& registry);
void addCurvenetGenerators(GeneratorRegistry& registry);

}  // namespace ffdkit::scenes::generators
