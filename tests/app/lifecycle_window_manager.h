#pragma once

// What a window manager and a keyboard do to an X11 client's windows, done by the test through
// a connection of its own to the X server (Xvfb runs no window manager): ask a window to close
// (a WM_DELETE_WINDOW ClientMessage, ICCCM 4.2.8.1), give a window the keyboard focus, type
// keys into it, and find a process's windows by their titles. The client sees exactly what a
// window manager and a keyboard would send it; nothing goes through Qt's own calls.

#include <xcb/xcb.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ffdkit::app::testing {

class WindowManager {
 public:
  using Window = std::uint32_t;

  /// Connects to $DISPLAY; connected() says whether that worked.
  WindowManager() : connection_(xcb_connect(nullptr, &screenNumber_)) {
    if (xcb_connection_has_error(connection_) != 0) return;
    xcb_screen_iterator_t screens = xcb_setup_roots_iterator(xcb_get_setup(connection_));
    for (int i = 0; i < screenNumber_ && screens.rem > 0; ++i) xcb_screen_next(&screens);
    root_ = screens.data->root;
    wmProtocols_ = atom("WM_PROTOCOLS");
    wmDeleteWindow_ = atom("WM_DELETE_WINDOW");
    netWmName_ = atom("_NET_WM_NAME");
    netWmPid_ = atom("_NET_WM_PID");
    utf8String_ = atom("UTF8_STRING");
  }
  ~WindowManager() { xcb_disconnect(connection_); }
  WindowManager(const WindowManager&) = delete;
  WindowManager& operator=(const WindowManager&) = delete;

  bool connected() const { return root_ != 0; }

  /// The shown (mapped) top-level windows of process `pid` (by their _NET_WM_PID).
  std::vector<Window> windowsOf(std::int64_t pid) {
    std::vector<Window> out;
    const Reply<xcb_query_tree_reply_t> tree(xcb_query_tree_reply(connection_, xcb_query_tree(connection_, root_), nullptr));
    if (!tree) return out;
    const xcb_window_t* children = xcb_query_tree_children(tree.get());
    for (int i = 0; i < xcb_query_tree_children_length(tree.get()); ++i) {
      const Window window = children[i];
      const Reply<xcb_get_window_attributes_reply_t> attributes(
          xcb_get_window_attributes_reply(connection_, xcb_get_window_attributes(connection_, window), nullptr));
      if (!attributes || attributes->map_state != XCB_MAP_STATE_VIEWABLE) continue;
      const std::string owner = property(window, netWmPid_, XCB_ATOM_CARDINAL);
      if (owner.size() == 4 && *reinterpret_cast<const std::uint32_t*>(owner.data()) == std::uint32_t(pid))
        out.push_back(window);
    }
    return out;
  }

  /// The title a window manager shows (_NET_WM_NAME, else WM_NAME).
  std::string title(Window window) {
    const std::string name = property(window, netWmName_, utf8String_);
    return name.empty() ? property(window, XCB_ATOM_WM_NAME, XCB_ATOM_STRING) : name;
  }

  /// The shown window of process `pid` titled `text`, if there is one.
  std::optional<Window> findWindow(std::int64_t pid, const std::string& text) {
    for (Window window : windowsOf(pid))
      if (title(window) == text) return window;
    return std::nullopt;
  }

  /// Whether the window asks to be sent WM_DELETE_WINDOW rather than be destroyed (its
  /// WM_PROTOCOLS property lists it): a window manager checks this before it sends one.
  bool takesDeleteWindow(Window window) {
    const std::string atoms = property(window, wmProtocols_, XCB_ATOM_ATOM);
    for (std::size_t at = 0; at + 4 <= atoms.size(); at += 4)
      if (*reinterpret_cast<const std::uint32_t*>(atoms.data() + at) == wmDeleteWindow_) return true;
    return false;
  }

  /// The close button of the window's frame: a WM_DELETE_WINDOW ClientMessage to the client that
  /// created the window (ICCCM 4.2.8.1).
  void requestClose(Window window) {
    xcb_client_message_event_t event{};
    event.response_type = XCB_CLIENT_MESSAGE;
    event.format = 32;
    event.window = window;
    event.type = wmProtocols_;
    event.data.data32[0] = wmDeleteWindow_;
    event.data.data32[1] = XCB_CURRENT_TIME;
    xcb_send_event(connection_, 0, window, XCB_EVENT_MASK_NO_EVENT, reinterpret_cast<const char*>(&event));
    sync();
  }

