// glTF 2.0 (.gltf JSON, .glb binary) through tinygltf (Debian's libtinygltf-dev), which parses
// the JSON and loads the buffers; everything read from a buffer is bounds-checked here first:
// accessor and buffer-view ranges, strides, index ranges, finiteness. All meshes of the default
// scene are merged with their node transforms applied; what the node tree instantiates (each
// mesh's primitives times the nodes that instance it) is counted and charged to the read's
// budget before anything is merged. Images are never decoded; every external file a URI names
// goes through the one confinement rule (path_confinement.h). A required extension, or morph
// targets with weights (which would move the points), is an error: the reader would drop them.
#include <algorithm>
#include <climits>
#include <set>

#include <Eigen/Geometry>
#include <tiny_gltf.h>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {
namespace {

namespace fs = std::filesystem;

struct Context {
  const tinygltf::Model& model;
  const std::string& source;
  [[noreturn]] void fail(const std::string& message) const { throw MeshIoError(source + ": " + message); }
};

// A checked window onto an accessor's elements.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int componentType = 0;
};

std::size_t componentSize(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

AccessorView view(const Context& c, int index, int type, int components, const std::string& what) {
  const auto& m = c.model;
  const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
  if (index < 0 || std::size_t(index) >= m.accessors.size())
    c.fail(what + ": accessor " + std::to_string(index) + " does not exist (" + std::to_string(m.accessors.size()) + " accessors)");
  const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
  if (a.sparse.isSparse) c.fail(name + ": sparse accessors are not supported");
  if (a.type != type) c.fail(name + ": wrong element type");
  const std::size_t size = componentSize(a.componentType);
  if (size == 0) c.fail(name + ": unsupported component type " + std::to_string(a.componentType));
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= m.bufferViews.size())
    c.fail(name + ": buffer view " + std::to_string(a.bufferView) + " does not exist");
  const tinygltf::BufferView& bv = m.bufferViews[std::size_t(a.bufferView)];
  if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size())
    c.fail(name + ": buffer " + std::to_string(bv.buffer) + " does not exist");
  const std::vector<unsigned char>& buffer = m.buffers[std::size_t(bv.buffer)].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
    c.fail(name + ": buffer view " + std::to_string(a.bufferView) + " (offset " + std::to_string(bv.byteOffset) + ", " +
           std::to_string(bv.byteLength) + " bytes) runs past its buffer of " + std::to_string(buffer.size()) + " bytes");
  const std::size_t element = size * std::size_t(components);
  const std::size_t stride = bv.byteStride != 0 ? bv.byteStride : element;
  if (stride < element) c.fail(name + ": byte stride " + std::to_string(stride) + " is smaller than an element");
  AccessorView v;
  v.count = a.count;
  v.stride = stride;
  v.componentType = a.componentType;
  if (a.count == 0) return v;
  // The last element must end inside the buffer view: offset + (count - 1) * stride + element.
  const std::size_t length = bv.byteLength;
  if (a.byteOffset > length || element > length - a.byteOffset ||
      a.count - 1 > (length - a.byteOffset - element) / stride)
    c.fail(name + ": " + std::to_string(a.count) + " elements of " + std::to_string(element) + " bytes from offset " +
           std::to_string(a.byteOffset) + " run past buffer view " + std::to_string(a.bufferView) + " of " +
           std::to_string(length) + " bytes");
  v.data = buffer.data() + bv.byteOffset + a.byteOffset;
  return v;
}

long long indexAt(const AccessorView& v, std::size_t k) {
  const unsigned char* p = v.data + k * v.stride;
  switch (v.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t i; std::memcpy(&i, p, 2); return i; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t i; std::memcpy(&i, p, 4); return i; }
    default: return -1;
  }
}

Eigen::Affine3d nodeTransform(const Context& c, const tinygltf::Node& node, int index) {
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (node.matrix.size() == 16) {
    Eigen::Matrix4d m;
    for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = node.matrix[std::size_t(k)];  // column-major
    t.matrix() = m;
  } else {
    if (node.translation.size() == 3) t.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)
      t.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
    if (node.scale.size() == 3) t.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  }
  if (!t.matrix().allFinite()) c.fail("node " + std::to_string(index) + ": non-finite transform");
  return t;
}

