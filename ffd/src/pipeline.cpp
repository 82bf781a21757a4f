#include "ffdkit/ffd/pipeline.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <string>

#include "ffdkit/ffd/huge_pages.h"

namespace ffdkit::ffd {
namespace {

/// Runs `chunk(first, count)` over the rows [0, n) in chunks of 2^16 on all cores; `chunk`
/// returns the first row of its range that is not finite, or n. Throws for the first such row.
template <class Chunk>
void finiteByChunks(Eigen::Index n, const Chunk& chunk) {
  constexpr Eigen::Index kChunk = Eigen::Index(1) << 16;
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
  Eigen::Index firstBad = n;
#pragma omp parallel for schedule(static) reduction(min : firstBad) if (chunks > 1)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    const Eigen::Index first = c * kChunk;
    firstBad = std::min(firstBad, chunk(first, std::min(kChunk, n - first)));
  }
  if (firstBad < n) throw LatticeError("pipeline: object point " + std::to_string(firstBad) + " is not finite");
}

/// The first row of points.middleRows(first, count) that is not finite, or n.
Eigen::Index firstNonFinite(const Eigen::MatrixX3d& points, Eigen::Index first, Eigen::Index count) {
  if (points.middleRows(first, count).allFinite()) return points.rows();
  for (Eigen::Index r = first; r < first + count; ++r)
    if (!points.row(r).allFinite()) return r;
  return points.rows();
}

/// The object's points copied into fresh memory backed by huge pages, by all cores, checking on
/// the way that each is finite (one pass over them). A plain copy of 1M points faulted 6,000
/// small pages on one core: 12-14 ms of the CLI's 1M-vertex deformation, against about 3 ms.
Eigen::MatrixX3d finiteCopy(const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  Eigen::MatrixX3d copy(points.rows(), 3);
  adviseHugePages(copy);
  finiteByChunks(points.rows(), [&](Eigen::Index first, Eigen::Index count) {
    copy.middleRows(first, count) = points.middleRows(first, count);
    return firstNonFinite(copy, first, count);
  });
  return copy;
}

}  // namespace

Pipeline::Pipeline(const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options)
    : input_(finiteCopy(points)), options_(options) {}

Pipeline Pipeline::adopting(Eigen::MatrixX3d&& points, const EmbedOptions& options) {
  finiteByChunks(points.rows(), [&](Eigen::Index first, Eigen::Index count) {
    return firstNonFinite(points, first, count);
  });
  Pipeline pipeline(Eigen::MatrixX3d(0, 3), options);
  pipeline.input_ = std::move(points);
  return pipeline;
}

Pipeline::Node& Pipeline::node(LatticeId id) {
  const auto it = nodes_.find(id);
  if (it == nodes_.end()) throw LatticeError("pipeline: unknown lattice id " + std::to_string(id.value));
  return it->second;
}

const Pipeline::Node& Pipeline::node(LatticeId id) const {
  const auto it = nodes_.find(id);
  if (it == nodes_.end()) throw LatticeError("pipeline: unknown lattice id " + std::to_string(id.value));
  return it->second;
}

LatticeId Pipeline::addLattice(Lattice lattice, std::optional<LatticeId> parent, int priority) {
  if (parent) node(*parent);  // existence check
  const LatticeId id{nextId_++};
  nodes_.emplace(id, Node{std::move(lattice), parent, priority, id.value, nullptr, 0, 0, 0, 0});
  return id;
}

void Pipeline::removeLattice(LatticeId id) {
  node(id);
  std::vector<LatticeId> doomed{id};
  for (std::size_t i = 0; i < doomed.size(); ++i) {
    for (const auto& [other, n] : nodes_) {
      if (n.parent == doomed[i]) doomed.push_back(other);
    }
  }
  for (LatticeId d : doomed) nodes_.erase(d);
  if (active_ && !nodes_.count(*active_)) active_.reset();
  inputVersion_ = ++versionCounter_;  // downstream inputs change: force re-evaluation
  output_ = nullptr;
}

void Pipeline::setPriority(LatticeId id, int priority) { node(id).priority = priority; }

Lattice& Pipeline::lattice(LatticeId id) { return node(id).lattice; }

const Lattice& Pipeline::lattice(LatticeId id) const { return node(id).lattice; }

std::optional<LatticeId> Pipeline::parent(LatticeId id) const { return node(id).parent; }

std::vector<LatticeId> Pipeline::order() const {
  std::map<std::optional<LatticeId>, std::vector<LatticeId>> children;
  for (const auto& [id, n] : nodes_) children[n.parent].push_back(id);
  for (auto& [parent, list] : children) {
    std::sort(list.begin(), list.end(), [this](LatticeId a, LatticeId b) {
      const Node& na = nodes_.at(a);
      const Node& nb = nodes_.at(b);
      return std::pair(na.priority, na.serial) < std::pair(nb.priority, nb.serial);
    });
  }
  std::vector<LatticeId> result;
  std::function<void(std::optional<LatticeId>)> visit = [&](std::optional<LatticeId> parent) {
    const auto it = children.find(parent);
    if (it == children.end()) return;
    for (LatticeId id : it->second) {
      result.push_back(id);
      visit(id);
    }
  };
  visit(std::nullopt);
  return result;
}

