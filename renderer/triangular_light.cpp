#include "rayview/triangular_light.h"

namespace rayview {

std::string_view toString(TriangularLightModel model) {
  return model == TriangularLightModel::Area ? "area" : "directional";
}

bool parseTriangularLightModel(std::string_view text, TriangularLightModel& out) {
  if (text == "area") out = TriangularLightModel::Area;
  else if (text == "directional") out = TriangularLightModel::Directional;
  else return false;
  return true;
}

}  // namespace rayview
