#include "ffdkit/ffd/pipeline.h"

#include <algorithm>
#include <functional>
#include <string>

namespace ffdkit::ffd {
namespace {

void checkPoints(const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  for (Eigen::Index r = 0; r < points.rows(); ++r) {
    if (!points.row(r).allFinite()) throw LatticeError("pipeline: object point " + std::to_string(r) + " is not finite");
  }
}

}  // namespace

Pipeline::Pipeline(const Eigen::Ref<const Eigen::MatrixX3d>& points, const EmbedOptions& options)
    : input_(points), options_(options) {
  checkPoints(points);
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
  checkPoints(points);
  input_ = points;
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

const Eigen::MatrixX3d& Pipeline::update() { return run(false); }

const Eigen::MatrixX3d& Pipeline::reembedAll() { return run(true); }

const Eigen::MatrixX3d& Pipeline::points() const { return output_ ? *output_ : input_; }

const Embedding* Pipeline::embedding(LatticeId id) const {
  const Node& n = node(id);
  return n.deformer ? &n.deformer->embedding() : nullptr;
}

const Eigen::MatrixX3d& Pipeline::run(bool forceEmbed) {
  report_.clear();
  const Eigen::MatrixX3d* input = &input_;
  std::uint64_t inputVersion = inputVersion_;
  for (LatticeId id : order()) {
    Node& n = nodes_.at(id);
    StageReport report{id};
    const bool fresh = n.deformer && n.embeddedRest == n.lattice.restRevision() && n.embeddedInput == inputVersion;
    if (fresh) {
      n.deformer->update(n.lattice, *input);
      report.outputChanged = n.deformer->lastStats().changedControlPoints > 0;
    } else {
      const bool compatible = n.deformer && n.deformer->embedding().latticeCounts() == n.lattice.counts() &&
                              n.deformer->embedding().pointCount() == input->rows();
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
      if (reembed) {
        n.deformer = std::make_unique<Deformer>(embed(n.lattice, *input, options_));
        n.embeddedRest = n.lattice.restRevision();
        n.embeddedInput = inputVersion;
        n.pending = 0;
        n.deformer->deform(n.lattice, *input);
        report.reembedded = true;
      } else {
        ++n.pending;
        n.deformer->deformStale(n.lattice, *input);
        report.approximate = true;
      }
      report.outputChanged = true;
    }
    if (report.outputChanged || n.outputVersion == 0) n.outputVersion = ++versionCounter_;
    inputVersion = n.outputVersion;
    input = &n.deformer->points();
    report_.push_back(report);
  }
  output_ = input == &input_ ? nullptr : input;
  return points();
}

}  // namespace ffdkit::ffd
