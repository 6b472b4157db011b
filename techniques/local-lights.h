// The lit pass's local-light cbuffer (shaders-hlsl/common/local-lights.hlsli, b6), private to the
// renderer.
#pragma once
#include <sp/tech/technique.h>

namespace sp::tech {

// cbuffer LocalLights (D3D packing: each light is 64 bytes, the array starts at 16).
struct LocalLightConstants {
  uint32_t count;
  uint32_t pad[3];
  struct Light {
    glm::vec3 position;
    float range;
    glm::vec3 color;
    float type;  // 0 point, 1 spot
    glm::vec3 direction;
    float cosInner;
    float cosOuter;
    float pad[3];
  } lights[kMaxLocalLights];
};
static_assert(sizeof(LocalLightConstants) == 16 + 64 * kMaxLocalLights);

// Throws std::invalid_argument naming the scene and the light for more than kMaxLocalLights
// lights or a light the lit pass cannot shade (range <= 0, negative colour, a bad cone).
void CheckLocalLights(const scene::Scene& scene);
LocalLightConstants PackLocalLights(const std::vector<LocalLight>& lights);

// The point light `light` that a point-light technique (cube, paraboloid) shadows this frame.
// Throws std::invalid_argument naming the technique and the scene when the scene has no such
// point light, or the technique's `near` when it is not below the light's range.
const LocalLight& ShadowedPointLight(const std::string& technique, uint32_t light, float nearZ, const FrameInputs& frame);

}  // namespace sp::tech
