#pragma once

// Shared by the widget-model tests.

#include <utility>

#include <gtest/gtest.h>

#include "ffdkit/widgets/widget_error.h"

namespace ffdkit::widgets::testing {

/// Runs `f`, expecting it to throw a WidgetError with `code`; returns the error (for its message).
template <class F>
WidgetError expectError(WidgetErrorCode code, F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const WidgetError& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    return e;
  }
  ADD_FAILURE() << "expected a WidgetError";
  return WidgetError(code, "");
}

}  // namespace ffdkit::widgets::testing