void Pipeline::setPoints(const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  input_ = finiteCopy(points);
  inputVersion_ = ++versionCounter_;
  for (auto& [id, n] : nodes_) n.deformer.reset();  // the point count may have changed
  output_ = nullptr;
}

void Pipeline::setThrottle(const ReembedThrottle& throttle) {
  if (throttle.kind == ReembedThrottle::Kind::EveryN && throttle.n < 1) {
    throw LatticeError("pipeline: EveryN throttle needs n >= 1, got " + std::to_string(throttle.n));
  }
  throttle_ = throttle;
}

void Pipeline::setPrecision(Precision precision) {
  if (precision == precision_) return;
  precision_ = precision;
  for (auto& [id, n] : nodes_) {
    if (!n.deformer) continue;
    n.deformer->setPrecision(precision);
    n.outputInexact = true;
  }
}

const Eigen::MatrixX3d& Pipeline::update(const EmbedProgress& progress) { return run(false, progress); }

const Eigen::MatrixX3d& Pipeline::reembedAll(const EmbedProgress& progress) { return run(true, progress); }

const Eigen::MatrixX3d& Pipeline::points() const { return output_ ? *output_ : input_; }

Eigen::MatrixX3d Pipeline::takePoints() {
  Eigen::MatrixX3d taken;
  if (!output_) {
    taken = input_;  // no stage ran: the output is the input, which the pipeline keeps
  } else if (output_ == heldOutput_.get()) {
    taken = std::move(*heldOutput_);
  } else {
    for (auto& [id, n] : nodes_) {
      if (n.deformer && output_ == &n.deformer->points()) {
        taken = n.deformer->takePoints();
        break;
      }
    }
  }
  for (auto& [id, n] : nodes_) n.deformer.reset();
  heldOutput_.reset();
  output_ = nullptr;
  return taken;
}

const Embedding* Pipeline::embedding(LatticeId id) const {
  const Node& n = node(id);
  return n.deformer ? &n.deformer->embedding() : nullptr;
}

const Deformer* Pipeline::deformer(LatticeId id) const { return node(id).deformer.get(); }

Pipeline::Action Pipeline::decide(LatticeId id, const Node& n, std::uint64_t inputVersion, bool forceEmbed) const {
  const bool fresh = n.deformer && n.embeddedRest == n.lattice.restRevision() && n.embeddedInput == inputVersion;
  if (fresh) return Action::Update;
  // Every stage's input has the object's point count (each stage maps n points to n points).
  const bool compatible = n.deformer && n.deformer->embedding().latticeCounts() == n.lattice.counts() &&
                          n.deformer->embedding().pointCount() == input_.rows();
  bool reembed = forceEmbed || !compatible || active_ == id;
  switch (throttle_.kind) {
    case ReembedThrottle::Kind::Immediate:
      reembed = true;
      break;
    case ReembedThrottle::Kind::EveryN:
      reembed = reembed || n.pending + 1 >= throttle_.n;
      break;
    case ReembedThrottle::Kind::OnDemand:
      break;
  }
  if (reembed) return Action::Reembed;
  const bool kept = n.keptInput == inputVersion && n.keptRest == n.lattice.restRevision() &&
                    n.deformer->isCurrentFor(n.lattice);
  return kept ? Action::Keep : Action::Stale;
}

bool Pipeline::onlyLastStageMovesByDeltas() const {
  if (mode_ != UpdateMode::Delta || !output_) return false;
  const std::vector<LatticeId> stages = order();
  std::uint64_t inputVersion = inputVersion_;
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const Node& n = nodes_.at(stages[k]);
    // decide() as run() would: Update means a fresh embedding of this input.
    if (!n.deformer || n.outputVersion == 0 || decide(stages[k], n, inputVersion, false) != Action::Update) return false;
    if (k + 1 < stages.size()) {
      if (!n.deformer->isCurrentFor(n.lattice)) return false;  // its output would change too
      inputVersion = n.outputVersion;
      continue;
    }
    const Deformer& last = *n.deformer;
    return output_ == &last.points() && !n.lattice.isRational() && last.lastWeights().size() == n.lattice.weights().size() &&
           last.lastWeights() == n.lattice.weights() &&
           last.lastControlPoints().rows() == n.lattice.pointCount();
  }
  return false;
}

Eigen::Index Pipeline::pointsToEmbed(bool reembedAll) const {
  // Replays run()'s decisions without running: a stage whose output changes gives it a version no
  // stage has seen, so the next stage is not fresh; a fresh stage's output changes iff one of its
  // control points moved since its deformer last ran (what Deformer::update() compares).
  Eigen::Index total = 0;
  std::uint64_t counter = versionCounter_;
  std::uint64_t inputVersion = inputVersion_;
  for (LatticeId id : order()) {
    const Node& n = nodes_.at(id);
    const Action action = decide(id, n, inputVersion, reembedAll);
    bool changed = action != Action::Keep;
    if (action == Action::Update)
      changed = (n.outputInexact && (reembedAll || mode_ == UpdateMode::Exact)) ||
                !n.deformer->isCurrentFor(n.lattice);
    if (action == Action::Reembed) total += input_.rows();
    inputVersion = changed || n.outputVersion == 0 ? ++counter : n.outputVersion;
  }
  return total;
}

