#include "window.h"

#include <cstdlib>
#include <utility>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rayview {
namespace {

// GLFW reports errors through a callback on the UI thread; the latest explains a failed init or window.
std::string lastGlfwError;

void recordGlfwError(int, const char* description) { lastGlfwError = description ? description : "unknown error"; }

bool hasEnvironment(const char* name) {
  const char* value = std::getenv(name);
  return value && *value;
}

}  // namespace

std::string Window::displayProblem() {
  if (!hasEnvironment("DISPLAY") && !hasEnvironment("WAYLAND_DISPLAY"))
    return "neither DISPLAY nor WAYLAND_DISPLAY is set";
  return {};
}

Window::Window(const char* title, int width, int height) {
  glfwSetErrorCallback(recordGlfwError);
  if (!glfwInit()) throw DisplayUnavailable("cannot open the display (" + lastGlfwError + ")");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // a high-DPI monitor gets a proportionally bigger window
  window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
  if (!window_) {
    const std::string reason = lastGlfwError;
    glfwTerminate();
    throw DisplayUnavailable("cannot create an OpenGL 3.3 core window (" + reason + ")");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);  // vsync: never draw faster than the screen shows
  glfwSetWindowUserPointer(window_, this);

  // Installed before ImGui's backend, which chains to the previous mouse, scroll, key, char, focus and
  // cursor-enter callbacks after handling them itself.
  glfwSetMouseButtonCallback(window_, onMouseButton);
  glfwSetCursorPosCallback(window_, onCursorMove);
  glfwSetScrollCallback(window_, onScroll);
  glfwSetKeyCallback(window_, onKey);
  glfwSetDropCallback(window_, onDrop);
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int) { onActivity(w); });
  glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int) { onActivity(w); });
  glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int) { onActivity(w); });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { onActivity(w); });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { onActivity(w); });
  glfwSetWindowContentScaleCallback(window_, onContentScale);
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

Window& Window::from(GLFWwindow* window) { return *static_cast<Window*>(glfwGetWindowUserPointer(window)); }

void Window::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  Window& self = from(window);
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  InputEvent e;
  e.kind = InputEvent::Kind::MouseButton;
  e.button = button;
  e.pressed = action == GLFW_PRESS;
  e.mods = mods;
  e.x = x;
  e.y = y;
  self.input_.push_back(e);
  self.activity_ = true;
}

void Window::onCursorMove(GLFWwindow* window, double x, double y) {
  Window& self = from(window);
  InputEvent e;
  e.kind = InputEvent::Kind::CursorMove;
  e.x = x;
  e.y = y;
  self.input_.push_back(e);
  self.activity_ = true;
}

void Window::onScroll(GLFWwindow* window, double dx, double dy) {
  Window& self = from(window);
  InputEvent e;
  e.kind = InputEvent::Kind::Scroll;
  e.x = dx;
  e.y = dy;
  // GLFW gives the wheel no modifiers: Ctrl+wheel zooms the image, so read Ctrl here.
  if (glfwGetKey(window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(window, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS)
    e.mods |= GLFW_MOD_CONTROL;
  self.input_.push_back(e);
  self.activity_ = true;
}

void Window::onKey(GLFWwindow* window, int key, int, int action, int mods) {
  Window& self = from(window);
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  e.key = key;
  e.pressed = action != GLFW_RELEASE;
  e.repeat = action == GLFW_REPEAT;
  e.mods = mods;
  self.input_.push_back(e);
  self.activity_ = true;
}

void Window::onDrop(GLFWwindow* window, int count, const char** paths) {
  Window& self = from(window);
  for (int i = 0; i < count; ++i) self.dropped_.emplace_back(paths[i]);
  self.activity_ = true;
}

void Window::onActivity(GLFWwindow* window) { from(window).activity_ = true; }

void Window::onContentScale(GLFWwindow* window, float, float) {
  Window& self = from(window);
  self.contentScaleChanged_ = true;
  self.activity_ = true;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::cancelClose() { glfwSetWindowShouldClose(window_, GLFW_FALSE); }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
void Window::setSize(int width, int height) { glfwSetWindowSize(window_, width, height); }

bool Window::fullscreen() const { return glfwGetWindowMonitor(window_) != nullptr; }

void Window::toggleFullscreen() {
  if (fullscreen()) {
    glfwSetWindowMonitor(window_, nullptr, windowedX_, windowedY_, windowedWidth_, windowedHeight_, GLFW_DONT_CARE);
    return;
  }
  GLFWmonitor* monitor = glfwGetPrimaryMonitor();
  const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
  if (!mode) return;
  glfwGetWindowPos(window_, &windowedX_, &windowedY_);
  glfwGetWindowSize(window_, &windowedWidth_, &windowedHeight_);
  glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
}

void Window::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

float Window::contentScale() const {
  float x = 1.0f, y = 1.0f;
  glfwGetWindowContentScale(window_, &x, &y);
  return x > 0.0f ? x : 1.0f;
}

float Window::framebufferScale() const {
  int framebufferWidth = 0, framebufferHeight = 0, width = 0, height = 0;
  glfwGetFramebufferSize(window_, &framebufferWidth, &framebufferHeight);
  glfwGetWindowSize(window_, &width, &height);
  return width > 0 && framebufferWidth > 0 ? static_cast<float>(framebufferWidth) / width : 1.0f;
}

void Window::waitEvents(double timeoutSeconds) {
  if (timeoutSeconds > 0.0)
    glfwWaitEventsTimeout(timeoutSeconds);
  else
    glfwPollEvents();
}

void Window::swapBuffers() { glfwSwapBuffers(window_); }

std::vector<InputEvent> Window::takeInput() { return std::exchange(input_, {}); }
std::vector<std::string> Window::takeDroppedPaths() { return std::exchange(dropped_, {}); }
bool Window::takeActivity() { return std::exchange(activity_, false); }
bool Window::takeContentScaleChange() { return std::exchange(contentScaleChanged_, false); }

}  // namespace rayview
