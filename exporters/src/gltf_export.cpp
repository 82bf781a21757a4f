#include "ffdkit/exporters/gltf_export.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "ffdkit/exporters/skin_binding.h"
#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "glb_builder.h"

namespace ffdkit::exporters {
namespace {

using detail::GlbBuilder;
using detail::RowMatrixXf;

std::string number(double value) {
  std::ostringstream text;
  text.precision(4);
  text << value;
  return text.str();
}

RowMatrixXf toFloat(const Eigen::MatrixX3d& m) { return m.cast<float>(); }

// Unit vertex normals of a triangle mesh; a vertex on no (or only degenerate) triangles gets +z,
// since glTF asks for unit normals.
Eigen::MatrixX3d unitNormals(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles) {
  Eigen::MatrixX3d n = meshio::vertexNormals(points, triangles);
  for (Eigen::Index v = 0; v < n.rows(); ++v)
    if (!(n.row(v).squaredNorm() > 0.5)) n.row(v) = Eigen::RowVector3d(0.0, 0.0, 1.0);
  return n;
}

// The largest distance between rows and the row where it is.
std::pair<double, Eigen::Index> maxDistance(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  double best = 0.0;
  Eigen::Index at = -1;
  for (Eigen::Index v = 0; v < a.rows(); ++v) {
    const double d = (a.row(v) - b.row(v)).norm();
    if (!(d <= best)) {  // NaN counts as the worst
      best = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
      at = v;
    }
  }
  return {best, at};
}

// The meshes to write: the objects that have points.
std::vector<const scenes::SceneObject*> exportedObjects(const scenes::Scene& scene) {
  std::vector<const scenes::SceneObject*> objects;
  for (const auto& object : scene.objects())
    if (object.mesh.points.rows() > 0) objects.push_back(&object);
  if (objects.empty()) throw GltfExportError("glTF export: the scene has no object with points");
  return objects;
}

// One primitive per kind of element of the object, sharing its vertex attributes.
tinygltf::Mesh meshOf(GlbBuilder& glb, const scenes::SceneObject& object, const std::map<std::string, int>& attributes) {
  tinygltf::Mesh mesh;
  mesh.name = object.name;
  auto add = [&](int mode, int indices) {
    tinygltf::Primitive primitive;
    primitive.attributes = attributes;
    primitive.mode = mode;
    primitive.indices = indices;
    mesh.primitives.push_back(std::move(primitive));
  };
  if (object.mesh.triangles.rows() > 0) add(TINYGLTF_MODE_TRIANGLES, glb.indexAccessor(object.mesh.triangles));
  if (object.mesh.segments.rows() > 0) add(TINYGLTF_MODE_LINE, glb.indexAccessor(object.mesh.segments));
  if (mesh.primitives.empty()) add(TINYGLTF_MODE_POINTS, -1);
  return mesh;
}

// Evaluates a working copy of the scene at any time: ffdkit's exact deformation. Each time starts
// from the exported scene's own widget state, so the state at t does not depend on the times
// sampled before (an animation applied through gestures may: non-commuting motions).
class Evaluator {
 public:
  Evaluator(const scenes::Scene& scene, const AnimationSource& animation)
      : original_(scene), work_(scene), animation_(animation) {}
  void at(double t) {
    if (animation_.setTime) {
      work_.widgets = original_.widgets;  // the deformer syncs another model instance by value
      animation_.setTime(work_, t);
    }
    deformer_.evaluate(work_);
  }
  const Eigen::MatrixX3d& points(const std::string& object) const { return deformer_.points(object); }
  scenes::Scene& scene() { return work_; }

