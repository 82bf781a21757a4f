#pragma once

#include <cstdint>
#include <limits>
#include <string>

namespace ffdkit::scenes {

/// Stable handle of an object inside one Scene, as widgets::WidgetId is for a widget: the scene
/// gives it when the object is added and keeps it through renames, so everything that refers to
/// an object (attachments, the deformer's pipelines, the view's actors, the outliner's rows) holds
/// the id and a rename touches the object's name only. Not written to files: a scene file names
/// its objects, and a read gives them ids in file order.
struct ObjectId {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();  ///< the value of an invalid id
  std::uint32_t value = kInvalid;  ///< the object's number in its scene

  /// True unless default-constructed.
  constexpr bool valid() const { return value != kInvalid; }
  friend constexpr auto operator<=>(const ObjectId&, const ObjectId&) = default;  ///< ordered by value
};

/// "o7"; "none" for an invalid id (messages and logs; files write names).
inline std::string toString(ObjectId id) { return id.valid() ? "o" + std::to_string(id.value) : std::string("none"); }

}  // namespace ffdkit::scenes