// a * b and a + b, saturating: a count that overflows is over any limit.
std::uint64_t product(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r = 0;
  return __builtin_mul_overflow(a, b, &r) ? UINT64_MAX : r;
}
std::uint64_t sum(std::uint64_t a, std::uint64_t b) { return b > UINT64_MAX - a ? UINT64_MAX : a + b; }

// The elements of accessor `index`, or 0 when it does not exist (view() says so when merging).
std::uint64_t accessorCount(const tinygltf::Model& m, int index) {
  return index >= 0 && std::size_t(index) < m.accessors.size() ? m.accessors[std::size_t(index)].count : 0;
}

// What one instance of a primitive adds: its points, and its cells' bytes in the merged mesh.
struct PrimitiveSize {
  std::uint64_t points = 0, triangles = 0, segments = 0;
};
PrimitiveSize primitiveSize(const tinygltf::Model& m, const tinygltf::Primitive& p) {
  PrimitiveSize size;
  const auto position = p.attributes.find("POSITION");
  size.points = position == p.attributes.end() ? 0 : accessorCount(m, position->second);
  const std::uint64_t n = p.indices >= 0 ? accessorCount(m, p.indices) : size.points;
  switch (p.mode) {
    case TINYGLTF_MODE_TRIANGLES: size.triangles = n / 3; break;
    case TINYGLTF_MODE_TRIANGLE_STRIP: case TINYGLTF_MODE_TRIANGLE_FAN: size.triangles = n > 2 ? n - 2 : 0; break;
    case TINYGLTF_MODE_LINE: size.segments = n / 2; break;
    case TINYGLTF_MODE_LINE_STRIP: size.segments = n > 1 ? n - 1 : 0; break;
    case TINYGLTF_MODE_LINE_LOOP: size.segments = n; break;
    default: break;
  }
  return size;
}

class Merger {
 public:
  explicit Merger(const Context& c) : c_(c), instances_(c.model.meshes.size(), 0) {}

  /// Walks the node tree counting the instances of each mesh (nothing is merged), then charges
  /// what they instantiate to `budget` and sizes the merged mesh for exactly that.
  template <class Roots>
  void plan(Roots&& walkRoots, ReadBudget& budget) {
    counting_ = true;
    walkRoots();
    counting_ = false;
    visited_.clear();
    PrimitiveSize total;
    std::uint64_t largest = 0;
    std::string what;
    for (std::size_t m = 0; m < instances_.size(); ++m) {
      if (instances_[m] == 0) continue;
      PrimitiveSize one;
      for (const tinygltf::Primitive& p : c_.model.meshes[m].primitives) {
        const PrimitiveSize s = primitiveSize(c_.model, p);
        one = {sum(one.points, s.points), sum(one.triangles, s.triangles), sum(one.segments, s.segments)};
      }
      const std::uint64_t points = product(instances_[m], one.points);
      total = {sum(total.points, points), sum(total.triangles, product(instances_[m], one.triangles)),
               sum(total.segments, product(instances_[m], one.segments))};
      if (points >= largest) {
        largest = points;
        what = "mesh " + std::to_string(m) + " (" + std::to_string(c_.model.meshes[m].primitives.size()) + " primitives, " +
               std::to_string(one.points) + " points) instanced by " + std::to_string(instances_[m]) + " nodes";
      }
    }
    const std::string scene = "the scene's nodes instantiate " + std::to_string(total.points) + " points; the most: " + what;
    budget.chargePoints(total.points, scene);
    budget.chargeBytes(total.triangles, TriangleSink::kRowBytes, "the scene's triangles");
    budget.chargeBytes(total.segments, SegmentSink::kRowBytes, "the scene's segments");
    if (total.points > std::uint64_t(INT_MAX)) c_.fail(scene + ", more than ffdkit indexes");
    points_ = PointSink(Eigen::Index(total.points));
    triangles_ = TriangleSink(Eigen::Index(total.triangles));
    segments_ = SegmentSink(Eigen::Index(total.segments));
  }

