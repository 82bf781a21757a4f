#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/mesh_io.h"

namespace ffdkit::scenes {

/// One generator parameter as it stands in a scene file: a flag, a number, a name, a list of
/// numbers, or a list of rows of numbers (points, a grid, per-vertex values).
using ParameterValue = std::variant<bool, double, std::string, std::vector<double>, std::vector<std::vector<double>>>;

/// A generator's parameters by name, with typed accessors whose errors name the parameter.
class GeneratorParameters {
 public:
  GeneratorParameters() = default;
  /// Parameters with these values.
  explicit GeneratorParameters(std::map<std::string, ParameterValue> values) : values_(std::move(values)) {}

  /// True when parameter `name` is present.
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  /// Sets parameter `name`.
  void set(const std::string& name, ParameterValue value) { values_[name] = std::move(value); }
  /// Every parameter by name.
  const std::map<std::string, ParameterValue>& values() const { return values_; }

  /// The value, or `fallback` when absent. @throws GeneratorError when present with another type.
  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback) const;  ///< a whole number in [-1e9, 1e9]
  /// A whole number in [lo, hi] (the rule scene files apply to every integer):
  /// "parameter 'samples': expected an integer in [2, 100000000], got 10.5".
  int integer(const std::string& name, int fallback, int lo, int hi) const;
  /// A true / false parameter, or `fallback` when absent. @throws GeneratorError for another type.
  bool flag(const std::string& name, bool fallback) const;
  /// A text parameter, or `fallback` when absent. @throws GeneratorError for another type.
  std::string text(const std::string& name, const std::string& fallback) const;
  /// A list of numbers, or `fallback` when absent. @throws GeneratorError for another type.
  std::vector<double> numbers(const std::string& name, std::vector<double> fallback = {}) const;
  /// Rows of `columns` numbers as a #rows x columns matrix (e.g. points, columns = 3).
  /// @throws GeneratorError when absent and `required`, or a row has another length.
  Eigen::MatrixXd rows(const std::string& name, int columns, bool required = true) const;

  /// Names present but not in `known`: a typo must not be silently ignored.
  /// @throws GeneratorError naming the unknown parameter and the known ones.
  void checkKnown(const std::vector<std::string>& known) const;

 private:
  std::map<std::string, ParameterValue> values_;
};

/// A generator that cannot run with the given parameters; what() names generator and parameter.
class GeneratorError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Curvature (and torsion) of a generated curve against arc length, for plots and combs.
struct CurvatureProfile {
  Eigen::VectorXd arcLength;  ///< #samples, ascending, from 0
  Eigen::VectorXd curvature;  ///< #samples, 1/length units (signed for planar curves)
  Eigen::VectorXd torsion;    ///< #samples, or empty for planar curves
  Eigen::MatrixX3d points;    ///< #samples x 3: where each sample lies
  Eigen::MatrixX3d normals;   ///< #samples x 3: unit principal normals (curvature comb direction)
};

/// A named curve or surface generator (a geometry topic plugged into scenes). A generated
/// object keeps its parameters; `density` scales its sampling, so that it can be regenerated
/// finer or coarser (1 = the generator's default sampling).
struct Generator {
  std::string name;     ///< as used in scene files, e.g. "qi-interpolate"
  std::string summary;  ///< one line for `ffdkit-cli info` and the GUI
  std::vector<std::string> parameterNames;  ///< the parameters it accepts (others are refused)
  std::function<MeshData(const GeneratorParameters&, double density)> generate;  ///< builds the curve or surface at `density`
  /// Curves only (empty for surfaces): the curvature profile at the same sampling.
  std::function<CurvatureProfile(const GeneratorParameters&, double density)> profile;
  /// An upper bound of the points `generate` makes from these parameters at `density`, found
  /// from the counts in the parameters and the sampling without generating, so that a reader
  /// can charge it to its budget first. Empty for a generator that cannot say: its points are
  /// then charged once generated.
  std::function<std::uint64_t(const GeneratorParameters&, double density)> pointBound;
};

/// Generators by name. Not a singleton: builtinGenerators() builds the registry of every
/// geometry topic, and callers pass a registry where it is needed.
class GeneratorRegistry {
 public:
  /// @throws std::invalid_argument for an empty or duplicate name or a missing function.
  void add(Generator generator);
  /// @throws GeneratorError naming the unknown generator and the known ones.
  const Generator& get(const std::string& name) const;
  /// True when a generator of that name is registered.
  bool contains(const std::string& name) const { return generators_.count(name) != 0; }
  /// The registered names, sorted.
  std::vector<std::string> names() const;

  /// Runs a generator: checks parameter names, runs it, validates the mesh (finite points,
  /// indices in range, not empty). @throws GeneratorError naming the generator.
  MeshData generate(const std::string& name, const GeneratorParameters& parameters, double density = 1.0) const;

  /// generate() as part of a read: the generator's pointBound (its points, and per point
  /// kGeneratedBytesPerPoint for its triangles or segments and working copies) is charged to
  /// `budget` before it runs. @throws GeneratorError naming the generator, with the budget's
  /// message when the bound is over it.
  MeshData generate(const std::string& name, const GeneratorParameters& parameters, double density,
                    meshio::ReadBudget& budget) const;

  /// The curvature profile of a curve generator. @throws GeneratorError for a surface
  /// generator or bad parameters, naming the generator.
  CurvatureProfile profile(const std::string& name, const GeneratorParameters& parameters, double density = 1.0) const;

 private:
  std::map<std::string, Generator> generators_;
};

/// Bytes a generated point costs beyond its coordinates, charged with it: about two triangles
/// (or one segment) of indices, the normals and parameters a tessellation computes beside the
/// points, and the copy into the object's mesh.
inline constexpr std::uint64_t kGeneratedBytesPerPoint = 96;

/// The registry with every generator of the geometry topics.
const GeneratorRegistry& builtinGenerators();

}  // namespace ffdkit::scenes
