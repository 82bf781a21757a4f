#include "ffdkit/scenes/command_stack.h"

#include <limits>
#include <stdexcept>

namespace ffdkit::scenes {

namespace {
constexpr std::size_t kNoCleanState = std::numeric_limits<std::size_t>::max();
}

CommandStack::CommandStack(std::size_t limit) : limit_(limit) {
  if (limit == 0) throw std::invalid_argument("CommandStack: limit must be >= 1");
}

void CommandStack::push(Command command) {
  if (!command.undo || !command.redo)
    throw std::invalid_argument("CommandStack::push: command '" + command.description + "' lacks undo or redo");
  if (cleanPosition_ > position_ && cleanPosition_ != kNoCleanState) cleanPosition_ = kNoCleanState;
  commands_.resize(position_);
  if (!command.mergeKey.empty() && position_ > 0 && commands_[position_ - 1].mergeKey == command.mergeKey &&
      cleanPosition_ != position_) {
    // One more edit of the same field: one step from before the first to after the last.
    Command& top = commands_[position_ - 1];
    top.undo = [later = std::move(command.undo), earlier = std::move(top.undo)] {
      later();
      earlier();
    };
    top.redo = [earlier = std::move(top.redo), later = std::move(command.redo)] {
      earlier();
      later();
    };
    top.description = std::move(command.description);
    top.bytes += command.bytes;
    changed();
    return;
  }
  commands_.push_back(std::move(command));
  ++position_;
  if (commands_.size() > limit_) {
    commands_.erase(commands_.begin());
    --position_;
    cleanPosition_ = (cleanPosition_ == kNoCleanState || cleanPosition_ == 0) ? kNoCleanState : cleanPosition_ - 1;
  }
  changed();
}

void CommandStack::undo() {
  if (!canUndo()) throw std::logic_error("CommandStack::undo: nothing to undo");
  commands_[position_ - 1].undo();
  --position_;
  changed();
}

void CommandStack::redo() {
  if (!canRedo()) throw std::logic_error("CommandStack::redo: nothing to redo");
  commands_[position_].redo();
  ++position_;
  changed();
}

std::size_t CommandStack::bytes() const {
  std::size_t total = 0;
  for (const Command& c : commands_) total += c.bytes;
  return total;
}

std::string CommandStack::undoDescription() const { return canUndo() ? commands_[position_ - 1].description : ""; }
std::string CommandStack::redoDescription() const { return canRedo() ? commands_[position_].description : ""; }

void CommandStack::clear() {
  commands_.clear();
  position_ = 0;
  cleanPosition_ = 0;
  changed();
}

void CommandStack::changed() const {
  if (onChanged) onChanged();
}

}  // namespace ffdkit::scenes
