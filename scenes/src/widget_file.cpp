#include "ffdkit/scenes/widget_file.h"

#include <algorithm>

#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <new>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ffdkit/ffd/lattice.h"
#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/read_failures.h"
#include "json_text.h"
#include "widget_json.h"

namespace ffdkit::scenes {
namespace {

using detail::Json;
using namespace ffdkit::widgets;

constexpr const char* kFormatName = "ffdkit-widgets";

using Location = detail::JsonLocation<WidgetFileError>;
using detail::boolean;
using detail::checkArray;
using detail::checkKeys;
using detail::checkObject;
using detail::integerIn;
using detail::intIn;
using detail::member;
using detail::number;
using detail::text;

WidgetId widgetId(const Json& j, const Location& at) {
  const std::string s = text(j, at);
  auto id = parseWidgetId(s);
  if (!id) at.fail("expected a widget id like 'w3', got '" + s + "'");
  return *id;
}

BindingId bindingId(const Json& j, const Location& at) {
  const std::string s = text(j, at);
  auto id = parseBindingId(s);
  if (!id) at.fail("expected a binding id like 'b3', got '" + s + "'");
  return *id;
}

// Points per lattice axis, and grid indices along one: what a file may ask for before the budget
// counts the whole lattice (WidgetModel keeps a lattice's flat point indices in int).
constexpr int kMaxLatticeAxisCount = 1'000'000;
constexpr std::uint64_t kMaxLatticePoints = ffd::kMaxLatticeControlPoints;
constexpr int kMaxBasisDegree = 32;  // the B-spline evaluation's fixed-size tables (ffd/bspline_basis)

// Three integers, each in [lo, hi].
Eigen::Vector3i vector3i(const Json& j, int lo, int hi, const Location& at) {
  checkArray(j, at);
  if (j.size() != 3) at.fail("expected 3 integers, got " + std::to_string(j.size()) + " values");
  return {intIn(j[0], lo, hi, at / 0), intIn(j[1], lo, hi, at / 1), intIn(j[2], lo, hi, at / 2)};
}

Eigen::MatrixX3d points(const Json& j, const Location& at) {
  checkArray(j, at);
  Eigen::MatrixX3d p(static_cast<Eigen::Index>(j.size()), 3);
  for (std::size_t r = 0; r < j.size(); ++r) {
    const Location ar = at / r;
    checkArray(j[r], ar);
    if (j[r].size() != 3) ar.fail("expected a point [x, y, z], got " + std::to_string(j[r].size()) + " values");
    for (std::size_t c = 0; c < 3; ++c) p(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = number(j[r][c], ar / c);
  }
  return p;
}

// An affine map as its top three rows [[r00, r01, r02, t0], ...].
Eigen::Affine3d affine(const Json& j, const Location& at) {
  checkArray(j, at);
  if (j.size() != 3) at.fail("expected 3 rows [r0, r1, r2, t] of an affine map, got " + std::to_string(j.size()));
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  for (std::size_t r = 0; r < 3; ++r) {
    const Location ar = at / r;
    checkArray(j[r], ar);
    if (j[r].size() != 4) ar.fail("expected 4 numbers per row, got " + std::to_string(j[r].size()));
    for (std::size_t c = 0; c < 4; ++c) a.matrix()(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = number(j[r][c], ar / c);
  }
  return a;
}

template <class T>
T named(const std::optional<T>& parsed, const std::string& name, const char* what, const char* known, const Location& at) {
  if (!parsed) at.fail(std::string("unknown ") + what + " '" + name + "' (known: " + known + ")");
  return *parsed;
}

std::string_view basisKindName(ffd::AxisBasis::Kind kind) {
  switch (kind) {
    case ffd::AxisBasis::Kind::Bernstein: return "bernstein";
    case ffd::AxisBasis::Kind::BSpline: return "bspline";
    case ffd::AxisBasis::Kind::PeriodicBSpline: return "periodic-bspline";
  }
  return "unknown";
}

std::string_view outsideKindName(ffd::OutsidePolicy::Kind kind) {
  switch (kind) {
    case ffd::OutsidePolicy::Kind::Identity: return "identity";
    case ffd::OutsidePolicy::Kind::ClampEdge: return "clamp-edge";
    case ffd::OutsidePolicy::Kind::Extrapolate: return "extrapolate";
    case ffd::OutsidePolicy::Kind::Falloff: return "falloff";
  }
  return "unknown";
}

ffd::AxisBasis readBasis(const Json& j, const Location& at) {
  checkObject(j, at);
  checkKeys(j, {"kind", "degree", "knots"}, at);
  const std::string kind = text(member(j, "kind", at), at / "kind");
  ffd::AxisBasis b = ffd::AxisBasis::bernstein();
  if (kind == "bernstein") {
    if (j.contains("degree") || j.contains("knots")) at.fail("a Bernstein basis takes no degree or knots");
    return b;
  }
  if (kind == "bspline") b = ffd::AxisBasis::bspline(intIn(member(j, "degree", at), 1, kMaxBasisDegree, at / "degree"));
  else if (kind == "periodic-bspline")
    b = ffd::AxisBasis::periodic(intIn(member(j, "degree", at), 1, kMaxBasisDegree, at / "degree"));
  else (at / "kind").fail("unknown basis '" + kind + "' (known: bernstein, bspline, periodic-bspline)");
  if (j.contains("knots")) {
    if (kind != "bspline") (at / "knots").fail("only a bspline basis takes explicit knots");
    const Json& k = j["knots"];
    checkArray(k, at / "knots");
    b.knots.resize(static_cast<Eigen::Index>(k.size()));
    for (std::size_t i = 0; i < k.size(); ++i) b.knots[static_cast<Eigen::Index>(i)] = number(k[i], at / "knots" / i);
  }
  return b;
}

CellSpec readCellSpec(const Json& j, CellKind kind, const Location& at) {
  CellSpec s;
  s.kind = kind;
  switch (kind) {
    case CellKind::Point:
    case CellKind::Box: s.base = vector3i(member(j, "base", at), 0, kMaxLatticeAxisCount - 1, at / "base"); break;
    case CellKind::Edge:
    case CellKind::Face:
      s.base = vector3i(member(j, "base", at), 0, kMaxLatticeAxisCount - 1, at / "base");
      s.axis = intIn(member(j, "axis", at), 0, 2, at / "axis");
      break;
    case CellKind::Slab: {
      s.axis = intIn(member(j, "axis", at), 0, 2, at / "axis");
      s.base[s.axis] = intIn(member(j, "plane", at), 0, kMaxLatticeAxisCount - 1, at / "plane");
      break;
    }
    case CellKind::Custom: {
      const Json& idx = member(j, "indices", at);
      checkArray(idx, at / "indices");
      s.indices.reserve(idx.size());
      for (std::size_t i = 0; i < idx.size(); ++i)
        s.indices.push_back(integerIn(idx[i], 0, std::int64_t(kMaxLatticePoints) - 1, at / "indices" / i));
      break;
    }
  }
  return s;
}

// What a file's widgets cost beyond their points (names, frames, glyphs, revisions: the model's
// node of each widget, and the reader's copy of it), charged per widget and per binding.
constexpr std::uint64_t kWidgetNodeBytes = 1024;
constexpr std::uint64_t kBindingBytes = 256;
// Bytes per lattice point beyond the point itself (chargePoints counts 24): its rest point, and
// the reader's copies of both that live until the model is built.
constexpr std::uint64_t kLatticePointCopyBytes = 3 * 3 * sizeof(double);
// Bytes per point of a cell: its flat index and its rest position.
constexpr std::uint64_t kCellPointBytes = sizeof(Eigen::Index) + 3 * sizeof(double);

// The control points of a lattice of `counts`, charged before its arrays are built.
void chargeLattice(const Eigen::Vector3i& counts, const std::string& name, meshio::ReadBudget& budget, const Location& at) {
  const std::uint64_t n = std::uint64_t(counts.x()) * std::uint64_t(counts.y()) * std::uint64_t(counts.z());
  const std::string what = "lattice '" + name + "' asks for " + std::to_string(counts.x()) + " x " + std::to_string(counts.y()) +
                           " x " + std::to_string(counts.z()) + " = " + std::to_string(n) + " control points";
  if (n > kMaxLatticePoints) at.fail(what + ", more than a lattice holds (" + std::to_string(kMaxLatticePoints) + ")");
  detail::chargePoints(budget, n, what, at);
  detail::chargeBytes(budget, n, kLatticePointCopyBytes, "lattice '" + name + "': its rest points and the reader's copies", at);
}

// The points of a cell (its flat indices and rest positions), known from its spec and lattice.
std::uint64_t cellPointCount(const CellSpec& spec, const WidgetModelData& d, WidgetId lattice) {
  switch (spec.kind) {
    case CellKind::Point: return 1;
    case CellKind::Edge: return 2;
    case CellKind::Face: return 4;
    case CellKind::Box: return 8;
    case CellKind::Custom: return spec.indices.size();
    case CellKind::Slab:
      for (const LatticeData& l : d.lattices)
        if (l.id == lattice && spec.axis >= 0 && spec.axis <= 2)
          return std::uint64_t(l.counts[(spec.axis + 1) % 3]) * std::uint64_t(l.counts[(spec.axis + 2) % 3]);
      return 0;  // an unknown lattice: WidgetModel::fromData names it
  }
  return 0;
}

// The array `key` of `root` (an absent key: none): `bytesEach` of each element charged to the
// budget before any is read, then `readOne(element, its location)` for each, in order. The one
// loop every list of the file (lattices, cells, affines, bindings) is read by.
template <class ReadOne>
void readList(const Json& root, const char* key, std::uint64_t bytesEach, const char* what, const Location& at,
              meshio::ReadBudget& budget, ReadOne readOne) {
  if (!root.contains(key)) return;
  const Json& list = root[key];
  const Location listAt = at / key;
  checkArray(list, listAt);
  detail::chargeBytes(budget, list.size(), bytesEach, what, listAt);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Location itemAt = listAt / i;
    checkObject(list[i], itemAt);
    readOne(list[i], itemAt);
  }
}

// Checks the format name and version; returns the version.
int checkFormat(const Json& root, const Location& at) {
  checkObject(root, at);
  checkKeys(root, {"format", "version", "lattices", "rootOrder", "cells", "affines", "bindings"}, at);
  const std::string format = text(member(root, "format", at), at / "format");
  if (format != kFormatName) (at / "format").fail("expected '" + std::string(kFormatName) + "', got '" + format + "'");
  const int version = intIn(member(root, "version", at), 1, std::numeric_limits<int>::max(), at / "version");
  if (version > kWidgetFileVersion)
    (at / "version").fail("widget file version " + std::to_string(version) + " is newer than this build reads (" +
                          std::to_string(kWidgetFileVersion) + "); update ffdkit");
  return version;
}

// A lattice's control-point weights (version 2): `count` numbers, each finite and > 0.
Eigen::VectorXd readWeights(const Json& j, Eigen::Index count, const Location& at) {
  checkArray(j, at);
  if (static_cast<Eigen::Index>(j.size()) != count)
    at.fail("expected " + std::to_string(count) + " weights (one per control point), got " + std::to_string(j.size()));
  Eigen::VectorXd w(count);
  for (std::size_t i = 0; i < j.size(); ++i) {
    w[static_cast<Eigen::Index>(i)] = number(j[i], at / i);
    if (!(w[static_cast<Eigen::Index>(i)] > 0.0)) (at / i).fail("a weight must be > 0, got " + j[i].dump());
  }
  return w;
}

ffd::OutsidePolicy readOutsidePolicy(const Json& o, const Location& at) {
  checkObject(o, at);
  checkKeys(o, {"policy", "distance"}, at);
  const std::string policy = text(member(o, "policy", at), at / "policy");
  using K = ffd::OutsidePolicy::Kind;
  ffd::OutsidePolicy outside;
  bool found = false;
  for (K k : {K::Identity, K::ClampEdge, K::Extrapolate, K::Falloff}) {
    if (outsideKindName(k) == policy) {
      outside.kind = k;
      found = true;
    }
  }
  if (!found) (at / "policy").fail("unknown outside policy '" + policy + "' (known: identity, clamp-edge, extrapolate, falloff)");
  if (outside.kind == K::Falloff) outside.distance = number(member(o, "distance", at), at / "distance");
  else if (o.contains("distance")) (at / "distance").fail("only the falloff policy takes a distance");
  return outside;
}

void readReembedPolicy(const Json& r, const Location& at, LatticeSettings& settings) {
  checkObject(r, at);
  checkKeys(r, {"policy", "n"}, at);
  const std::string policy = text(member(r, "policy", at), at / "policy");
  settings.reembed.kind = named(parseReembedKind(policy), policy, "re-embed policy", "immediate, every-n, on-release", at / "policy");
  if (settings.reembed.kind == ReembedKind::EveryN) settings.reembed.everyN = intIn(member(r, "n", at), 1, 1'000'000, at / "n");
  else if (r.contains("n")) (at / "n").fail("only the every-n policy takes n");
}

ffd::CylinderRestShape readCylinder(const Json& c, const Location& at) {
  checkKeys(c, {"innerRadius", "outerRadius", "zMin", "zMax"}, at);
  ffd::CylinderRestShape shape;
  shape.innerRadius = number(member(c, "innerRadius", at), at / "innerRadius");
  shape.outerRadius = number(member(c, "outerRadius", at), at / "outerRadius");
  shape.zMin = number(member(c, "zMin", at), at / "zMin");
  shape.zMax = number(member(c, "zMax", at), at / "zMax");
  if (shape.innerRadius < 0.0 || shape.outerRadius <= shape.innerRadius || shape.zMax <= shape.zMin)
    at.fail("expected 0 <= innerRadius < outerRadius and zMin < zMax");
  return shape;
}

// The rest points a file gives, else the default box lattice of the bases (Greville abscissae for
// B-splines).
Eigen::MatrixX3d readRestPoints(const Json& j, const LatticeData& l, const Location& at) {
  if (j.contains("rest")) return points(j["rest"], at / "rest");
  ffd::BoxLatticeOptions box;
  box.counts = l.counts;
  box.bases = l.settings.basis;
  box.capDegreeToCount = false;
  try {
    return ffd::makeBoxLattice(box).restPoints();
  } catch (const std::invalid_argument& e) {
    (at / "basis").fail(e.what());
  }
}

// One lattice; its control points are charged to the budget as soon as its counts are known.
LatticeData readLattice(const Json& j, const Location& at, meshio::ReadBudget& budget, int version) {
  checkKeys(j, {"id", "name", "counts", "basis", "outside", "reembed", "cylinder", "frame", "children", "rest", "points", "weights"},
            at);
  LatticeData l;
  l.id = widgetId(member(j, "id", at), at / "id");
  l.name = text(member(j, "name", at), at / "name");
  l.counts = vector3i(member(j, "counts", at), 2, kMaxLatticeAxisCount, at / "counts");
  chargeLattice(l.counts, l.name, budget, at / "counts");
  if (j.contains("basis")) {
    const Json& b = j["basis"];
    checkArray(b, at / "basis");
    if (b.size() != 3) (at / "basis").fail("expected one basis per axis (3), got " + std::to_string(b.size()));
    for (std::size_t a = 0; a < 3; ++a) l.settings.basis[a] = readBasis(b[a], at / "basis" / a);
  }
  if (j.contains("outside")) l.settings.outside = readOutsidePolicy(j["outside"], at / "outside");
  if (j.contains("reembed")) readReembedPolicy(j["reembed"], at / "reembed", l.settings);
  if (j.contains("cylinder")) l.settings.cylinder = readCylinder(j["cylinder"], at / "cylinder");
  if (j.contains("frame")) l.frame = affine(j["frame"], at / "frame");
  if (j.contains("children")) {
    const Json& c = j["children"];
    checkArray(c, at / "children");
    for (std::size_t k = 0; k < c.size(); ++k) l.children.push_back(widgetId(c[k], at / "children" / k));
  }
  l.restPoints = readRestPoints(j, l, at);
  l.controlPoints = j.contains("points") ? points(j["points"], at / "points") : l.restPoints;
  if (j.contains("weights")) {
    if (version < 2)
      (at / "weights").fail("'weights' needs widget file version 2 (this file says version " + std::to_string(version) + ")");
    l.weights = readWeights(j["weights"], static_cast<Eigen::Index>(l.counts.prod()), at / "weights");
  }
  return l;
}

// One cell; its points are charged once its spec (and, for a slab, its lattice) says how many.
CellData readCell(const Json& j, const Location& at, const WidgetModelData& d, meshio::ReadBudget& budget) {
  CellData c;
  c.id = widgetId(member(j, "id", at), at / "id");
  c.name = text(member(j, "name", at), at / "name");
  c.lattice = widgetId(member(j, "lattice", at), at / "lattice");
  const std::string kind = text(member(j, "kind", at), at / "kind");
  const CellKind k = named(parseCellKind(kind), kind, "cell kind", "point, edge, face, slab, box, custom", at / "kind");
  switch (k) {
    case CellKind::Point:
    case CellKind::Box: checkKeys(j, {"id", "name", "lattice", "kind", "base"}, at); break;
    case CellKind::Edge:
    case CellKind::Face: checkKeys(j, {"id", "name", "lattice", "kind", "base", "axis"}, at); break;
    case CellKind::Slab: checkKeys(j, {"id", "name", "lattice", "kind", "axis", "plane"}, at); break;
    case CellKind::Custom: checkKeys(j, {"id", "name", "lattice", "kind", "indices"}, at); break;
  }
  c.spec = readCellSpec(j, k, at);
  detail::chargeBytes(budget, cellPointCount(c.spec, d, c.lattice), kCellPointBytes, "cell '" + c.name + "': its points", at);
  return c;
}

AffineData readAffine(const Json& j, const Location& at) {
  checkKeys(j, {"id", "name", "kind", "placement", "variation", "glyph"}, at);
  AffineData a;
  a.id = widgetId(member(j, "id", at), at / "id");
  a.name = text(member(j, "name", at), at / "name");
  const std::string kind = text(member(j, "kind", at), at / "kind");
  a.kind = named(parseAffineKind(kind), kind, "affine widget kind", "translate, rotate, scale", at / "kind");
  if (j.contains("placement")) a.placement = affine(j["placement"], at / "placement");
  if (j.contains("variation")) a.variation = number(j["variation"], at / "variation");
  a.glyph.shape = a.kind == AffineKind::Translate ? "arrow" : a.kind == AffineKind::Rotate ? "ring" : "cube";
  if (j.contains("glyph")) {
    const Json& g = j["glyph"];
    const Location ag = at / "glyph";
    checkObject(g, ag);
    checkKeys(g, {"shape", "size", "placement"}, ag);
    if (g.contains("shape")) a.glyph.shape = text(g["shape"], ag / "shape");
    if (g.contains("size")) a.glyph.size = number(g["size"], ag / "size");
    if (g.contains("placement")) a.glyph.partPlacement = affine(g["placement"], ag / "placement");
  }
  return a;
}

// One binding: a variation binding's conversion rule (gain, clamp), or another kind's mask.
Binding readBinding(const Json& j, const Location& at) {
  Binding b;
  b.id = bindingId(member(j, "id", at), at / "id");
  const std::string kind = text(member(j, "kind", at), at / "kind");
  b.kind = named(parseBindingKind(kind), kind, "binding kind", "attachment, variation, cell-motion, hierarchy", at / "kind");
  if (b.kind == BindingKind::Variation) {
    checkKeys(j, {"id", "kind", "from", "to", "gain", "clamp", "oneWay"}, at);
    b.mask = AffineMask::none();
    b.rule.gain = j.contains("gain") ? number(j["gain"], at / "gain") : 1.0;
    if (j.contains("clamp")) {
      const Json& c = j["clamp"];
      checkArray(c, at / "clamp");
      if (c.size() != 2) (at / "clamp").fail("expected [min, max]");
      b.rule.clamp = VariationRange{number(c[0], at / "clamp" / 0), number(c[1], at / "clamp" / 1)};
    }
  } else {
    checkKeys(j, {"id", "kind", "from", "to", "mask", "oneWay"}, at);
    const std::string mask = text(member(j, "mask", at), at / "mask");
    b.mask = named(parseMask(mask), mask, "mask", "letters T, R, S, e.g. \"TR\"", at / "mask");
  }
  b.from = widgetId(member(j, "from", at), at / "from");
  b.to = widgetId(member(j, "to", at), at / "to");
  if (j.contains("oneWay")) b.oneWay = boolean(j["oneWay"], at / "oneWay");
  return b;
}

// The lattice tree's order: the file's rootOrder, or by default the roots in file order; a
// lattice without "children" gets its children in binding order.
void readTreeOrder(const Json& root, const Location& at, WidgetModelData& d) {
  if (root.contains("rootOrder")) {
    const Json& r = root["rootOrder"];
    checkArray(r, at / "rootOrder");
    for (std::size_t k = 0; k < r.size(); ++k) d.rootOrder.push_back(widgetId(r[k], at / "rootOrder" / k));
  } else {
    for (const LatticeData& l : d.lattices) {
      bool child = false;
      for (const Binding& b : d.bindings) child = child || (b.kind == BindingKind::Hierarchy && b.to == l.id);
      if (!child) d.rootOrder.push_back(l.id);
    }
  }
  if (d.lattices.empty()) return;
  const Json& lattices = root["lattices"];
  for (std::size_t i = 0; i < d.lattices.size(); ++i) {
    if (lattices[i].contains("children")) continue;
    for (const Binding& b : d.bindings) {
      if (b.kind != BindingKind::Hierarchy) continue;
      for (const CellData& c : d.cells)
        if (c.id == b.from && c.lattice == d.lattices[i].id) d.lattices[i].children.push_back(b.to);
    }
  }
}

WidgetModelData readData(const Json& root, const Location& at, meshio::ReadBudget& budget) {
  const int version = checkFormat(root, at);
  WidgetModelData d;
  readList(root, "lattices", kWidgetNodeBytes, "lattices", at, budget,
           [&](const Json& j, const Location& li) { d.lattices.push_back(readLattice(j, li, budget, version)); });
  readList(root, "cells", kWidgetNodeBytes, "cells", at, budget,
           [&](const Json& j, const Location& ci) { d.cells.push_back(readCell(j, ci, d, budget)); });
  readList(root, "affines", kWidgetNodeBytes, "affine widgets", at, budget,
           [&](const Json& j, const Location& ai) { d.affines.push_back(readAffine(j, ai)); });
  readList(root, "bindings", kBindingBytes, "bindings", at, budget,
           [&](const Json& j, const Location& bi) { d.bindings.push_back(readBinding(j, bi)); });
  readTreeOrder(root, at, d);
  return d;
}

// ---- writing ------------------------------------------------------------------------------

Json row(const Eigen::Ref<const Eigen::RowVectorXd>& r) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < r.size(); ++i) a.push_back(r[i]);
  return a;
}

Json affineJson(const Eigen::Affine3d& a) {
  Json rows = Json::array();
  for (int r = 0; r < 3; ++r) rows.push_back(row(a.matrix().row(r)));
  return rows;
}

Json pointsJson(const Eigen::MatrixX3d& p) {
  Json rows = Json::array();
  for (Eigen::Index r = 0; r < p.rows(); ++r) rows.push_back(row(p.row(r)));
  return rows;
}

Json ids(const std::vector<WidgetId>& list) {
  Json a = Json::array();
  for (WidgetId id : list) a.push_back(toString(id));
  return a;
}

Json toJson(const WidgetModelData& d) {
  Json root;
  root["format"] = kFormatName;
  // Version 2 only where weights appear: a tool without them is written as before, byte for byte.
  const bool weighted = std::any_of(d.lattices.begin(), d.lattices.end(), [](const LatticeData& l) { return l.weights.size() > 0; });
  root["version"] = weighted ? kWidgetFileVersion : 1;
  Json lattices = Json::array();
  for (const LatticeData& l : d.lattices) {
    Json j;
    j["id"] = toString(l.id);
    j["name"] = l.name;
    j["counts"] = {l.counts.x(), l.counts.y(), l.counts.z()};
    Json basis = Json::array();
    for (const ffd::AxisBasis& b : l.settings.basis) {
      Json jb;
      jb["kind"] = std::string(basisKindName(b.kind));
      if (b.kind != ffd::AxisBasis::Kind::Bernstein) jb["degree"] = b.degree;
      if (b.kind == ffd::AxisBasis::Kind::BSpline && b.knots.size() > 0) jb["knots"] = row(b.knots.transpose());
      basis.push_back(jb);
    }
    j["basis"] = basis;
    Json outside;
    outside["policy"] = std::string(outsideKindName(l.settings.outside.kind));
    if (l.settings.outside.kind == ffd::OutsidePolicy::Kind::Falloff) outside["distance"] = l.settings.outside.distance;
    j["outside"] = outside;
    Json reembed;
    reembed["policy"] = std::string(reembedKindName(l.settings.reembed.kind));
    if (l.settings.reembed.kind == ReembedKind::EveryN) reembed["n"] = l.settings.reembed.everyN;
    j["reembed"] = reembed;
    if (l.settings.cylinder) {
      const ffd::CylinderRestShape& c = *l.settings.cylinder;
      j["cylinder"] = {{"innerRadius", c.innerRadius}, {"outerRadius", c.outerRadius}, {"zMin", c.zMin}, {"zMax", c.zMax}};
    }
    j["frame"] = affineJson(l.frame);
    j["children"] = ids(l.children);
    j["rest"] = pointsJson(l.restPoints);
    j["points"] = pointsJson(l.controlPoints);
    if (l.weights.size() > 0) j["weights"] = row(l.weights.transpose());
    lattices.push_back(j);
  }
  root["lattices"] = lattices;
  root["rootOrder"] = ids(d.rootOrder);
  Json cells = Json::array();
  for (const CellData& c : d.cells) {
    Json j;
    j["id"] = toString(c.id);
    j["name"] = c.name;
    j["lattice"] = toString(c.lattice);
    j["kind"] = std::string(cellKindName(c.spec.kind));
    const Eigen::Vector3i& b = c.spec.base;
    switch (c.spec.kind) {
      case CellKind::Point:
      case CellKind::Box: j["base"] = {b.x(), b.y(), b.z()}; break;
      case CellKind::Edge:
      case CellKind::Face:
        j["base"] = {b.x(), b.y(), b.z()};
        j["axis"] = c.spec.axis;
        break;
      case CellKind::Slab:
        j["axis"] = c.spec.axis;
        j["plane"] = b[c.spec.axis];
        break;
      case CellKind::Custom: {
        Json idx = Json::array();
        for (Eigen::Index i : c.spec.indices) idx.push_back(i);
        j["indices"] = idx;
        break;
      }
    }
    cells.push_back(j);
  }
  root["cells"] = cells;
  Json affines = Json::array();
  for (const AffineData& a : d.affines) {
    Json j;
    j["id"] = toString(a.id);
    j["name"] = a.name;
    j["kind"] = std::string(affineKindName(a.kind));
    j["placement"] = affineJson(a.placement);
    j["variation"] = a.variation;
    Json g;
    g["shape"] = a.glyph.shape;
    g["size"] = a.glyph.size;
    g["placement"] = affineJson(a.glyph.partPlacement);
    j["glyph"] = g;
    affines.push_back(j);
  }
  root["affines"] = affines;
  Json bindings = Json::array();
  for (const Binding& b : d.bindings) {
    Json j;
    j["id"] = toString(b.id);
    j["kind"] = std::string(bindingKindName(b.kind));
    j["from"] = toString(b.from);
    j["to"] = toString(b.to);
    if (b.kind == BindingKind::Variation) {
      j["gain"] = b.rule.gain;
      if (b.rule.clamp) j["clamp"] = {b.rule.clamp->min, b.rule.clamp->max};
    } else {
      j["mask"] = maskString(b.mask);
    }
    j["oneWay"] = b.oneWay;
    bindings.push_back(j);
  }
  root["bindings"] = bindings;
  return root;
}

}  // namespace

