#include "fly-camera.h"

#include <algorithm>
#include <cmath>

namespace viewer {

constexpr float kRadiansPerPixel = 0.005f;
constexpr float kMaxPitch = 1.5f;  // short of straight up or down, where yaw is undefined

FlyCamera::FlyCamera(const sp::scene::Camera& start) : camera_(start) {
  glm::vec3 f = start.forward();
  yaw_ = std::atan2(f.x, -f.z);
  pitch_ = std::asin(std::clamp(f.y, -1.0f, 1.0f));
  distance_ = std::max(glm::length(start.target - start.position), 1e-3f);
}

void FlyCamera::Update() {
  glm::vec3 f{std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
  camera_.target = camera_.position + f * distance_;
}

void FlyCamera::Look(double dx, double dy) {
  yaw_ += float(dx) * kRadiansPerPixel;
  pitch_ = std::clamp(pitch_ - float(dy) * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
  Update();
}

void FlyCamera::Move(float right, float up, float forward) {
  glm::vec3 f = camera_.forward();
  glm::vec3 r = glm::normalize(glm::cross(f, camera_.up));
  glm::vec3 d = r * right + camera_.up * up + f * forward;
  camera_.position += d;
  camera_.target += d;
}

void DragLight(sp::scene::DirectionalLight& light, double dx, double dy) {
  glm::vec3 d = glm::normalize(light.direction);
  float azimuth = std::atan2(d.x, d.z) + float(dx) * kRadiansPerPixel;
  // Elevation of the direction the light travels: negative, i.e. downwards.
  float elevation = std::clamp(std::asin(std::clamp(d.y, -1.0f, 1.0f)) + float(dy) * kRadiansPerPixel, -1.55f, -0.05f);
  light.direction = {std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation)};
}

}  // namespace viewer
