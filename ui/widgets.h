#pragma once
// Small ImGui building blocks for the panels: vectors and colours of the scene format, in its units.

#include <cstddef>
#include <string>

#include <glm/vec3.hpp>

#include "rayview/knobs.h"
#include "rayview/scene.h"

namespace rayview {

// Drag to change, double-click (or Ctrl+click) to type. Full precision kept (no rounding to the display).
// A render knob (rayview/knobs.h) as the table describes it: its label, limits or choices, and its help as the
// tooltip; greyed out where it changes nothing for this scene, shown as text where the build offers one value.
// `shownChoice`: what the closed dropdown of a choice says instead of the chosen label (the traversal actually
// built, when it is not the one chosen).
bool editKnob(const Knob& knob, SceneParameters& parameters, RenderSettings& settings, const char* shownChoice = nullptr);

bool editPoint(const char* label, glm::dvec3& value, double speed);
bool editDoubles(const char* label, double* values, int count, double speed, double minimum, double maximum);
// A colour in radiance units (0..255 and beyond, lights and background).
bool editRadiance(const char* label, Color& value);
// A reflectance coefficient (0..1 typically, more allowed): a swatch plus three numbers.
bool editCoefficient(const char* label, Color& value);
// The red text under a field that explains why an edit is not rendered.
void problemText(const std::string& problem);
// "1 point light", "2 point lights": every count the viewer shows or prints.
std::string counted(std::size_t count, const char* singular);
// A grey hint line.
void hintText(const char* text);
// A tooltip wrapped to stay inside the window: at most 35 characters' widths of the font, or the window's width
// less margins when that is narrower. `shown` (tests): where it was drawn, as (min x, min y, max x, max y).
void tooltip(const std::string& text, float* shown = nullptr);

}  // namespace rayview