namespace detail {

widgets::WidgetModel widgetModelFromJson(const Json& root, const std::string& sourceName, const std::string& pointer,
                                         meshio::ReadBudget& budget) {
  const Location at{&sourceName, pointer};
  const WidgetModelData data = readData(root, at, budget);
  try {
    return WidgetModel::fromData(data);
  } catch (const WidgetError& e) {
    throw WidgetFileError(sourceName + " " + pointer + (e.where().empty() ? (pointer.empty() ? "/" : "") : e.where()) + ": " +
                          e.message());
  }
}

Json widgetModelToJson(const widgets::WidgetModel& model) { return toJson(model.toData()); }

}  // namespace detail

WidgetModel readWidgetFile(std::istream& in, const std::string& sourceName) { return readWidgetFile(in, sourceName, {}); }

WidgetModel readWidgetFile(const std::filesystem::path& path) { return readWidgetFile(path, WidgetReadOptions{}); }

namespace {

// Reads the text of a widget file from `in` after charging `knownSize` bytes (the file's size,
// when known) or, for a stream of unknown size, what it held; then the model against the same
// budget. The one place that turns a failed allocation, or a budget overrun that escaped a
// located check, into a WidgetFileError.
WidgetModel readWidgetStream(std::istream& in, std::optional<std::uint64_t> knownSize, const std::string& sourceName,
                             const WidgetReadOptions& options) {
  meshio::ReadBudget ownBudget(options.limits);
  meshio::ReadBudget& budget = options.budget != nullptr ? *options.budget : ownBudget;
  return meshio::convertReadFailures<WidgetFileError>(sourceName, "the widget file", budget, [&] {
    if (knownSize) budget.chargeBytes(*knownSize, 1, "the text of the widget file");
    const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!knownSize) budget.chargeBytes(content.size(), 1, "the text of the widget file");
    return detail::widgetModelFromJson(detail::parseJson<WidgetFileError>(content, sourceName, budget), sourceName, "", budget);
  });
}

}  // namespace

WidgetModel readWidgetFile(std::istream& in, const std::string& sourceName, const WidgetReadOptions& options) {
  return readWidgetStream(in, std::nullopt, sourceName, options);
}

WidgetModel readWidgetFile(const std::filesystem::path& path, const WidgetReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw WidgetFileError(path.string() + ": cannot open the widget file for reading");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  return readWidgetStream(in, ec ? std::nullopt : std::optional<std::uint64_t>(size), path.string(), options);
}

std::string widgetFileText(const WidgetModel& model) { return detail::canonicalJsonText(detail::widgetModelToJson(model)); }

void writeWidgetFile(std::ostream& out, const WidgetModel& model) { out << widgetFileText(model); }

void writeWidgetFile(const std::filesystem::path& path, const WidgetModel& model) {
  try {
    meshio::writeFileAtomically(path, widgetFileText(model));
  } catch (const std::exception& e) {
    throw WidgetFileError(path.string() + ": cannot write the widget file: " + e.what());
  }
}

}  // namespace ffdkit::scenes
