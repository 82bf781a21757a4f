#include "ffdkit/widgets/affine_kind.h"

#include <gtest/gtest.h>

namespace ffdkit::widgets {
namespace {

TEST(AffineKind, NamesRoundTrip) {
  for (AffineKind k : {AffineKind::Translate, AffineKind::Rotate, AffineKind::Scale}) {
    EXPECT_EQ(parseAffineKind(affineKindName(k)), k);
  }
}

TEST(AffineKind, UnknownNameIsRejected) {
  EXPECT_FALSE(parseAffineKind("shear").has_value());
  EXPECT_FALSE(parseAffineKind("").has_value());
}

}  // namespace
}  // namespace ffdkit::widgets
