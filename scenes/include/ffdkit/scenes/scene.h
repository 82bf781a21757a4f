#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Geometry>

#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/keyframes.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/object_id.h"
#include "ffdkit/scenes/primitive.h"
#include "ffdkit/scenes/up_axis.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::scenes {

/// An object read from a mesh or point file (Kuriyama 1996, sec. 6.4).
struct MeshFileSource {
  std::string path;  ///< as written in the scene file: relative to the scene file's folder, or absolute
  /// The file's up axis: a Y-up file's points are turned to Z-up as they are read (up_axis.h).
  UpAxis up = UpAxis::Z;
};

/// An object made by a named generator (curves and surfaces of the geometry topics); it keeps
/// its parameters so that it can be regenerated at another sampling density.
struct GeneratedSource {
  std::string generator;  ///< a name in the generator registry, e.g. "qi-interpolate"
  GeneratorParameters parameters;  ///< the generator's parameters, by name
  double density = 1.0;   ///< sampling relative to the generator's default, (0, 64]
};

/// Where an object's own (undeformed) points come from.
using ObjectSource = std::variant<PrimitiveOptions, MeshFileSource, GeneratedSource>;

/// How a surface is drawn: shaded in its colour, or with zebra (reflection-line) stripes that
/// show the smoothness of the deformed surface (Kuriyama 1996, sec. 5.1).
enum class SurfaceStyle { Shaded, Zebra };

/// How a curve is drawn: a shaded tube around the polyline, or the polyline itself as unlit
/// lines in the object's colour (lighter on a dense scene, and the exact points of the curve).
enum class CurveStyle { Tube, Line };

/// How an object looks in the 3D view.
struct DisplaySettings {
  Eigen::Vector3d color{0.85, 0.55, 0.30};  ///< RGB in [0, 1]
  double opacity = 1.0;                     ///< in [0, 1]
  bool visible = true;  ///< drawn in the view
  /// Surfaces only (objects with triangles); curves and point clouds ignore it.
  SurfaceStyle surfaceStyle = SurfaceStyle::Shaded;
  /// Zebra: dark/light stripe pairs over the angle 0..pi between the vertex normal and
  /// zebraDirection, an integer in [1, 256].
  int zebraStripes = 8;
  /// Zebra: the "light tube" direction in world coordinates (any non-zero length).
  Eigen::Vector3d zebraDirection{0.0, 0.0, 1.0};
  /// Curves only (objects with segments): draws a curvature comb of the deformed polyline.
  bool curvatureComb = false;
  /// Comb tooth length proportional to curvature, such that the longest tooth of the undeformed
  /// curve is combScale times the diagonal of its bounding box (a straight undeformed curve:
  /// length = combScale * curvature * diagonal^2); positive.
  double combScale = 0.15;
  /// Curves only (objects with segments); surfaces and point clouds ignore it. Tube: a shaded
  /// tube of radius 0.6 % of the deformed curve's bounding-box diagonal. Line: the polyline,
  /// unlit, in `color`, 2 pixels wide. The curvature comb is drawn the same for both.
  CurveStyle curveStyle = CurveStyle::Tube;

  friend bool operator==(const DisplaySettings&, const DisplaySettings&) = default;  ///< equal when every field is
};

/// A deformable object: its source, its own points (built from the source on load), its look.
struct SceneObject {
  /// Given by the scene when the object is added (Scene::insertObject), kept through renames and
  /// undo; what attachments, the deformer, the view and the outliner hold.
  ObjectId id;
  std::string name;  ///< unique within the scene; a label (a rename changes nothing else)
  ObjectSource source;  ///< where its own points come from
  DisplaySettings display;  ///< how it is drawn
  MeshData mesh;     ///< the object's own points; the widget trees deform copies of them
  /// Scene revisions (scene_changes.h) of the last change of `mesh` / `display`; stamped by the
  /// scene edit functions, read by the deformer and the view instead of comparing the data.
  std::uint64_t meshRevision = 0;
  std::uint64_t displayRevision = 0;  ///< see meshRevision
};

