// The viewer's camera and light controls: a fly camera (yaw/pitch from a mouse drag, WASD in the
// view plane, Q/E down and up) and a sun direction dragged on a sphere.
#pragma once
#include <sp/scene/scene.h>

namespace viewer {

class FlyCamera {
 public:
  explicit FlyCamera(const sp::scene::Camera& start);
  // Mouse drag in pixels; positive dx turns right, positive dy looks down.
  void Look(double dx, double dy);
  // Movement in the camera's frame: x right, y up, z forward, in scene units.
  void Move(float right, float up, float forward);
  const sp::scene::Camera& camera() const { return camera_; }

 private:
  void Update();
  sp::scene::Camera camera_;
  float yaw_ = 0, pitch_ = 0, distance_ = 1;
};

// Turns the light's direction by a mouse drag: azimuth around the world up axis, elevation kept
// below the horizon so the light always comes from above.
void DragLight(sp::scene::DirectionalLight& light, double dx, double dy);

}  // namespace viewer
