#include "ffdkit/widgets/widget_id.h"

#include <gtest/gtest.h>

#include "ffdkit/widgets/widget_error.h"
#include "ffdkit/widgets/widget_model.h"

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

TEST(WidgetModel, RenameMovesTheNameAndOnlyChangesOnANewName) {
  WidgetModel m;
  const WidgetId box = m.addLattice("box", Eigen::Vector3i(2, 2, 2));
  const std::uint64_t before = m.revision();
  m.rename(box, "box");  // the same name: nothing to do
  EXPECT_EQ(m.revision(), before);
  m.rename(box, "crate");
  EXPECT_GT(m.revision(), before);
  EXPECT_EQ(m.name(box), "crate");
  EXPECT_EQ(m.find("crate"), box);
  EXPECT_THROW(m.find("box"), WidgetError);
  // The old name is free again, the new one taken.
  const WidgetId other = m.addLattice("box", Eigen::Vector3i(2, 2, 2));
  EXPECT_EQ(m.find("box"), other);
  EXPECT_THROW(m.rename(other, "crate"), WidgetError);
}

}  // namespace
}  // namespace ffdkit::widgets
