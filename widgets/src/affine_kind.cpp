#include "ffdkit/widgets/affine_kind.h"

namespace ffdkit::widgets {

std::string_view affineKindName(AffineKind kind) {
  switch (kind) {
    case AffineKind::Translate: return "translate";
    case AffineKind::Rotate: return "rotate";
    case AffineKind::Scale: return "scale";
  }
  return "unknown";
}

std::optional<AffineKind> parseAffineKind(std::string_view name) {
  for (AffineKind k : {AffineKind::Translate, AffineKind::Rotate, AffineKind::Scale}) {
    if (affineKindName(k) == name) return k;
  }
  return std::nullopt;
}

}  // namespace ffdkit::widgets