const Eigen::MatrixX3d& Pipeline::run(bool forceEmbed, const EmbedProgress& progress) {
  const std::vector<LatticeId> stages = order();
  const Eigen::Index total = progress ? pointsToEmbed(forceEmbed) : 0;
  Eigen::Index done = 0;
  const auto tell = [&progress, total](Eigen::Index d) {
    if (progress && !progress(std::min(d, total), total)) {
      throw Cancelled("pipeline: cancelled after embedding " + std::to_string(std::min(d, total)) + " of " +
                      std::to_string(total) + " points");
    }
  };
  // After a cancel points() must still be the last completed output. It normally lives in the
  // last stage, which changes only when no stage is left to cancel; when the tree changed since
  // (a lattice added, priorities changed) it may live in an earlier stage: keep a copy.
  if (output_ && output_ != heldOutput_.get()) {
    const Node* last = stages.empty() ? nullptr : &nodes_.at(stages.back());
    if (!last || !last->deformer || output_ != &last->deformer->points()) {
      heldOutput_ = std::make_unique<Eigen::MatrixX3d>(*output_);
      output_ = heldOutput_.get();
    }
  }
  // Stages deformed approximately in this run, with their input version.
  std::vector<std::pair<Node*, std::uint64_t>> approximated;

  report_.clear();
  const Eigen::MatrixX3d* input = &input_;
  std::uint64_t inputVersion = inputVersion_;
  try {
    tell(0);
    for (LatticeId id : stages) {
      Node& n = nodes_.at(id);
      StageReport report{id};
      const Action action = decide(id, n, inputVersion, forceEmbed);
      const bool exact = forceEmbed || mode_ == UpdateMode::Exact;
      if (action == Action::Update && n.outputInexact && exact) {
        // Deltas (or a new precision) since the last full evaluation: evaluate in full again (bit
        // for bit what exact incremental updates would have given).
        n.deformer->deform(n.lattice, *input);
        n.outputInexact = false;
        report.outputChanged = true;
      } else if (action == Action::Update && !exact) {
        n.deformer->update(n.lattice);
        report.outputChanged = n.deformer->lastStats().changedControlPoints > 0;
        report.delta = report.outputChanged;
        n.outputInexact = n.outputInexact || report.outputChanged;
      } else if (action == Action::Update) {
        n.deformer->update(n.lattice, *input);
        report.outputChanged = n.deformer->lastStats().changedControlPoints > 0;
      } else if (action == Action::Reembed) {
        EmbedOptions options = options_;
        options.progress = {};
        if (progress) {
          options.progress = [&progress, done, total](Eigen::Index d, Eigen::Index) {
            return progress(std::min(done + d, total), total);
          };
        }
        const auto start = std::chrono::steady_clock::now();
        // A cancel throws here, before the stage is touched.
        Embedding embedding = embed(n.lattice, *input, options);
        report.embedSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        done += input->rows();
        if (n.deformer && output_ == &n.deformer->points()) output_ = nullptr;
        n.deformer = std::make_unique<Deformer>(std::move(embedding));
        n.deformer->setPrecision(precision_);
        n.embeddedRest = n.lattice.restRevision();
        n.embeddedInput = inputVersion;
        n.pending = 0;
        n.outputInexact = false;
        n.deformer->deform(n.lattice, *input);
        report.reembedded = true;
        report.outputChanged = true;
      } else if (action == Action::Stale) {
        ++n.pending;
        approximated.emplace_back(&n, inputVersion);
        n.deformer->deformStale(n.lattice, *input);
        n.outputInexact = false;
        report.approximate = true;
        report.outputChanged = true;
      } else {  // Keep: this output, from a cancelled run, is what deformStale would compute again.
        ++n.pending;
        approximated.emplace_back(&n, inputVersion);
        report.approximate = true;
      }
      n.keptInput = n.keptRest = 0;
      if (report.outputChanged || n.outputVersion == 0) n.outputVersion = ++versionCounter_;
      inputVersion = n.outputVersion;
      input = &n.deformer->points();
      report_.push_back(report);
    }
  } catch (...) {
    // The next run must decide as this one did, as if it had not been cut short: the throttled
    // stages that ran keep their output (Action::Keep) and count this run once.
    for (auto& [n, version] : approximated) {
      --n->pending;
      n->keptInput = version;
      n->keptRest = n->lattice.restRevision();
    }
    throw;
  }
  output_ = input == &input_ ? nullptr : input;
  heldOutput_.reset();
  tell(total);
  return points();
}

}  // namespace ffdkit::ffd
