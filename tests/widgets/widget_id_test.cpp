#include "ffdkit/widgets/widget_id.h"

#include <gtest/gtest.h>

namespace ffdkit::widgets {
namespace {

TEST(WidgetId, ParsingAcceptsOnlyThePrefixAndDigits) {
  EXPECT_EQ(parseWidgetId("w7"), WidgetId{7});
  EXPECT_EQ(parseBindingId("b30"), BindingId{30});
  EXPECT_EQ(parseWidgetId(toString(WidgetId{4021})), WidgetId{4021});
  for (const char* bad : {"w7x", "w1 ", "w", "", "w-1", "b7", "w0x1", "w99999999999", "W7"}) {
    EXPECT_FALSE(parseWidgetId(bad).has_value()) << bad;
  }
  EXPECT_FALSE(parseBindingId("b3.0").has_value());
  EXPECT_FALSE(parseBindingId("w3").has_value());
}

}  // namespace
}  // namespace ffdkit::widgets
