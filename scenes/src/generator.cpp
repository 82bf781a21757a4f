#include "ffdkit/scenes/generator.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "json_text.h"

namespace ffdkit::scenes {
namespace {

const char* typeName(const ParameterValue& value) {
  switch (value.index()) {
    case 0: return "a flag";
    case 1: return "a number";
    case 2: return "a string";
    case 3: return "a list of numbers";
    default: return "a list of rows";
  }
}

template <class T>
const T* typed(const std::map<std::string, ParameterValue>& values, const std::string& name, const char* expected) {
  auto it = values.find(name);
  if (it == values.end()) return nullptr;
  if (const T* value = std::get_if<T>(&it->second)) return value;
  throw GeneratorError("parameter '" + name + "': expected " + expected + ", got " + typeName(it->second));
}

}  // namespace

double GeneratorParameters::number(const std::string& name, double fallback) const {
  const double* value = typed<double>(values_, name, "a number");
  if (value == nullptr) return fallback;
  if (!std::isfinite(*value)) throw GeneratorError("parameter '" + name + "': must be finite");
  return *value;
}

int GeneratorParameters::integer(const std::string& name, int fallback) const {
  return integer(name, fallback, -1'000'000'000, 1'000'000'000);
}

int GeneratorParameters::integer(const std::string& name, int fallback, int lo, int hi) const {
  const double* value = typed<double>(values_, name, "a whole number");
  if (value == nullptr) return fallback;
  if (const std::string problem = detail::integerProblem(*value, lo, hi); !problem.empty())
    throw GeneratorError("parameter '" + name + "': " + problem);
  return static_cast<int>(*value);
}

bool GeneratorParameters::flag(const std::string& name, bool fallback) const {
  const bool* value = typed<bool>(values_, name, "true or false");
  return value == nullptr ? fallback : *value;
}

std::string GeneratorParameters::text(const std::string& name, const std::string& fallback) const {
  const std::string* value = typed<std::string>(values_, name, "a string");
  return value == nullptr ? fallback : *value;
}

std::vector<double> GeneratorParameters::numbers(const std::string& name, std::vector<double> fallback) const {
  const auto* value = typed<std::vector<double>>(values_, name, "a list of numbers");
  if (value == nullptr) return fallback;
  for (double x : *value)
    if (!std::isfinite(x)) throw GeneratorError("parameter '" + name + "': all numbers must be finite");
  return *value;
}

Eigen::MatrixXd GeneratorParameters::rows(const std::string& name, int columns, bool required) const {
  const auto* value = typed<std::vector<std::vector<double>>>(values_, name, "a list of rows");
  if (value == nullptr) {
    if (required) throw GeneratorError("missing parameter '" + name + "'");
    return Eigen::MatrixXd(0, columns);
  }
  Eigen::MatrixXd matrix(static_cast<Eigen::Index>(value->size()), columns);
  for (std::size_t r = 0; r < value->size(); ++r) {
    const auto& row = (*value)[r];
    if (static_cast<int>(row.size()) != columns)
      throw GeneratorError("parameter '" + name + "' row " + std::to_string(r) + ": expected " +
                           std::to_string(columns) + " numbers, got " + std::to_string(row.size()));
    for (int c = 0; c < columns; ++c) {
      if (!std::isfinite(row[std::size_t(c)]))
        throw GeneratorError("parameter '" + name + "' row " + std::to_string(r) + ": non-finite number");
      matrix(static_cast<Eigen::Index>(r), c) = row[std::size_t(c)];
    }
  }
  return matrix;
}

void GeneratorParameters::checkKnown(const std::vector<std::string>& known) const {
  for (const auto& [name, value] : values_) {
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw GeneratorError("unknown parameter '" + name + "' (known: " + list + ")");
  }
}

void GeneratorRegistry::add(Generator generator) {
  if (generator.name.empty() || !generator.generate)
    throw std::invalid_argument("GeneratorRegistry::add: a generator needs a name and a function");
  if (generators_.count(generator.name) != 0)
    throw std::invalid_argument("GeneratorRegistry::add: duplicate generator '" + generator.name + "'");
  std::string name = generator.name;
  generators_.emplace(std::move(name), std::move(generator));
}

const Generator& GeneratorRegistry::get(const std::string& name) const {
  auto it = generators_.find(name);
  if (it != generators_.end()) return it->second;
  std::string list;
  for (const auto& [known, g] : generators_) list += (list.empty() ? "" : ", ") + known;
  throw GeneratorError("unknown generator '" + name + "' (known: " + list + ")");
}

std::vector<std::string> GeneratorRegistry::names() const {
  std::vector<std::string> result;
  for (const auto& [name, g] : generators_) result.push_back(name);
  return result;
}

MeshData GeneratorRegistry::generate(const std::string& name, const GeneratorParameters& parameters,
                                     double density) const {
  const Generator& generator = get(name);
  if (!(density > 0.0) || !std::isfinite(density) || density > 64.0)
    throw GeneratorError("generator '" + name + "': density must be in (0, 64], got " + std::to_string(density));
  try {
    parameters.checkKnown(generator.parameterNames);
    MeshData mesh = generator.generate(parameters, density);
    validateMesh(mesh, "generator '" + name + "'");
    return mesh;
  } catch (const GeneratorError& e) {
    throw GeneratorError("generator '" + name + "': " + e.what());
  } catch (const MeshIoError& e) {
    throw GeneratorError(e.what());
  } catch (const std::bad_alloc&) {
    throw GeneratorError("generator '" + name + "': out of memory while generating (a read charges its pointBound first)");
  } catch (const std::exception& e) {
    throw GeneratorError("generator '" + name + "': " + e.what());
  }
}

MeshData GeneratorRegistry::generate(const std::string& name, const GeneratorParameters& parameters, double density,
                                     meshio::ReadBudget& budget) const {
  const Generator& generator = get(name);
  const std::string what = "generator '" + name + "'";
  try {
    if (generator.pointBound) {
      if (!(density > 0.0) || !std::isfinite(density) || density > 64.0)
        throw GeneratorError("density must be in (0, 64], got " + std::to_string(density));
      parameters.checkKnown(generator.parameterNames);
      const std::uint64_t bound = generator.pointBound(parameters, density);
      budget.chargePoints(bound, "up to " + std::to_string(bound) + " points");
      budget.chargeBytes(bound, kGeneratedBytesPerPoint, "their triangles or segments and working copies");
    }
  } catch (const GeneratorError& e) {
    throw GeneratorError(what + ": " + e.what());
  } catch (const std::exception& e) {
    throw GeneratorError(what + ": " + e.what());
  }
  MeshData mesh = generate(name, parameters, density);
  if (!generator.pointBound) {
    try {
      budget.chargePoints(std::uint64_t(mesh.points.rows()), "its points");
      budget.chargeBytes(std::uint64_t(mesh.points.rows()), kGeneratedBytesPerPoint, "their triangles or segments and working copies");
    } catch (const std::exception& e) {
      throw GeneratorError(what + ": " + e.what());
    }
  }
  return mesh;
}

CurvatureProfile GeneratorRegistry::profile(const std::string& name, const GeneratorParameters& parameters,
                                            double density) const {
  const Generator& generator = get(name);
  if (!generator.profile) throw GeneratorError("generator '" + name + "' makes a surface: it has no curvature profile");
  try {
    parameters.checkKnown(generator.parameterNames);
    return generator.profile(parameters, density);
  } catch (const GeneratorError& e) {
    throw GeneratorError("generator '" + name + "': " + e.what());
  } catch (const std::exception& e) {
    throw GeneratorError("generator '" + name + "': " + e.what());
  }
}

}  // namespace ffdkit::scenes
