#pragma once

#include <compare>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd {

/// Typed handle of a lattice in a Pipeline.
struct LatticeId {
  int value = -1;  ///< index of the lattice in its Pipeline; -1: none.
  /// Ordered by value.
  auto operator<=>(const LatticeId&) const = default;
};

/// When lattices other than the one being edited are re-embedded after their input points or
/// their rest lattice moved (Kuriyama 1996, sec. 6.3.2). Between re-embeddings such a lattice
/// deforms its new input with its old (u,v,w) (Deformer::deformStale), which is exact while it is
/// at rest.
struct ReembedThrottle {
  /// The throttle's rule.
  enum class Kind {
    Immediate,  ///< re-embed on every update (exact, slowest)
    EveryN,     ///< re-embed on every n-th update that finds the lattice stale
    OnDemand    ///< re-embed only in reembedAll() (e.g. on gesture release)
  };
  Kind kind = Kind::Immediate;  ///< the rule.
  int n = 1;  ///< EveryN only, >= 1

  /// Re-embed on every update.
  static ReembedThrottle immediate() { return {Kind::Immediate, 1}; }
  /// Re-embed on every n-th update that finds the lattice stale (n >= 1).
  static ReembedThrottle everyN(int n) { return {Kind::EveryN, n}; }
  /// Re-embed only in reembedAll().
  static ReembedThrottle onDemand() { return {Kind::OnDemand, 1}; }
};

/// How Pipeline::update() evaluates a stage whose embedding is fresh when its control points moved.
enum class UpdateMode {
  /// Re-evaluates the points the moved control points influence from the stage's input
  /// (Deformer::update(lattice, input)): bit-identical to a full evaluation.
  Exact,
  /// Adds B_ijk(u,v,w) * dP_ijk per moved control point to the stage's previous output
  /// (Deformer::update(lattice)): one term per point and moved control point instead of the
  /// (p+1)^3 of a full evaluation, for the steps of a gesture. Agrees with Exact to ~1e-16
  /// relative per step; rounding accumulates slowly (~1e-12 after 10^4 steps). The next Exact
  /// run, or reembedAll(), evaluates such a stage in full again (the exact result, bit for bit).
  Delta
};

/// What one lattice did in the last update().
struct StageReport {
  LatticeId id;  ///< the lattice.
  bool reembedded = false;     ///< a new embedding was computed
  bool approximate = false;    ///< deformed with a stale embedding (throttled)
  bool outputChanged = false;  ///< its output points differ from the previous update
  bool delta = false;          ///< updated by deltas (UpdateMode::Delta): exact to rounding only
  double embedSeconds = 0.0;   ///< wall time spent in embed() (0 unless reembedded)
};

/// The FFD pipeline of one object (Kuriyama 1996, sec. 6.3.2, Fig. 6-7): a tree of lattices
/// evaluated in pre-order (parent before children, siblings by ascending priority, then by
/// insertion), the output points of one lattice being the input points of the next.
/// Owns its lattices (value semantics); edit them through lattice(id) or setLattice(id, ...).
class Pipeline {
 public:
  /// @param points #points x 3 WORLD object points (the input of the first lattice).
  /// @throws LatticeError on non-finite points.
  explicit Pipeline(const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options = {});
  /// The same, taking the points over instead of copying them (for a caller done with them: the
  /// CLI saves a copy of 24 bytes per point). @throws LatticeError on non-finite points.
  static Pipeline adopting(Eigen::MatrixX3d&& points, const EmbedOptions& options = {});

  /// Adds a lattice as a root (no parent) or as the last-by-priority child of `parent`.
  /// @throws LatticeError on an unknown parent.
  LatticeId addLattice(Lattice lattice, std::optional<LatticeId> parent = std::nullopt, int priority = 0);
  /// Removes a lattice and its whole subtree. @throws LatticeError on an unknown id.
  void removeLattice(LatticeId id);
  /// Sibling order: lower priority runs first. @throws LatticeError on an unknown id.
  void setPriority(LatticeId id, int priority);

  /// @throws LatticeError on an unknown id.
  Lattice& lattice(LatticeId id);
  /// The lattice `id` (read-only). @throws LatticeError on an unknown id.
  const Lattice& lattice(LatticeId id) const;
  /// Replaces lattice `id`. @throws LatticeError on an unknown id.
  void setLattice(LatticeId id, const Lattice& lattice) { this->lattice(id) = lattice; }
  /// The parent lattice of `id` (none for a root). @throws LatticeError on an unknown id.
  std::optional<LatticeId> parent(LatticeId id) const;

  /// The lattices in evaluation (pre-)order.
  std::vector<LatticeId> order() const;

  /// Replaces the object points (same or different count): every lattice re-embeds on the next update.
  void setPoints(const Eigen::Ref<const Eigen::MatrixX3d>& points);

  /// The lattice being edited is always re-embedded immediately; the others follow the throttle.
  void setActiveLattice(std::optional<LatticeId> id) { active_ = id; }
  /// Sets when lattices other than the active one re-embed (default Immediate).
  void setThrottle(const ReembedThrottle& throttle);
  /// The re-embedding throttle.
  const ReembedThrottle& throttle() const { return throttle_; }
  /// How the following update() calls evaluate fresh stages (default Exact); reembedAll() is
  /// always exact.
  void setUpdateMode(UpdateMode mode) { mode_ = mode; }
  /// How update() evaluates fresh stages.
  UpdateMode updateMode() const { return mode_; }
  /// The arithmetic of every stage's deformation (Deformer::setPrecision; default Double). A
  /// change makes the next run evaluate every embedded stage in full.
  void setPrecision(Precision precision);
  /// The arithmetic of the stages' deformation.
  Precision precision() const { return precision_; }