  void node(int index, const Eigen::Affine3d& parent, int depth) {
    if (index < 0 || std::size_t(index) >= c_.model.nodes.size()) c_.fail("node " + std::to_string(index) + " does not exist");
    // glTF nodes form trees: a node reached twice is a cycle or a shared child (both invalid,
    // and either could make the walk endless or exponential).
    if (depth > 256 || !visited_.insert(index).second) c_.fail("node " + std::to_string(index) + " is reached twice (the nodes must form trees)");
    const tinygltf::Node& n = c_.model.nodes[std::size_t(index)];
    const Eigen::Affine3d world = counting_ ? parent : parent * nodeTransform(c_, n, index);
    if (n.mesh >= 0) {
      if (std::size_t(n.mesh) < c_.model.meshes.size() && hasWeights(n.weights) && morphs(c_.model.meshes[std::size_t(n.mesh)]))
        c_.fail("node " + std::to_string(index) + ": morph target weights would move the points of mesh " + std::to_string(n.mesh) +
                " (ffdkit does not apply morph targets)");
      mesh(n.mesh, world);
    } else if (n.mesh != -1) {
      c_.fail("node " + std::to_string(index) + ": mesh " + std::to_string(n.mesh) + " does not exist");
    }
    for (int child : n.children) node(child, world, depth + 1);
  }

  void mesh(int index, const Eigen::Affine3d& world) {
    if (std::size_t(index) >= c_.model.meshes.size()) c_.fail("mesh " + std::to_string(index) + " does not exist");
    if (counting_) {
      ++instances_[std::size_t(index)];
      return;
    }
    const tinygltf::Mesh& m = c_.model.meshes[std::size_t(index)];
    if (hasWeights(m.weights) && morphs(m))
      c_.fail("mesh " + std::to_string(index) + ": morph target weights would move its points (ffdkit does not apply morph targets)");
    for (std::size_t p = 0; p < m.primitives.size(); ++p) primitive(m.primitives[p], world, "mesh " + std::to_string(index) + " primitive " + std::to_string(p));
  }

  MeshData take() {
    if (points_.rows() == 0) c_.fail("the file has no mesh points");
    MeshData mesh;
    mesh.points = points_.take();
    mesh.triangles = triangles_.take();
    mesh.segments = segments_.take();
    mesh.hasNormals = hasNormals_;
    return mesh;
  }

 private:
  void primitive(const tinygltf::Primitive& p, const Eigen::Affine3d& world, const std::string& what) {
    const auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end()) c_.fail(what + ": no POSITION attribute");
    const AccessorView points = view(c_, position->second, TINYGLTF_TYPE_VEC3, 3, what + " POSITION");
    if (points.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) c_.fail(what + ": POSITION must be float");
    if (points.count > std::size_t(INT_MAX) - std::size_t(points_.rows())) c_.fail(what + ": more points than ffdkit indexes");
    if (p.attributes.count("NORMAL") != 0) hasNormals_ = true;
    const long long base = points_.rows();
    for (std::size_t k = 0; k < points.count; ++k) {
      float xyz[3];
      std::memcpy(xyz, points.data + k * points.stride, sizeof xyz);
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
        c_.fail(what + ": " + Where{"vertex", (long long)k}.text() + ": non-finite coordinate");
      const Eigen::Vector3d q = world * Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
      if (!q.allFinite()) c_.fail(what + ": " + Where{"vertex", (long long)k}.text() + ": non-finite after the node transform");
      points_.add(q.x(), q.y(), q.z());
    }
    // Indices: an accessor of unsigned integers, or 0..count-1.
    AccessorView indices;
    std::size_t n = points.count;
    if (p.indices >= 0) {
      indices = view(c_, p.indices, TINYGLTF_TYPE_SCALAR, 1, what + " indices");
      if (indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        c_.fail(what + ": indices must be unsigned integers");
      n = indices.count;
    }
    auto at = [&](std::size_t k) -> int {
      const long long i = p.indices >= 0 ? indexAt(indices, k) : (long long)k;
      if (i < 0 || std::size_t(i) >= points.count)
        c_.fail(what + ": index " + std::to_string(k) + " is " + std::to_string(i) + ", outside 0.." + std::to_string(points.count - 1));
      return int(base + i);
    };
    switch (p.mode) {
      case TINYGLTF_MODE_TRIANGLES:
        if (n % 3 != 0) c_.fail(what + ": " + std::to_string(n) + " triangle indices is not a multiple of 3");
        for (std::size_t k = 0; k + 2 < n; k += 3) triangles_.add(at(k), at(k + 1), at(k + 2));
        break;
      case TINYGLTF_MODE_TRIANGLE_STRIP:
        for (std::size_t k = 0; k + 2 < n; ++k) {
          if (k % 2 == 0) triangles_.add(at(k), at(k + 1), at(k + 2));
          else triangles_.add(at(k + 1), at(k), at(k + 2));
        }
        break;
      case TINYGLTF_MODE_TRIANGLE_FAN:
        for (std::size_t k = 1; k + 1 < n; ++k) triangles_.add(at(0), at(k), at(k + 1));
        break;
      case TINYGLTF_MODE_LINE:
        for (std::size_t k = 0; k + 1 < n; k += 2) segments_.add(at(k), at(k + 1));
        break;
      case TINYGLTF_MODE_LINE_STRIP:
      case TINYGLTF_MODE_LINE_LOOP:
        for (std::size_t k = 0; k + 1 < n; ++k) segments_.add(at(k), at(k + 1));
        if (p.mode == TINYGLTF_MODE_LINE_LOOP && n > 2) segments_.add(at(n - 1), at(0));
        break;
      case TINYGLTF_MODE_POINTS:
        for (std::size_t k = 0; k < n; ++k) (void)at(k);
        break;
      default: c_.fail(what + ": unknown primitive mode " + std::to_string(p.mode));
    }
  }

