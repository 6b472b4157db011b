// The scene's local lights as the lit pass shades them (technique.h, LocalLight) and the cbuffer
// that carries them (shaders-hlsl/common/local-lights.hlsli).
#include <cmath>
#include <stdexcept>

#include "local-lights.h"

namespace sp::tech {

std::vector<LocalLight> LocalLightsOf(const scene::Scene& scene) {
  std::vector<LocalLight> out;
  for (const scene::PointLight& p : scene.pointLights) {
    LocalLight l;
    l.type = LocalLight::Point;
    l.position = p.position;
    l.color = p.color;
    l.range = p.range;
    out.push_back(l);
  }
  for (const scene::SpotLight& s : scene.spotLights) {
    LocalLight l;
    l.type = LocalLight::Spot;
    l.position = s.position;
    float len = glm::length(s.direction);
    l.direction = len > 0 ? s.direction / len : glm::vec3(0, -1, 0);
    l.color = s.color;
    l.range = s.range;
    l.cosInner = std::cos(s.innerConeAngle);
    l.cosOuter = std::cos(s.outerConeAngle);
    out.push_back(l);
  }
  return out;
}

void CheckLocalLights(const scene::Scene& scene) {
  std::vector<LocalLight> lights = LocalLightsOf(scene);
  if (lights.size() > kMaxLocalLights)
    throw std::invalid_argument("scene '" + scene.name + "' has " + std::to_string(lights.size()) + " local lights; the lit pass shades at most " +
                                std::to_string(kMaxLocalLights));
  for (size_t i = 0; i < lights.size(); ++i) {
    const LocalLight& l = lights[i];
    bool ok = std::isfinite(l.range) && l.range > 0 && std::isfinite(l.position.x + l.position.y + l.position.z) &&
              std::isfinite(l.color.x + l.color.y + l.color.z) && l.color.x >= 0 && l.color.y >= 0 && l.color.z >= 0;
    if (l.type == LocalLight::Spot) ok = ok && l.cosOuter < l.cosInner && l.cosOuter >= -1e-6f && std::isfinite(l.direction.x);
    if (!ok)
      throw std::invalid_argument("scene '" + scene.name + "': local light " + std::to_string(i) + " (" + (l.type == LocalLight::Spot ? "spot" : "point") +
                                  ") needs a finite position, a colour >= 0, range > 0 and, for spots, 0 <= inner < outer <= pi/2");
  }
}

const LocalLight& ShadowedPointLight(const std::string& technique, uint32_t light, float nearZ, const FrameInputs& frame) {
  size_t points = frame.scene->pointLights.size();
  if (light >= points || light >= frame.localLights.size() || frame.localLights[light].type != LocalLight::Point)
    throw std::invalid_argument(technique + ": light=" + std::to_string(light) + " but scene '" + frame.scene->name + "' has " + std::to_string(points) +
                                " point light(s)");
  const LocalLight& l = frame.localLights[light];
  if (!(nearZ < l.range))
    throw std::invalid_argument(technique + ": near=" + std::to_string(nearZ) + " is not below the range of point light " + std::to_string(light) + " (" +
                                std::to_string(l.range) + ")");
  return l;
}

LocalLightConstants PackLocalLights(const std::vector<LocalLight>& lights) {
  LocalLightConstants c{};
  c.count = uint32_t(std::min<size_t>(lights.size(), kMaxLocalLights));
  for (uint32_t i = 0; i < c.count; ++i) {
    const LocalLight& l = lights[i];
    LocalLightConstants::Light& g = c.lights[i];
    g.position = l.position;
    g.range = l.range;
    g.color = l.color;
    g.type = l.type == LocalLight::Spot ? 1.0f : 0.0f;
    g.direction = l.direction;
    g.cosInner = l.cosInner;
    g.cosOuter = l.cosOuter;
  }
  return c;
}

}  // namespace sp::tech