  /// Runs the pipeline: stages whose embedding is fresh and whose input did not change are updated
  /// incrementally; stale stages are re-embedded or deformed approximately per the throttle.
  /// @param progress optional hook over the whole run: `total` = pointsToEmbed() (the points of
  ///   every stage this run re-embeds), `done` counts them across the stages in order, monotone.
  ///   Called on this thread with (0, total) first, during each embedding (every
  ///   kEmbedProgressChunk points) and with (total, total) once the run is complete; the
  ///   EmbedOptions::progress given to the constructor is not used.
  /// @return #points x 3 deformed WORLD points.
  /// @throws Cancelled when `progress` returns false. The pipeline stays consistent and usable:
  ///   stages finished before the cancel keep their new embeddings and outputs, the cancelled
  ///   stage and the ones after it keep their previous embedding and output untouched (the
  ///   cancelled one is re-embedded by the next run), points() still returns the output of the
  ///   last completed run, and running the same call again gives bit for bit what a
  ///   never-cancelled call would have (stages deformed approximately before the cancel keep that
  ///   output and count once for the throttle). The last embedding also reports (total, total):
  ///   false there cancels it; false at the run's own closing call throws with all work kept.
  const Eigen::MatrixX3d& update(const EmbedProgress& progress = {});
  /// Re-embeds every stale lattice, then updates: the exact result (call on gesture release).
  /// Progress and cancel as update().
  const Eigen::MatrixX3d& reembedAll(const EmbedProgress& progress = {});
  /// How many points the next update() (`reembedAll` false) or reembedAll() (true) will embed: the
  /// input size times the number of stages it will re-embed (0 when it only deforms). The
  /// `total` of their progress; for a caller summing work over several pipelines.
  Eigen::Index pointsToEmbed(bool reembedAll = false) const;

  /// True when the next update() would change no output but the last stage's, and that one by
  /// deltas or not at all: the update mode is Delta, every stage's embedding is fresh for its
  /// input, every stage but the last is current for its lattice (Deformer::isCurrentFor), the
  /// last one is polynomial with the weights it last ran with (only control points may have
  /// moved) and its output is points(). A caller that follows such
  /// a motion itself (SceneDeformer, for a view that draws it without reading the points) may
  /// leave the run for later: a later update() adds the deltas of every move since the last run at
  /// once (Deformer::update(lattice) compares against the control points it last ran with).
  bool onlyLastStageMovesByDeltas() const;
  /// Output of the last update() (the object points before the first update()).
  const Eigen::MatrixX3d& points() const;
  /// points(), handed over without a copy (for a caller done with the deformation). The pipeline
  /// keeps its input and lattices but no output or embedding: the next run embeds every stage.
  Eigen::MatrixX3d takePoints();
  /// Input object points.
  const Eigen::MatrixX3d& inputPoints() const { return input_; }
  /// Embedding of a lattice's input (null before its first update). @throws LatticeError on an unknown id.
  const Embedding* embedding(LatticeId id) const;
  /// The deformer of a lattice's stage (null before its first update): what it kept of its last
  /// steps (Deformer::keptControlWeights). @throws LatticeError on an unknown id.
  const Deformer* deformer(LatticeId id) const;
  /// What each stage did in the last run (after a cancelled run: the stages finished before the cancel).
  const std::vector<StageReport>& lastReport() const { return report_; }

 private:
  struct Node {
    Lattice lattice;
    std::optional<LatticeId> parent;
    int priority = 0;
    int serial = 0;
    std::unique_ptr<Deformer> deformer;
    std::uint64_t embeddedRest = 0;
    std::uint64_t embeddedInput = 0;
    std::uint64_t outputVersion = 0;
    int pending = 0;
    // The output is not the exact evaluation of its control points: it holds delta updates
    // (UpdateMode::Delta) made since its last full evaluation, or the precision changed since.
    // The next exact run evaluates it in full.
    bool outputInexact = false;
    // Set when a run that deformed this stage approximately (throttled) was cancelled later on:
    // the input version and rest revision it used, so that the next run keeps that output
    // instead of recomputing it and bumping its version (Action::Keep). 0: none.
    std::uint64_t keptInput = 0;
    std::uint64_t keptRest = 0;
  };
  Node& node(LatticeId id);
  const Node& node(LatticeId id) const;
  enum class Action { Update, Reembed, Stale, Keep };
  // What run() does with a stage whose input has version `inputVersion`.
  Action decide(LatticeId id, const Node& n, std::uint64_t inputVersion, bool forceEmbed) const;
  const Eigen::MatrixX3d& run(bool forceEmbed, const EmbedProgress& progress);

  Eigen::MatrixX3d input_;
  EmbedOptions options_;
  std::map<LatticeId, Node> nodes_;
  int nextId_ = 0;
  std::uint64_t inputVersion_ = 1;
  std::uint64_t versionCounter_ = 1;
  std::optional<LatticeId> active_;
  ReembedThrottle throttle_;
  UpdateMode mode_ = UpdateMode::Exact;
  Precision precision_ = Precision::Double;
  std::vector<StageReport> report_;
  const Eigen::MatrixX3d* output_ = nullptr;
  // The last completed output when the stage holding it may change before a run completes
  // (the tree changed since that run); see run(). On the heap: output_ may point to it, and a
  // moved pipeline must keep that pointer valid.
  std::unique_ptr<Eigen::MatrixX3d> heldOutput_;
};

}  // namespace ffdkit::ffd