  static bool hasWeights(const std::vector<double>& weights) {
    return std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0.0; });
  }
  static bool morphs(const tinygltf::Mesh& m) {
    return std::any_of(m.primitives.begin(), m.primitives.end(), [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
  }

  const Context& c_;
  bool counting_ = false;
  std::vector<std::uint64_t> instances_;  // per mesh: the nodes that instance it
  std::set<int> visited_;
  PointSink points_;
  TriangleSink triangles_;
  SegmentSink segments_;
  bool hasNormals_ = false;
};

// Images are not needed: accept them undecoded.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// Every external file a glTF names (buffers, images) through the one confinement rule, charged
// to the read's budget before it is read. A refusal is kept here and thrown after tinygltf
// returns (no exception crosses tinygltf), and never quotes the refused file's bytes.
struct ExternalFiles {
  std::optional<fs::path> root;  ///< the glTF file's folder, absolute; none for a stream
  PathConfinement confinement;
  ReadBudget& budget;
  std::optional<std::string> refusal;

  // The URI as the file names it, from the path tinygltf joined to `root` ("<root>/<uri>").
  std::string named(const std::string& joined) const {
    const std::string prefix = root ? root->string() + "/" : std::string();
    return root && joined.starts_with(prefix) ? joined.substr(prefix.size()) : joined;
  }

  // The path tinygltf joined, checked; nullopt after a refusal.
  std::optional<fs::path> allowed(const std::string& joined) {
    if (!root) {
      refuse("external file '" + joined + "': a glTF read from a stream or from memory cannot name other files");
      return std::nullopt;
    }
    try {
      return confinedPath(*root, named(joined), "external file", confinement);
    } catch (const PathOutsideFolderError& e) {
      refuse(e.what());
      return std::nullopt;
    }
  }
  void refuse(std::string message) {
    if (!refusal) refusal = std::move(message);
  }
};

bool fileExists(const std::string& path, void* files) {
  const auto full = static_cast<ExternalFiles*>(files)->allowed(path);
  std::error_code ec;
  return full && fs::is_regular_file(*full, ec);
}
std::string expandPath(const std::string& path, void*) { return path; }
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* context) {
  auto& files = *static_cast<ExternalFiles*>(context);
  const auto full = files.allowed(path);
  if (!full) {
    *err += "external file refused\n";
    return false;
  }
  std::error_code ec;
  const auto size = fs::file_size(*full, ec);
  if (ec) {
    *err += "cannot read external file '" + files.named(path) + "'\n";
    return false;
  }
  try {
    files.budget.chargeBytes(size, 1, "external file '" + files.named(path) + "'");
  } catch (const ReadLimitError& e) {
    files.refuse(e.what());
    *err += "external file refused\n";
    return false;
  }
  std::FILE* f = std::fopen(full->c_str(), "rb");
  if (f == nullptr) {
    *err += "cannot open external file '" + files.named(path) + "'\n";
    return false;
  }
  out->resize(std::size_t(size));
  const bool ok = std::fread(out->data(), 1, out->size(), f) == out->size();
  std::fclose(f);
  if (!ok) *err += "cannot read external file '" + files.named(path) + "'\n";
  return ok;
}
bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err += "writing is not allowed\n";
  return false;
}

