#include "imgui_layer.h"

#include <algorithm>

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

namespace rayview {

ImGuiLayer::ImGuiLayer(GLFWwindow* window, float contentScale, float framebufferScale)
    : contentScale_(contentScale), framebufferScale_(framebufferScale) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is fixed: nothing to remember, no imgui.ini left in the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the window's own callbacks
  ImGui_ImplOpenGL3_Init("#version 330 core");
  applyScale();
}

ImGuiLayer::~ImGuiLayer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::setScale(float contentScale, float framebufferScale) {
  if (contentScale == contentScale_ && framebufferScale == framebufferScale_) return;
  contentScale_ = contentScale;
  framebufferScale_ = framebufferScale;
  applyScale();
  ImGui_ImplOpenGL3_DestroyFontsTexture();
  ImGui_ImplOpenGL3_CreateFontsTexture();
}

void ImGuiLayer::applyScale() {
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  ImFontConfig font;
  font.SizePixels = kBaseFontPixels * contentScale_;
  io.Fonts->AddFontDefault(&font);
  io.FontGlobalScale = 1.0f / framebufferScale_;  // the rasterised size is in pixels, the layout in coordinates
  ImGuiStyle& style = ImGui::GetStyle();
  style = ImGuiStyle();
  ImGui::StyleColorsDark(&style);
  style.WindowRounding = 0.0f;
  style.ScaleAllSizes(layoutScale());
}

void ImGuiLayer::beginFrame(const std::vector<int>& quickPresses, const std::vector<int>& touched) {
  ImGuiIO& io = ImGui::GetIO();
  constexpr int keys = static_cast<int>(sizeof io.KeysDown / sizeof io.KeysDown[0]);
  for (const int key : held_)
    if (std::find(touched.begin(), touched.end(), key) == touched.end()) io.KeysDown[key] = false;
  held_.clear();
  for (const int key : quickPresses)
    if (key >= 0 && key < keys) {
      io.KeysDown[key] = true;
      held_.push_back(key);
    }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::render() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace rayview
