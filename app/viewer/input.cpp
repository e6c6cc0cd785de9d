// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/input.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace lic3d::viewer {
namespace {

Input& inputOf(GLFWwindow* window) {
  return *static_cast<Input*>(glfwGetWindowUserPointer(window));
}

void onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  Input& in = inputOf(window);
  if (ImGui::GetIO().WantCaptureMouse && action == GLFW_PRESS) return;
  const bool pressed = action == GLFW_PRESS;
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    in.orbiting = pressed && !(mods & GLFW_MOD_SHIFT);
    in.panning = pressed && (mods & GLFW_MOD_SHIFT);
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    in.panning = pressed;
  }
  glfwGetCursorPos(window, &in.lastX, &in.lastY);
}

void onCursor(GLFWwindow* window, double x, double y) {
  Input& in = inputOf(window);
  if (in.orbiting || in.panning) {
    in.dx += x - in.lastX;
    in.dy += y - in.lastY;
  }
  in.lastX = x;
  in.lastY = y;
}

void onScroll(GLFWwindow* window, double, double y) {
  if (!ImGui::GetIO().WantCaptureMouse) inputOf(window).scroll += y;
}

void onKey(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  Input& in = inputOf(window);
  switch (key) {
    case GLFW_KEY_R: in.resetView = true; break;
    case GLFW_KEY_SPACE: in.togglePlay = true; break;
    case GLFW_KEY_F12: in.screenshot = true; break;
    case GLFW_KEY_H:
    case GLFW_KEY_TAB: in.toggleUi = true; break;
    case GLFW_KEY_F1: in.toggleHelp = true; break;
    case GLFW_KEY_ESCAPE: in.quit = true; break;
    default: break;
  }
}

void onFramebufferSize(GLFWwindow* window, int, int) { inputOf(window).resized = true; }

}  // namespace

Input Input::take() {
  const Input taken = *this;
  dx = dy = scroll = 0.0;
  resetView = togglePlay = screenshot = toggleUi = toggleHelp = false;
  return taken;
}

void listenForInput(GLFWwindow* window, Input& input) {
  glfwSetWindowUserPointer(window, &input);
  glfwSetMouseButtonCallback(window, onMouseButton);
  glfwSetCursorPosCallback(window, onCursor);
  glfwSetScrollCallback(window, onScroll);
  glfwSetKeyCallback(window, onKey);
  glfwSetFramebufferSizeCallback(window, onFramebufferSize);
}

}  // namespace lic3d::viewer