std::uint32_t littleEndian32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
  return v;
}

// The GLB container (glTF 2.0, sec. "Binary glTF Layout"): a 12-byte header (magic, version,
// length) and chunks of an 8-byte header (length, type) and their data. Every declared length is
// checked against the bytes there before tinygltf reads them: its loader copies a BIN chunk by
// its declared length without that check (a heap over-read, found by fuzz_mesh_glb).
void checkGlbLayout(std::string_view bytes, const std::string& source) {
  const auto bad = [&](const std::string& what) { throw MeshIoError(source + ": GLB " + what); };
  if (bytes.size() < 20) bad("of " + std::to_string(bytes.size()) + " bytes is shorter than its header and first chunk header (20 bytes)");
  const std::uint64_t length = littleEndian32(bytes, 8);
  if (length > bytes.size())
    bad("header declares " + std::to_string(length) + " bytes (byte 8), the file has " + std::to_string(bytes.size()));
  for (std::uint64_t at = 12, chunk = 0; at < length; ++chunk) {
    if (length - at < 8)
      bad("chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) + ": " + std::to_string(length - at) +
          " bytes left, fewer than a chunk header (8)");
    const std::uint64_t size = littleEndian32(bytes, static_cast<std::size_t>(at));
    if (size > length - at - 8)
      bad("chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) + " declares " + std::to_string(size) +
          " bytes, " + std::to_string(length - at - 8) + " are left");
    at += 8 + size;
  }
}

std::string firstLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const std::size_t newline = text.find('\n');
  return newline == std::string::npos ? text : text.substr(0, newline);
}

}  // namespace

MeshData readGltf(std::string_view bytes, bool binary, const std::string& source, const std::optional<fs::path>& folder,
                  const PathConfinement& confinement, ReadBudget& budget) {
  if (bytes.size() > UINT_MAX) throw MeshIoError(source + ": glTF files over 4 GB are not supported");
  ExternalFiles files{std::nullopt, confinement, budget, std::nullopt};
  if (folder) {
    std::error_code ec;
    files.root = fs::weakly_canonical(fs::absolute(folder->empty() ? fs::path(".") : *folder, ec), ec);
    if (ec) files.root.reset();
  }
  if (binary) checkGlbLayout(bytes, source);
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  loader.SetFsCallbacks({fileExists, expandPath, readWholeFile, refuseWrite, &files});
  tinygltf::Model model;
  std::string error, warning;
  const std::string base = files.root ? files.root->string() : std::string();
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       unsigned(bytes.size()), base)
                         : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), unsigned(bytes.size()), base);
  if (files.refusal) throw MeshIoError(source + ": " + *files.refusal);
  if (!ok) throw MeshIoError(source + ": cannot read glTF (" + firstLine(error.empty() ? warning : error) + ")");

  const Context context{model, source};
  if (!model.extensionsRequired.empty())
    context.fail("requires the extension '" + model.extensionsRequired.front() + "', which ffdkit does not read");
  Merger merger(context);
  const auto walk = [&] {
    if (!model.scenes.empty()) {
      const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
      if (std::size_t(scene) >= model.scenes.size()) context.fail("default scene " + std::to_string(scene) + " does not exist");
      for (int node : model.scenes[std::size_t(scene)].nodes) merger.node(node, Eigen::Affine3d::Identity(), 0);
    } else {
      // No scene: every mesh, untransformed (the glTF spec leaves such files to the application).
      for (std::size_t m = 0; m < model.meshes.size(); ++m) merger.mesh(int(m), Eigen::Affine3d::Identity());
    }
  };
  merger.plan(walk, budget);
  walk();
  return merger.take();
}

}  // namespace ffdkit::meshio::detail
