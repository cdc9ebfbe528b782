#pragma once
// Dear ImGui on the GLFW window: context, backends, and a font sized for the monitor's content scale.

#include <vector>

struct GLFWwindow;

namespace rayview {

// ImGui's built-in font is drawn for this size at content scale 1.
inline constexpr float kBaseFontPixels = 13.0f;

// Scales: `contentScale` is the monitor's (glfwGetWindowContentScale: 2 on a "200%" screen);
// `framebufferScale` is framebuffer pixels per window coordinate (1 on X11, 2 where window coordinates are
// points, as on macOS or scaled Wayland). Fonts are rasterised at contentScale for crisp text; widget sizes,
// which are in window coordinates, grow by contentScale / framebufferScale.
class ImGuiLayer {
 public:
  ImGuiLayer(GLFWwindow* window, float contentScale, float framebufferScale);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  // Rebuilds the font and widget sizes for a new content scale (the window moved to another monitor).
  void setScale(float contentScale, float framebufferScale);
  // How much bigger than at scale 1 things are in window coordinates (for layout).
  float layoutScale() const { return contentScale_ / framebufferScale_; }

  // `quickPresses`: keys (GLFW_KEY_*) pressed and released again since the last frame. ImGui reads a key's state
  // once a frame, so such a press would be lost (a fast Enter in a text field): each is held down for this frame.
  // `touched`: every key with an event since the last frame, whose state the window's callback set and a key held
  // by the previous frame must not undo.
  void beginFrame(const std::vector<int>& quickPresses = {}, const std::vector<int>& touched = {});
  // Renders ImGui's draw lists into the bound default framebuffer.
  void render();

 private:
  void applyScale();
  float contentScale_ = 1.0f;
  float framebufferScale_ = 1.0f;
  std::vector<int> held_;  // keys held down for one frame by beginFrame, released at the next
};

}  // namespace rayview
