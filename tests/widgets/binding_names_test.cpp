// The file-format names of binding and re-embed kinds (docs/file-formats): each name parses back
// to its own kind, written out here, and nothing else parses.
#include <gtest/gtest.h>

#include "ffdkit/widgets/binding.h"
#include "ffdkit/widgets/lattice_settings.h"

namespace ffdkit::widgets {
namespace {

TEST(BindingKind, NamesParseToTheirOwnKind) {
  EXPECT_EQ(parseBindingKind("attachment"), BindingKind::Attachment);
  EXPECT_EQ(parseBindingKind("variation"), BindingKind::Variation);
  EXPECT_EQ(parseBindingKind("cell-motion"), BindingKind::CellMotion);
  EXPECT_EQ(parseBindingKind("hierarchy"), BindingKind::Hierarchy);
  for (BindingKind k : {BindingKind::Attachment, BindingKind::Variation, BindingKind::CellMotion, BindingKind::Hierarchy}) {
    EXPECT_EQ(parseBindingKind(bindingKindName(k)), k);
  }
  EXPECT_FALSE(parseBindingKind("Variation").has_value());
  EXPECT_FALSE(parseBindingKind("").has_value());
}

TEST(ReembedKind, NamesParseToTheirOwnKind) {
  EXPECT_EQ(parseReembedKind("immediate"), ReembedKind::Immediate);
  EXPECT_EQ(parseReembedKind("every-n"), ReembedKind::EveryN);
  EXPECT_EQ(parseReembedKind("on-release"), ReembedKind::OnRelease);
  for (ReembedKind k : {ReembedKind::Immediate, ReembedKind::EveryN, ReembedKind::OnRelease}) {
    EXPECT_EQ(parseReembedKind(reembedKindName(k)), k);
  }
  EXPECT_FALSE(parseReembedKind("sometimes").has_value());
}

}  // namespace
}  // namespace ffdkit::widgets
