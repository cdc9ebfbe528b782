#include "rayview/render_settings.h"

#include "rayview/build_features.h"

namespace rayview {

std::string_view toString(AccelKind kind) {
  switch (kind) {
    case AccelKind::Embree: return "embree";
    case AccelKind::Packet: return "packet";
    default: return "reference";
  }
}

bool parseAccelKind(std::string_view text, AccelKind& out) {
  if (text == "embree") out = AccelKind::Embree;
  else if (text == "reference") out = AccelKind::Reference;
  else if (text == "packet") out = AccelKind::Packet;
  else return false;
  return true;
}

std::string_view toString(SecondaryRayStart start) {
  return start == SecondaryRayStart::Offset ? "offset" : "exclude-hit";
}

bool parseSecondaryRayStart(std::string_view text, SecondaryRayStart& out) {
  if (text == "offset") out = SecondaryRayStart::Offset;
  else if (text == "exclude-hit") out = SecondaryRayStart::ExcludeHitTriangle;
  else return false;
  return true;
}

AccelKind availableAccel(AccelKind requested) {
#ifdef RAYVIEW_HAVE_EMBREE
  return requested;
#else
  // Without Embree its place as the fast traversal is the packet BVH's, which gives Embree's answers.
  return requested == AccelKind::Embree ? AccelKind::Packet : requested;
#endif
}

}  // namespace rayview