/// A root lattice widget (with its whole subtree of child lattices) deforming some objects:
/// for each object the lattices run in pre-order (Kuriyama 1996, secs. 6.2.3, 6.3.2). The lattice is held
/// by its id and the objects by theirs, which renames keep (the scene file writes their names,
/// scene-file-format.md).
struct Attachment {
  widgets::WidgetId lattice;      ///< a ROOT lattice widget of the scene's model
  std::vector<ObjectId> objects;  ///< the objects it deforms
  friend bool operator==(const Attachment&, const Attachment&) = default;  ///< equal when lattice and objects are
};

/// The view's camera, in world coordinates.
struct Camera {
  Eigen::Vector3d position{2.4, -3.0, 2.0};  ///< eye position
  Eigen::Vector3d focalPoint{0.0, 0.0, 0.0};  ///< the point looked at
  Eigen::Vector3d viewUp{0.0, 0.0, 1.0};  ///< up direction of the view
  double viewAngleDegrees = 30.0;  ///< vertical view angle
};

/// A document: objects, the widget model whose lattices deform them, attachments, a camera, an
/// animation.
///
/// Every edit of the parts outside the widget model goes through a member below that stamps what
/// it changed with a new `revision()` (scene_changes.h turns the stamps into a change set); the
/// widget model stamps its own edits (WidgetModel::changesSince). Read-only access is through
/// the const accessors.
class Scene {
 public:
  std::string description;  ///< a line or two about the scene, shown by `ffdkit-cli info`
  /// Public: the model reports its own edits (revision(), changesSince); assigning another model
  /// is another instance, which consumers take anew.
  widgets::WidgetModel widgets;
  /// When set, the widget model lives in this widget file (relative to the scene's folder)
  /// and the scene file references it instead of holding the widgets inline.
  std::optional<std::string> widgetFile;

  // ---- revisions of the parts outside the widget model (which keeps its own) -----------------
  /// Grows by one with every edit below; each stamps what it changed with the new value.
  std::uint64_t revision() const { return revision_; }
  std::uint64_t structureRevision() const { return structureRevision_; }  ///< objects added / removed / renamed, attachments
  std::uint64_t cameraRevision() const { return cameraRevision_; }        ///< camera, background
  std::uint64_t animationRevision() const { return animationRevision_; }  ///< keys, frame rate, frame range

  // ---- objects -------------------------------------------------------------------------------
  /// In the order they were added (the scene file's order).
  const std::vector<SceneObject>& objects() const { return objects_; }
  /// The object with this name, or nullptr.
  const SceneObject* findObject(const std::string& name) const;
  /// The object with this id, or nullptr.
  const SceneObject* findObject(ObjectId id) const;
  /// The id of the object with this name. @throws std::invalid_argument for an unknown name.
  ObjectId objectId(const std::string& name) const;
  /// The name of the object with this id. @throws std::invalid_argument for an unknown id.
  const std::string& objectName(ObjectId id) const;
  /// Adds an object at the end (stamps the structure and the object's mesh and look) and returns
  /// its id. @throws std::invalid_argument for an empty or duplicate name.
  ObjectId addObject(SceneObject object);
  /// The same at `position` (<= objects().size(); an undo puts an object back in its place). The
  /// object keeps its id when it has one no other object holds (an object taken out and put back
  /// is the same object to the attachments and the deformer); otherwise it gets a new one.
  ObjectId insertObject(std::size_t position, SceneObject object);
  /// Removes an object and its place in every attachment (an attachment left with no object goes).
  /// @throws std::invalid_argument for an unknown object.
  void removeObject(const std::string& name);
  /// The same, handing the object over with its id (an undoable removal keeps it).
  SceneObject takeObject(const std::string& objectName);
  /// The same by id. @throws std::invalid_argument for an unknown object.
  SceneObject takeObject(ObjectId id);
  /// Renames an object: its name only (attachments and everything else hold its id); stamps the
  /// structure so that the outliner and the panel show the new name.
  /// @throws std::invalid_argument for an unknown object, or an empty or used name.
  void renameObject(const std::string& fromName, const std::string& to);
  /// The same by id.
  void renameObject(ObjectId id, const std::string& to);
  /// Replaces an object's own points, and its source when given (which the points then come
  /// from). @throws std::invalid_argument for an unknown object.
  void setObjectMesh(const std::string& name, MeshData mesh, std::optional<ObjectSource> source = {});
  /// Hands an object's own points over, leaving its mesh without points (its faces and the rest
  /// stay): for a caller done with them (SceneDeformer::finishGestureTakingPoints).
  /// @throws std::invalid_argument for an unknown object.
  Eigen::MatrixX3d takeObjectPoints(const std::string& name);
  /// Changes how an object looks (no geometry changes). @throws for an unknown object.
  void setObjectDisplay(const std::string& name, const DisplaySettings& display);