 private:
  const scenes::Scene& original_;
  scenes::Scene work_;
  const AnimationSource& animation_;
  scenes::SceneDeformer deformer_;
};

void checkAnimation(const AnimationSource& animation, const char* content) {
  const std::string what = std::string("glTF ") + content + " export";
  if (!animation.setTime) throw GltfExportError(what + ": the scene has no animation (no keys)");
  if (animation.keyTimes.empty()) throw GltfExportError(what + ": the animation has no keys");
  for (std::size_t i = 0; i < animation.keyTimes.size(); ++i) {
    if (!std::isfinite(animation.keyTimes[i]))
      throw GltfExportError(what + ": key " + std::to_string(i) + " has a non-finite time");
    if (i > 0 && !(animation.keyTimes[i] > animation.keyTimes[i - 1]))
      throw GltfExportError(what + ": key times must increase, key " + std::to_string(i) + " is at " +
                            number(animation.keyTimes[i]) + " after " + number(animation.keyTimes[i - 1]));
  }
  if (!animation.interpolation.empty() && animation.interpolation.size() != animation.keyTimes.size())
    throw GltfExportError(what + ": " + std::to_string(animation.keyTimes.size()) + " keys but " +
                          std::to_string(animation.interpolation.size()) + " interpolations");
  if (!(animation.frameRate > 0.0) || !std::isfinite(animation.frameRate))
    throw GltfExportError(what + ": frame rate must be > 0, got " + number(animation.frameRate));
}

KeyInterpolation interpolationOf(const AnimationSource& animation, std::size_t key) {
  return animation.interpolation.empty() ? KeyInterpolation::Linear : animation.interpolation[key];
}

bool allConstant(const AnimationSource& animation) {
  for (std::size_t i = 0; i + 1 < animation.keyTimes.size(); ++i)
    if (interpolationOf(animation, i) != KeyInterpolation::Constant) return false;
  return true;
}

// A LINEAR sampler holds a Constant key's state up to just before the next key: a sample at
// t1 - hold, hold small against the interval and above float32 resolution of the times.
double holdBefore(double t0, double t1) {
  const double resolution = 64.0 * std::numeric_limits<float>::epsilon() * std::max(1.0, std::abs(t1));
  return std::max(std::min(1e-4, (t1 - t0) / 1000.0), resolution);
}

// Sample times: the keys, the frames between them (when `frames`), and for a LINEAR sampler the
// holds of Constant keys; sorted, distinct as float32.
std::vector<double> sampleTimes(const AnimationSource& animation, bool frames, bool step) {
  // Morph (no frames): only Constant segments hold; a skin also holds where a part jumps.
  const auto holds = [&](std::size_t i) {
    return interpolationOf(animation, i) == KeyInterpolation::Constant ||
           (frames && i < animation.jumps.size() && animation.jumps[i]);
  };
  std::set<double> times(animation.keyTimes.begin(), animation.keyTimes.end());
  const double first = animation.keyTimes.front();
  const double last = animation.keyTimes.back();
  if (frames && !step) {
    const auto count = static_cast<long long>(std::floor((last - first) * animation.frameRate + 1e-9));
    for (long long f = 1; f <= count; ++f) times.insert(first + static_cast<double>(f) / animation.frameRate);
  }
  if (!step) {
    for (std::size_t i = 0; i + 1 < animation.keyTimes.size(); ++i) {
      if (!holds(i)) continue;
      const double t0 = animation.keyTimes[i];
      const double t1 = animation.keyTimes[i + 1];
      const double hold = t1 - holdBefore(t0, t1);
      times.erase(times.lower_bound(hold), times.lower_bound(t1));  // frames inside the hold
      times.insert(hold);
    }
  }
  std::vector<double> sorted;
  for (double t : times) {
    if (t > last) break;
    if (!sorted.empty() && !(static_cast<float>(t) > static_cast<float>(sorted.back()))) continue;
    sorted.push_back(t);
  }
  return sorted;
}

int timeAccessor(GlbBuilder& glb, const std::vector<double>& times) {
  RowMatrixXf input(static_cast<Eigen::Index>(times.size()), 1);
  for (std::size_t i = 0; i < times.size(); ++i) input(Eigen::Index(i), 0) = static_cast<float>(times[i]);
  return glb.floatAccessor(input, TINYGLTF_TYPE_SCALAR, /*bounds=*/true);
}

struct Written {
  GltfExportReport report;
  GlbBuilder glb;
};

void finishScene(GlbBuilder& glb, const std::vector<int>& roots) {
  tinygltf::Scene scene;
  scene.nodes = roots;
  glb.model().scenes.push_back(scene);
  glb.model().defaultScene = 0;
}

double sceneSize(const std::vector<const scenes::SceneObject*>& objects) {
  Eigen::AlignedBox3d box;
  for (const auto* object : objects)
    for (Eigen::Index v = 0; v < object->mesh.points.rows(); ++v) box.extend(object->mesh.points.row(v).transpose());
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

// ---- frame ----------------------------------------------------------------------------------

void writeFrame(const scenes::Scene& scene, const AnimationSource& animation, const GltfExportOptions& options,
                Written& out) {
  if (!std::isfinite(options.time)) throw GltfExportError("glTF frame export: the time is not finite");
  const auto objects = exportedObjects(scene);
  Evaluator evaluator(scene, animation);
  evaluator.at(options.time);
  GltfSampleError sample;
  sample.time = options.time;
  std::vector<int> roots;
  for (const auto* object : objects) {
    const Eigen::MatrixX3d& points = evaluator.points(object->name);
    const RowMatrixXf positions = toFloat(points);
    const auto [error, vertex] = maxDistance(positions.cast<double>(), points);
    if (error > sample.error4 || sample.vertex < 0) sample = {options.time, error, error, 0.0, object->name, vertex};
    std::map<std::string, int> attributes{
        {"POSITION", out.glb.floatAccessor(positions, TINYGLTF_TYPE_VEC3, true, TINYGLTF_TARGET_ARRAY_BUFFER)}};
    if (options.normals && object->mesh.triangles.rows() > 0)
      attributes["NORMAL"] = out.glb.floatAccessor(toFloat(unitNormals(points, object->mesh.triangles)),
                                                   TINYGLTF_TYPE_VEC3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    out.glb.model().meshes.push_back(meshOf(out.glb, *object, attributes));
    tinygltf::Node node;
    node.name = object->name;
    node.mesh = static_cast<int>(out.glb.model().meshes.size()) - 1;
    roots.push_back(out.glb.addNode(node));
  }
  finishScene(out.glb, roots);
  out.report.samples.push_back(sample);
  out.report.maxError = sample.error4;
}

// ---- morph targets --------------------------------------------------------------------------

void writeMorph(const scenes::Scene& scene, const AnimationSource& animation, const GltfExportOptions& options,
                Written& out) {
  checkAnimation(animation, "morph");
  const auto objects = exportedObjects(scene);
  const std::size_t keys = animation.keyTimes.size();
  Evaluator evaluator(scene, animation);
  // Per key, per object: the deformed points and, for surfaces, their normals.
  std::vector<std::vector<Eigen::MatrixX3d>> posed(keys);
  for (std::size_t key = 0; key < keys; ++key) {
    evaluator.at(animation.keyTimes[key]);
    for (const auto* object : objects) posed[key].push_back(evaluator.points(object->name));
  }
  out.report.morphTargets = static_cast<int>(keys);
  for (std::size_t key = 0; key < keys; ++key) out.report.samples.push_back({animation.keyTimes[key], 0, 0, 0, "", -1});

  std::vector<int> roots;
  std::vector<int> morphNodes;
  for (std::size_t o = 0; o < objects.size(); ++o) {
    const scenes::SceneObject& object = *objects[o];
    const Eigen::MatrixX3d& rest = object.mesh.points;
    const RowMatrixXf base = toFloat(rest);
    const Eigen::MatrixX3d baseValues = base.cast<double>();
    const bool normals = options.normals && object.mesh.triangles.rows() > 0;
    Eigen::MatrixX3d baseNormals;
    std::map<std::string, int> attributes{
        {"POSITION", out.glb.floatAccessor(base, TINYGLTF_TYPE_VEC3, true, TINYGLTF_TARGET_ARRAY_BUFFER)}};
    if (normals) {
      baseNormals = toFloat(unitNormals(rest, object.mesh.triangles)).cast<double>();
      attributes["NORMAL"] = out.glb.floatAccessor(baseNormals.cast<float>(), TINYGLTF_TYPE_VEC3, false,
                                                   TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    tinygltf::Mesh mesh = meshOf(out.glb, object, attributes);
    std::vector<std::map<std::string, int>> targets;
    for (std::size_t key = 0; key < keys; ++key) {
      const Eigen::MatrixX3d& points = posed[key][o];
      // The delta from the float32 base, so that base + delta is the nearest float sum.
      const RowMatrixXf delta = toFloat(points - baseValues);
      const auto [error, vertex] = maxDistance((baseValues + delta.cast<double>().eval()).cast<float>().cast<double>(), points);
      GltfSampleError& sample = out.report.samples[key];
      if (error > sample.error4 || sample.vertex < 0) sample = {animation.keyTimes[key], error, error, 0.0, object.name, vertex};
      std::map<std::string, int> target{
          {"POSITION", out.glb.floatAccessor(delta, TINYGLTF_TYPE_VEC3, true, TINYGLTF_TARGET_ARRAY_BUFFER)}};
      if (normals)
        target["NORMAL"] = out.glb.floatAccessor(toFloat(unitNormals(points, object.mesh.triangles) - baseNormals),
                                                 TINYGLTF_TYPE_VEC3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
      targets.push_back(std::move(target));
    }
    for (auto& primitive : mesh.primitives) primitive.targets = targets;
    mesh.weights.assign(keys, 0.0);
    out.glb.model().meshes.push_back(std::move(mesh));
    tinygltf::Node node;
    node.name = object.name;
    node.mesh = static_cast<int>(out.glb.model().meshes.size()) - 1;
    const int id = out.glb.addNode(node);
    roots.push_back(id);
    morphNodes.push_back(id);
  }
  for (const auto& sample : out.report.samples) out.report.maxError = std::max(out.report.maxError, sample.error4);

  // The weights: at a key's time its target alone (a LINEAR sampler blends neighbouring keys'
  // poses in between; a Constant key holds its pose up to the next one).
  const bool step = allConstant(animation);
  const std::vector<double> times = sampleTimes(animation, /*frames=*/false, step);
  RowMatrixXf weights = RowMatrixXf::Zero(static_cast<Eigen::Index>(times.size() * keys), 1);
  for (std::size_t s = 0; s < times.size(); ++s) {
    // The key whose pose this sample shows: the last key at or before it.
    const auto next = std::upper_bound(animation.keyTimes.begin(), animation.keyTimes.end(), times[s]);
    const std::size_t key = static_cast<std::size_t>(next - animation.keyTimes.begin()) - 1;
    weights(static_cast<Eigen::Index>(s * keys + key), 0) = 1.0f;
  }
  tinygltf::Animation anim;
  anim.name = "keys";
  tinygltf::AnimationSampler sampler;
  sampler.input = timeAccessor(out.glb, times);
  sampler.output = out.glb.floatAccessor(weights, TINYGLTF_TYPE_SCALAR, false);
  sampler.interpolation = step ? "STEP" : "LINEAR";
  anim.samplers.push_back(sampler);
  for (int node : morphNodes) {
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = node;
    channel.target_path = "weights";
    anim.channels.push_back(channel);
  }
  out.glb.model().animations.push_back(anim);
  out.report.interpolation = sampler.interpolation;
  finishScene(out.glb, roots);
}

// ---- skin -----------------------------------------------------------------------------------

void writeSkin(const scenes::Scene& scene, const AnimationSource& animation, const GltfExportOptions& options,
               Written& out) {
  checkAnimation(animation, "skin");
  if (options.joints != 4 && options.joints != 8)
    throw GltfExportError("glTF skin export: joints per vertex must be 4 or 8, got " + std::to_string(options.joints));
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance))
    throw GltfExportError("glTF skin export: the tolerance must be a finite number >= 0, got " + number(options.tolerance));
  const auto objects = exportedObjects(scene);
  Evaluator evaluator(scene, animation);

  // Bind state: the first key's frames with every lattice at rest.
  const double bindTime = animation.keyTimes.front();
  animation.setTime(evaluator.scene(), bindTime);
  scenes::Scene bind = evaluator.scene();
  for (const widgets::WidgetId lattice : bind.widgets.pipelineOrder())
    bind.widgets.setControlPoints(lattice, bind.widgets.restPoints(lattice));
  const SkinBinding binding = bindSkin(bind, 8);
  if (binding.joints.size() > 65536)
    throw GltfExportError("glTF skin export: " + std::to_string(binding.joints.size()) +
                          " joints; glTF's 16-bit joint indices allow 65536");
  std::map<std::string, const ObjectSkin*> skins;
  for (const auto& skin : binding.objects) skins[skin.object] = &skin;
  std::map<std::string, PrunedSkin> pruned4, pruned8;
  std::map<std::string, Eigen::MatrixX3d> restValues;  // the float32 positions written
  for (const auto* object : objects) {
    restValues[object->name] = roundToFloat(object->mesh.points);
    if (!skins.count(object->name)) continue;
    pruned4[object->name] = pruneSkin(*skins[object->name], 4);
    pruned8[object->name] = pruneSkin(*skins[object->name], 8);
  }
  Eigen::MatrixX3d inverseBind(static_cast<Eigen::Index>(binding.joints.size()), 3);
  for (std::size_t j = 0; j < binding.joints.size(); ++j)
    inverseBind.row(Eigen::Index(j)) = -binding.joints[j].bindPosition.transpose();
  inverseBind = roundToFloat(inverseBind);

  // Sample, measure against ffdkit's exact deformation; keep the joint translations.
  const bool step = allConstant(animation);
  const std::vector<double> times = skinSampleTimes(animation);
  std::vector<Eigen::MatrixX3d> translations;
  std::vector<GltfSampleError> samples;
  struct Worst {
    std::string object;
    Eigen::Index vertex = -1;
  };
  std::vector<Worst> worst4, worst8;
  for (const double t : times) {
    evaluator.at(t);
    const Eigen::MatrixX3d nodes = roundToFloat(jointTranslations(binding, evaluator.scene()));
    translations.push_back(nodes);
    GltfSampleError sample;
    sample.time = t;
    Worst w4, w8;
    for (const auto* object : objects) {
      const Eigen::MatrixX3d& exact = evaluator.points(object->name);
      if (!skins.count(object->name)) {  // not deformed: written as is
        const auto [e, v] = maxDistance(restValues[object->name], exact);
        if (e > sample.error4) sample.error4 = e, w4 = {object->name, v};
        if (e > sample.error8) sample.error8 = e, w8 = {object->name, v};
        continue;
      }
      const auto [e4, v4] = maxDistance(skinnedPositions(restValues[object->name], pruned4[object->name], nodes, inverseBind), exact);
      const auto [e8, v8] = maxDistance(skinnedPositions(restValues[object->name], pruned8[object->name], nodes, inverseBind), exact);
      const auto [el, vl] = maxDistance(linearPositions(*skins[object->name], evaluator.scene()), exact);
      if (e4 > sample.error4 || w4.vertex < 0) sample.error4 = e4, w4 = {object->name, v4};
      if (e8 > sample.error8 || w8.vertex < 0) sample.error8 = e8, w8 = {object->name, v8};
      sample.linearError = std::max(sample.linearError, el);
    }
    samples.push_back(sample);
    worst4.push_back(w4);
    worst8.push_back(w8);
  }
  auto maxOf = [&samples](double GltfSampleError::*field) {
    std::size_t at = 0;
    for (std::size_t s = 0; s < samples.size(); ++s)
      if (samples[s].*field > samples[at].*field) at = s;
    return at;
  };
  const std::size_t at4 = maxOf(&GltfSampleError::error4);
  const std::size_t at8 = maxOf(&GltfSampleError::error8);
  const std::size_t atLinear = maxOf(&GltfSampleError::linearError);
  int k = options.joints;
  if (k == 4 && samples[at4].error4 > options.tolerance && options.raiseJoints) k = 8;
  const std::size_t at = k == 4 ? at4 : at8;
  const double error = k == 4 ? samples[at4].error4 : samples[at8].error8;
  if (error > options.tolerance) {
    const Worst& w = k == 4 ? worst4[at] : worst8[at];
    throw GltfExportError(
        "glTF skin export refused: the skin's position error " + number(error) + " exceeds the tolerance " +
        number(options.tolerance) + " (at t = " + number(samples[at].time) + ", object '" + w.object + "', vertex " +
        std::to_string(w.vertex) + "); largest errors over " + std::to_string(samples.size()) + " sampled times: " +
        number(samples[at4].error4) + " with 4 joints per vertex, " + number(samples[at8].error8) + " with 8, " +
        number(samples[atLinear].linearError) + " with every weight kept (at t = " + number(samples[atLinear].time) +
        ": what no k removes: child lattices re-embedded as their parent moves, moving lattice frames)." +
        " Raise --tolerance, use --joints 8, or export --morph");
  }
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const Worst& w = k == 4 ? worst4[s] : worst8[s];
    samples[s].object = w.object;
    samples[s].vertex = w.vertex;
  }
  out.report.samples = samples;
  out.report.maxError = error;
  out.report.k = k;
  out.report.joints = static_cast<int>(binding.joints.size());
  out.report.jointScale = binding.jointScale;
  out.report.interpolation = step ? "STEP" : "LINEAR";

  // Nodes: a root "lattices" holding the static joint and one node per lattice with its joints.
  GlbBuilder& glb = out.glb;
  tinygltf::Node rootNode;
  rootNode.name = "lattices";
  const int root = glb.addNode(rootNode);
  std::vector<int> jointNodes(binding.joints.size());
  {
    tinygltf::Node rest;
    rest.name = binding.joints[0].name;
    jointNodes[0] = glb.addNode(rest);
    glb.model().nodes[std::size_t(root)].children.push_back(jointNodes[0]);
  }
  for (const auto& [lattice, first] : binding.firstJoint) {
    tinygltf::Node group;
    group.name = bind.widgets.name(lattice);
    const int groupId = glb.addNode(group);
    glb.model().nodes[std::size_t(root)].children.push_back(groupId);
    const Eigen::Index count = bind.widgets.controlPoints(lattice).rows();
    for (Eigen::Index f = 0; f < count; ++f) {
      const std::size_t j = std::size_t(first + f);
      tinygltf::Node joint;
      joint.name = binding.joints[j].name;
      const Eigen::RowVector3d t0 = translations.front().row(Eigen::Index(j));
      joint.translation = {t0.x(), t0.y(), t0.z()};
      jointNodes[j] = glb.addNode(joint);
      glb.model().nodes[std::size_t(groupId)].children.push_back(jointNodes[j]);
    }
  }
  RowMatrixXf matrices = RowMatrixXf::Zero(static_cast<Eigen::Index>(binding.joints.size()), 16);
  for (Eigen::Index j = 0; j < matrices.rows(); ++j) {
    matrices(j, 0) = matrices(j, 5) = matrices(j, 10) = matrices(j, 15) = 1.0f;  // column-major 4x4
    for (int c = 0; c < 3; ++c) matrices(j, 12 + c) = static_cast<float>(inverseBind(j, c));
  }
  tinygltf::Skin skin;
  skin.name = "lattices";
  skin.inverseBindMatrices = glb.floatAccessor(matrices, TINYGLTF_TYPE_MAT4, false);
  skin.skeleton = root;
  skin.joints = jointNodes;
  glb.model().skins.push_back(skin);

  std::vector<int> roots{root};
  for (const auto* object : objects) {
    std::map<std::string, int> attributes{{"POSITION", glb.floatAccessor(restValues[object->name].cast<float>(),
                                                                       TINYGLTF_TYPE_VEC3, true,
                                                                       TINYGLTF_TARGET_ARRAY_BUFFER)}};
    if (options.normals && object->mesh.triangles.rows() > 0)
      attributes["NORMAL"] = glb.floatAccessor(toFloat(unitNormals(object->mesh.points, object->mesh.triangles)),
                                               TINYGLTF_TYPE_VEC3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    tinygltf::Node node;
    node.name = object->name;
    if (skins.count(object->name)) {
      const PrunedSkin& p = k == 4 ? pruned4[object->name] : pruned8[object->name];
      for (int set = 0; set < k / 4; ++set) {
        const Eigen::Matrix<std::uint16_t, Eigen::Dynamic, 4, Eigen::RowMajor> joints = p.joints.middleCols(4 * set, 4);
        const RowMatrixXf weights = p.weights.middleCols(4 * set, 4);
        attributes["JOINTS_" + std::to_string(set)] = glb.jointAccessor(joints);
        attributes["WEIGHTS_" + std::to_string(set)] =
            glb.floatAccessor(weights, TINYGLTF_TYPE_VEC4, false, TINYGLTF_TARGET_ARRAY_BUFFER);
      }
      node.skin = 0;
    }
    glb.model().meshes.push_back(meshOf(glb, *object, attributes));
    node.mesh = static_cast<int>(glb.model().meshes.size()) - 1;
    roots.push_back(glb.addNode(node));
  }

  // The animation: each moving joint's translation at the sampled times.
  tinygltf::Animation anim;
  anim.name = "lattices";
  const int input = timeAccessor(glb, times);
  for (std::size_t j = 1; j < binding.joints.size(); ++j) {
    RowMatrixXf values(static_cast<Eigen::Index>(times.size()), 3);
    bool moves = false;
    for (std::size_t s = 0; s < times.size(); ++s) {
      values.row(Eigen::Index(s)) = translations[s].row(Eigen::Index(j)).cast<float>();
      moves = moves || values.row(Eigen::Index(s)) != values.row(0);
    }
    if (!moves) continue;
    tinygltf::AnimationSampler sampler;
    sampler.input = input;
    sampler.output = glb.floatAccessor(values, TINYGLTF_TYPE_VEC3, false);
    sampler.interpolation = out.report.interpolation;
    anim.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = static_cast<int>(anim.samplers.size()) - 1;
    channel.target_node = jointNodes[j];
    channel.target_path = "translation";
    anim.channels.push_back(channel);
  }
  if (!anim.channels.empty()) glb.model().animations.push_back(anim);
  finishScene(glb, roots);
}

}  // namespace

std::string_view gltfContentName(GltfContent content) {
  switch (content) {
    case GltfContent::Frame: return "frame";
    case GltfContent::Morph: return "morph";
    case GltfContent::Skin: return "skin";
  }
  return "frame";
}

GltfExportReport exportGltf(const scenes::Scene& scene, const AnimationSource& animation, std::ostream& out,
                            const GltfExportOptions& options) {
  Written written;
  written.report.content = options.content;
  switch (options.content) {
    case GltfContent::Frame: writeFrame(scene, animation, options, written); break;
    case GltfContent::Morph: writeMorph(scene, animation, options, written); break;
    case GltfContent::Skin: writeSkin(scene, animation, options, written); break;
  }
  const auto objects = exportedObjects(scene);
  written.report.objects = static_cast<int>(objects.size());
  for (const auto* object : objects) {
    written.report.vertices += object->mesh.points.rows();
    written.report.triangles += object->mesh.triangles.rows();
  }
  written.report.sceneSize = sceneSize(objects);
  if (written.glb.model().buffers[0].data.size() > std::size_t(std::numeric_limits<std::uint32_t>::max()) - 4096)
    throw GltfExportError("glTF export: " + std::to_string(written.glb.model().buffers[0].data.size()) +
                          " bytes of data; a .glb holds less than 4 GiB");
  const auto start = out.tellp();
  written.glb.write(out);
  if (!out) throw std::runtime_error("glTF export: writing the stream failed");
  if (start >= 0) written.report.bytes = static_cast<std::uintmax_t>(out.tellp() - start);
  return written.report;
}

std::vector<double> skinSampleTimes(const AnimationSource& animation) {
  checkAnimation(animation, "skin");
  return sampleTimes(animation, /*frames=*/true, allConstant(animation));
}

GltfExportReport exportGltf(const scenes::Scene& scene, const AnimationSource& animation,
                            const std::filesystem::path& path, const GltfExportOptions& options) {
  std::ostringstream buffer(std::ios::binary);
  GltfExportReport report = exportGltf(scene, animation, buffer, options);
  const std::string bytes = std::move(buffer).str();
  meshio::writeFileAtomically(path, bytes, options.durable);
  report.bytes = bytes.size();
  return report;
}

}  // namespace ffdkit::exporters
