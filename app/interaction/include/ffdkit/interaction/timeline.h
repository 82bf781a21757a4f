#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/command_stack.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::app {

/// The GUI-free side of the timeline (docs/animation.md): the current frame, scrubbing and
/// playback (the model set to the scene's animation at a frame, scenes::applyAnimation, then
/// re-deformed), the keys of the selection, and Insert Key / Delete Key as one undoable command
/// each that holds only the keys it added, replaced or removed and the animated channels' values
/// (for an undo after a frame change; no copy of the document). The
/// Qt timeline widget only turns pixels into frames and a QTimer into advance() calls.
class Timeline {
 public:
  /// All three must outlive the timeline; the controller supplies the selection and redraws.
  Timeline(scenes::Scene& scene, scenes::CommandStack& commands, InteractionController& controller);

  const scenes::Scene& scene() const { return scene_; }
  /// The current frame: a whole frame, in the scene's frame range (clamped when the range moves).
  int frame() const;
  /// Goes to `frame` (clamped to the range): the model takes the animation's values there
  /// (scenes::applyAnimationFrame), the objects are re-deformed and the views notified. Not an
  /// undoable edit (as in Blender, time is not part of the document's history).
  void setFrame(int frame);

  /// The channels Insert Key keys for the selection: an affine widget's variation; a lattice's
  /// frame (its control points when its frame cannot be keyed: a child bound two-way); a picked
  /// lattice point's lattice's control points.
  std::vector<std::pair<widgets::WidgetId, scenes::ChannelKind>> selectedChannels() const;
  /// The frames (fractional if keys were set between frames) of the keys of the selected widgets
  /// (every key of the scene when nothing is selected), sorted, unique.
  std::vector<double> keyFrames() const;
  /// The nearest key frame before / after the current frame (keyFrames()), if any.
  std::optional<double> previousKey() const;
  std::optional<double> nextKey() const;

  /// Keys every selected channel at the current frame with its present value (smooth), replacing
  /// keys at that frame: one command ("Insert Key"). @return how many keys were set.
  /// @throws std::invalid_argument when nothing selected can be keyed (the message says what can).
  int insertKeys();
  /// Removes the selected channels' keys at the current frame: one command ("Delete Key").
  /// @return how many were removed. @throws std::invalid_argument when there is none.
  int deleteKeys();

  // ---- playback ----------------------------------------------------------------------------
  /// Starts / stops playing. Playing, advance() moves the clock at the scene's frame rate.
  void setPlaying(bool playing);
  bool playing() const { return playing_; }
  /// Moves the playback clock on by `seconds` of wall time at the scene's rate, looping over the
  /// frame range; goes to the whole frame the clock reaches when it differs from the current
  /// one (a slow frame makes playback skip frames, not slow down). During a drag nothing is
  /// applied (the drag owns the model; the clock runs on). @return true if the frame changed.
  bool advance(double seconds);
  /// Moves the playback clock on by `frames` whole frames, as advance() does for time: a source
  /// of playback that does not follow the wall clock (a test stepping it), so a run shows the
  /// same frames every time. Nothing when not playing or `frames` < 1.
  /// @return true if the frame changed.
  bool advanceFrames(int frames);

  /// Bytes a key command holds for `keys` (CommandStack::bytes).
  static std::size_t bytesOf(const std::vector<scenes::Keyframe>& keys);

 private:
  struct KeyChange;
  /// Pushes the key changes as one command; `animatedBefore` is scenes::animatedState before them.
  void push(const std::string& description, std::vector<KeyChange> changes, const widgets::WidgetModelState& animatedBefore);
  /// Moves the playback clock on by `frames` (fractional) and goes to the whole frame it reaches
  /// (advance, advanceFrames). @return true if the frame changed.
  bool moveClock(double frames);

  scenes::Scene& scene_;
  scenes::CommandStack& commands_;
  InteractionController& controller_;
  int frame_ = 0;
  bool playing_ = false;
  double clock_ = 0.0;  ///< playback position in frames (fractional)
};

}  // namespace ffdkit::app