  /// The keyboard focus to `window`, as a click-to-focus window manager gives it.
  void focus(Window window) {
    xcb_set_input_focus(connection_, XCB_INPUT_FOCUS_POINTER_ROOT, window, XCB_CURRENT_TIME);
    sync();
  }

  /// The window that has the keyboard focus.
  Window focused() {
    const Reply<xcb_get_input_focus_reply_t> reply(
        xcb_get_input_focus_reply(connection_, xcb_get_input_focus(connection_), nullptr));
    return reply ? reply->focus : 0;
  }

  /// A key pressed and released in `window`: `keysym` (X11's keysymdef.h: 0xff0d Return,
  /// 0xffff Delete, a Latin-1 letter by its lower-case code) with `modifiers` held (an
  /// XCB_MOD_MASK_* mask, e.g. XCB_MOD_MASK_CONTROL). @return false if no key gives `keysym`.
  bool typeKey(Window window, std::uint32_t keysym, std::uint16_t modifiers = 0) {
    const std::optional<xcb_keycode_t> code = keycodeOf(keysym);
    if (!code) return false;
    for (const std::uint8_t type : {XCB_KEY_PRESS, XCB_KEY_RELEASE}) {
      xcb_key_press_event_t event{};
      event.response_type = type;
      event.detail = *code;
      event.time = XCB_CURRENT_TIME;
      event.root = root_;
      event.event = window;
      event.child = XCB_NONE;
      event.event_x = event.event_y = event.root_x = event.root_y = 10;
      event.state = modifiers;
      event.same_screen = 1;
      xcb_send_event(connection_, 0, window, XCB_EVENT_MASK_NO_EVENT, reinterpret_cast<const char*>(&event));
    }
    sync();
    return true;
  }

 private:
  struct FreeReply {
    void operator()(void* reply) const { std::free(reply); }
  };
  template <class T>
  using Reply = std::unique_ptr<T, FreeReply>;

  // Returns once the server has carried out every request sent so far (a round trip), so what
  // was sent reaches the client even if this connection closes next.
  void sync() {
    const Reply<xcb_get_input_focus_reply_t> reply(
        xcb_get_input_focus_reply(connection_, xcb_get_input_focus(connection_), nullptr));
  }

  xcb_atom_t atom(const char* name) {
    const Reply<xcb_intern_atom_reply_t> reply(xcb_intern_atom_reply(
        connection_, xcb_intern_atom(connection_, 0, std::uint16_t(std::char_traits<char>::length(name)), name), nullptr));
    return reply ? reply->atom : xcb_atom_t(XCB_ATOM_NONE);
  }

  // A property's bytes ("" if the window has none of that type).
  std::string property(Window window, xcb_atom_t name, xcb_atom_t type) {
    const Reply<xcb_get_property_reply_t> reply(xcb_get_property_reply(
        connection_, xcb_get_property(connection_, 0, window, name, type, 0, 1024), nullptr));
    if (!reply || reply->type != type) return {};
    const auto* bytes = static_cast<const char*>(xcb_get_property_value(reply.get()));
    return std::string(bytes, std::size_t(xcb_get_property_value_length(reply.get())));
  }

  // The first key whose unshifted symbol is `keysym` (the server's keyboard mapping).
  std::optional<xcb_keycode_t> keycodeOf(std::uint32_t keysym) {
    const xcb_setup_t* setup = xcb_get_setup(connection_);
    const int count = setup->max_keycode - setup->min_keycode + 1;
    const Reply<xcb_get_keyboard_mapping_reply_t> mapping(xcb_get_keyboard_mapping_reply(
        connection_, xcb_get_keyboard_mapping(connection_, setup->min_keycode, std::uint8_t(count)), nullptr));
    if (!mapping) return std::nullopt;
    const xcb_keysym_t* symbols = xcb_get_keyboard_mapping_keysyms(mapping.get());
    for (int key = 0; key < count; ++key)
      if (symbols[key * mapping->keysyms_per_keycode] == keysym) return xcb_keycode_t(setup->min_keycode + key);
    return std::nullopt;
  }

  int screenNumber_ = 0;
  xcb_connection_t* connection_;
  xcb_window_t root_ = 0;
  xcb_atom_t wmProtocols_ = 0, wmDeleteWindow_ = 0, netWmName_ = 0, netWmPid_ = 0, utf8String_ = 0;
};

}  // namespace ffdkit::app::testing
