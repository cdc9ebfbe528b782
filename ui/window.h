#pragma once
// The GLFW window and its OpenGL 3.3 core context, plus the raw input the viewer navigates with.
//
// Input arrives through GLFW callbacks in the order the user produced it; it is queued here and handled
// once per UI frame, after Dear ImGui has seen it and decided whether it wants it (WantCaptureMouse /
// WantCaptureKeyboard). ImGui's own GLFW backend chains to these callbacks.

#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace rayview {

class DisplayUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct InputEvent {
  enum class Kind { MouseButton, CursorMove, Scroll, Key };
  Kind kind = Kind::CursorMove;
  int button = 0;          // GLFW_MOUSE_BUTTON_*
  int key = 0;             // GLFW_KEY_*
  bool pressed = false;    // MouseButton and Key: press (or key repeat) rather than release
  bool repeat = false;     // Key: held down, repeated by the system
  int mods = 0;            // GLFW_MOD_*
  double x = 0.0, y = 0.0; // cursor position (window coordinates) or scroll offsets
};

class Window {
 public:
  // Throws DisplayUnavailable when there is no display or no OpenGL 3.3 core context.
  Window(const char* title, int width, int height);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }

  // Empty when a display seems present; otherwise why not (checked before initialising GLFW).
  static std::string displayProblem();

  bool shouldClose() const;
  void requestClose();
  void cancelClose();  // the close button was pressed, but the application asks first
  void setTitle(const std::string& title);
  void setSize(int width, int height);
  // F11: the primary monitor's whole screen, or back to the window it was.
  void toggleFullscreen();
  bool fullscreen() const;

  // Framebuffer pixels (the GL viewport) and the monitor's content scale (fonts, widget sizes).
  void framebufferSize(int& width, int& height) const;
  float contentScale() const;
  float framebufferScale() const;  // framebuffer pixels per window coordinate

  // Sleeps until an event arrives or `timeoutSeconds` pass; 0 only polls.
  void waitEvents(double timeoutSeconds);
  void swapBuffers();

  // What arrived since the last call.
  std::vector<InputEvent> takeInput();
  std::vector<std::string> takeDroppedPaths();
  // True when anything at all happened (input, resize, expose, focus, scale change) since the last call.
  bool takeActivity();
  bool takeContentScaleChange();

 private:
  static Window& from(GLFWwindow* window);
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);
  static void onCursorMove(GLFWwindow* window, double x, double y);
  static void onScroll(GLFWwindow* window, double dx, double dy);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onDrop(GLFWwindow* window, int count, const char** paths);
  static void onActivity(GLFWwindow* window);
  static void onContentScale(GLFWwindow* window, float, float);

  GLFWwindow* window_ = nullptr;
  int windowedX_ = 0, windowedY_ = 0, windowedWidth_ = 0, windowedHeight_ = 0;  // before F11
  std::vector<InputEvent> input_;
  std::vector<std::string> dropped_;
  bool activity_ = true;
  bool contentScaleChanged_ = false;
};

}  // namespace rayview