  // ---- attachments -------------------------------------------------------------------------
  /// Which root lattices deform which objects.
  const std::vector<Attachment>& attachments() const { return attachments_; }
  /// Replaces every attachment (a file read, an undo step); stamps the structure when they differ.
  void setAttachments(std::vector<Attachment> attachments);
  /// `lattice` deforms `object` too: appended to the lattice's attachment, or a new attachment at
  /// the end. Stamps the structure unless it already did. Checks nothing (validateScene does).
  void attach(widgets::WidgetId lattice, ObjectId object);
  /// attach() of the object with this name. @throws std::invalid_argument for an unknown name.
  void attach(widgets::WidgetId lattice, const std::string& object);
  /// `lattice` stops deforming `object` (an attachment left with no object goes).
  /// @throws std::invalid_argument if it was not attached.
  void detach(widgets::WidgetId lattice, ObjectId object);
  /// detach() of the object with this name. @throws std::invalid_argument for an unknown name.
  void detach(widgets::WidgetId lattice, const std::string& object);
  /// Drops the attachments whose lattice the widget model no longer has (after a removal).
  void dropStaleAttachments();
  /// Root lattices deforming `object`, in attachment order.
  std::vector<widgets::WidgetId> latticesDeforming(ObjectId object) const;
  /// The same for the object with this name (none for an unknown name).
  std::vector<widgets::WidgetId> latticesDeforming(const std::string& object) const;
  /// Every lattice deforming `object` in the order its pipeline runs them (Kuriyama 1996, sec. 6.2.3): each attached
  /// root in attachment order followed by its subtree (WidgetModel::pipelineOrder(root)).
  std::vector<widgets::WidgetId> stagesDeforming(ObjectId object) const;
  /// The same for the object with this name (none for an unknown name).
  std::vector<widgets::WidgetId> stagesDeforming(const std::string& object) const;

  // ---- camera and background -----------------------------------------------------------------
  /// The view's camera.
  const Camera& camera() const { return camera_; }
  /// Sets the camera; stamps the camera as changed.
  void setCamera(const Camera& camera);
  /// RGB in [0, 1].
  const Eigen::Vector3d& background() const { return background_; }
  /// Sets the background colour (RGB in [0, 1]); stamps the camera as changed.
  void setBackground(const Eigen::Vector3d& background);

  // ---- animation (animation.h evaluates it; its setKey / removeKey edit the keys) ------------
  /// Frame rate, frame range and keyed channels.
  const Animation& animation() const { return animation_; }
  /// Replaces the whole animation (a file read). Checks nothing (validateAnimation does).
  void setAnimation(Animation animation);
  /// Frames per second. Checks nothing (validateAnimation does).
  void setFrameRate(double framesPerSecond);
  /// The first and last frame. Checks nothing (validateAnimation does).
  void setFrameRange(int first, int last);

