#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace ffdkit::scenes {

/// One undoable change: a short description for menus ("Drag translate1", "Bind rotate1 ->
/// translate2") and the two ways to get from one state to the other. A command holds the delta
/// it applied (what changed, before and after), never a copy of the document or of a mesh.
struct Command {
  std::string description;  ///< for the Edit menu: "Drag translate1"
  std::function<void()> undo;  ///< puts the document back as it was before the change
  std::function<void()> redo;  ///< applies the change again
  /// Commands with the same non-empty key pushed one right after the other merge into one step
  /// (typing a value, dragging a spin box, the mouse wheel): its undo goes back to before the
  /// first, its redo to after the last (QUndoCommand::id / mergeWith). A clean state (a save)
  /// between them keeps them apart.
  std::string mergeKey;
  /// Bytes the command's deltas hold (heap included), for CommandStack::bytes().
  std::size_t bytes = 0;
};

/// Undo / redo for every change to a document (ParaView-style: the stack lives outside the
/// GUI and is passed explicitly; there is no global instance). A change is applied by the
/// caller and then pushed; one drag gesture is one command.
class CommandStack {
 public:
  /// `limit`: the most commands kept; the oldest are dropped first. >= 1.
  explicit CommandStack(std::size_t limit = 1000);

  /// Records a change the caller has already applied. Drops everything that could be redone.
  /// @throws std::invalid_argument if `undo` or `redo` is empty.
  void push(Command command);

  /// Records a change as two snapshots of a state and the function that restores one:
  /// undo = restore(before), redo = restore(after).
  template <class State, class Restore>
  void pushSnapshots(std::string description, State before, State after, Restore restore) {
    push(Command{std::move(description), [restore, before] { restore(before); },
                 [restore, after] { restore(after); }, std::string(), 2 * sizeof(State)});
  }

  /// True when there is a command to undo.
  bool canUndo() const { return position_ > 0; }
  /// True when there is a command to redo.
  bool canRedo() const { return position_ < commands_.size(); }
  /// Undoes the last applied command. @throws std::logic_error if there is none.
  void undo();
  /// Redoes the last undone command. @throws std::logic_error if there is none.
  void redo();

  /// Description of what undo() / redo() would do; empty if nothing.
  std::string undoDescription() const;
  /// Description of what redo() would do; empty if nothing.
  std::string redoDescription() const;

  /// Commands kept (undoable and redoable).
  std::size_t size() const { return commands_.size(); }
  /// Bytes held by every command kept (undoable and redoable): the undo memory.
  std::size_t bytes() const;
  /// Commands applied (and so undoable): the stack's position.
  std::size_t position() const { return position_; }
  /// True when the document differs from the last markClean() (e.g. the last save).
  bool isDirty() const { return cleanPosition_ != position_; }
  /// The document is clean (saved) at the present position.
  void markClean() { cleanPosition_ = position_; }
  /// Drops every command (a new or reopened document).
  void clear();

  /// Called after every push, undo, redo and clear (the GUI refreshes its menus).
  std::function<void()> onChanged;

 private:
  void changed() const;

  std::vector<Command> commands_;
  std::size_t position_ = 0;
  std::size_t cleanPosition_ = 0;  ///< SIZE_MAX when the clean state was dropped
  std::size_t limit_;
};

}  // namespace ffdkit::scenes