 private:
  friend std::optional<Keyframe> setKey(Scene& scene, widgets::WidgetId widget, ChannelKind kind, Keyframe key);
  friend std::optional<Keyframe> removeKey(Scene& scene, widgets::WidgetId widget, ChannelKind kind, double seconds);

  /// The next revision, which the caller stamps on what it changed.
  std::uint64_t stamp() { return ++revision_; }
  SceneObject& object(const std::string& name);
  SceneObject& object(ObjectId id);

  std::vector<SceneObject> objects_;
  std::uint32_t nextObjectId_ = 0;  // the id the next new object gets
  std::vector<Attachment> attachments_;
  Animation animation_;
  Camera camera_;
  Eigen::Vector3d background_{0.13, 0.15, 0.18};
  std::uint64_t revision_ = 0;
  std::uint64_t structureRevision_ = 0;
  std::uint64_t cameraRevision_ = 0;
  std::uint64_t animationRevision_ = 0;
};

/// Builds an object's own points from its source. Mesh paths resolve against `baseDirectory`
/// and are not confined (the caller chose them); the build has the default ReadLimits.
/// @throws MeshIoError / GeneratorError / std::invalid_argument naming the object;
///   meshio::ReadLimitError over the limits.
MeshData buildObjectMesh(const ObjectSource& source, const std::filesystem::path& baseDirectory,
                         const GeneratorRegistry& generators = builtinGenerators());

/// How an object's points are built as part of a read (a scene file's objects).
struct ObjectMeshOptions {
  const GeneratorRegistry* generators = nullptr;  ///< nullptr: builtinGenerators()
  /// Charged before anything is built: a primitive's vertices and triangles from its resolution
  /// (primitiveSize), a mesh file's contents (meshio::MeshReadOptions), a generator's pointBound.
  /// nullptr: a budget of the default ReadLimits for this object alone.
  meshio::ReadBudget* budget = nullptr;
  /// The rule for a mesh file's path (relative to `baseDirectory`) and the files it names.
  meshio::PathConfinement confinement{};
};

/// buildObjectMesh against a budget and the confinement rule.
/// @throws MeshIoError / GeneratorError / std::invalid_argument naming what failed;
///   meshio::ReadLimitError naming the primitive over the budget; meshio::PathOutsideFolderError.
MeshData buildObjectMesh(const ObjectSource& source, const std::filesystem::path& baseDirectory,
                         const ObjectMeshOptions& options);

/// Options of attachNewLattice: the new lattice's name, counts, settings and margin.
struct AttachOptions {
  std::string latticeName;                           ///< "" -> "lattice<N>"
  Eigen::Vector3i counts = Eigen::Vector3i::Constant(3);  ///< control points per axis, each >= 2
  widgets::LatticeSettings settings;                 ///< bases, outside policy, re-embed policy
  /// Grown around the objects' bounding box on every side, relative to its diagonal.
  double padding = 0.05;
};

/// Attach (Kuriyama 1996, sec. 6.4): adds a root lattice whose frame maps the local unit box onto the
/// bounding box of the named objects (fittedLatticeFrame, lattice_fit.h: padded; a flat or
/// degenerate box gets the minimum thickness), and attaches it to them.
/// @return the new lattice. @throws std::invalid_argument for unknown objects or no points.
widgets::WidgetId attachNewLattice(Scene& scene, const std::vector<std::string>& objects,
                                   const AttachOptions& options = {});

/// Detach: the lattice stops deforming `object` (the object shows its own points again).
/// @throws std::invalid_argument if it was not attached.
void detachLattice(Scene& scene, widgets::WidgetId lattice, const std::string& object);

/// Checks names and references: unique object names and ids, attachments holding ids of existing
/// root lattices and of existing objects, each object deformed at most once by a given lattice.
/// @throws std::invalid_argument naming the first problem.
void validateScene(const Scene& scene);

}  // namespace ffdkit::scenes
