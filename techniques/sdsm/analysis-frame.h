// Sample Distribution Shadow Maps: the camera and light side of the analysis, on the CPU.
//
//  - the light frame of the paper: a light view whose x axis is the camera's view direction
//    projected onto the plane perpendicular to the light (so partitions stretch along x as the
//    frustum does), origin at the camera;
//  - AnalysisFrame: what the passes need to turn a pixel of the camera depth buffer into view depth
//    and a light-space position, with CPU versions that repeat the shader's float operations in
//    the same order (tests compare bit for bit);
//  - the light-space boxes the analysis produces, their encoding in the results buffer, and the
//    turn of a box into a shadow projection (with optional dilation), or, when no analysis result
//    is available, the conservative box of a camera frustum slice.
#pragma once
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "sdsm/partitions.h"

namespace sp::tech::sdsm {

// World -> light view (right-handed, looking down -z along `lightDirection`, the way light travels).
// x: the camera forward projected onto the plane perpendicular to the light (when the camera
// looks along the light, the camera's up projected instead); origin: the camera position.
glm::mat4 MakeLightView(const glm::vec3& cameraPosition, const glm::vec3& cameraForward, const glm::vec3& cameraUp,
                        const glm::vec3& lightDirection);

// A float's bits mapped to a uint that orders like the float, negatives included (SdsmOrderedKey).
uint32_t OrderedKey(float f);
float FromOrderedKey(uint32_t key);

struct AnalysisFrame {
  uint32_t width = 0, height = 0;  // of the camera depth buffer
  float depthA = 0, depthB = 1;    // view depth = depthA / (depthB - d)
  float nearZ = 0, farZ = 0;       // the camera's
  glm::vec2 ndcScale{0}, ndcOffset{0}, rayScale{0}, rayOffset{0};
  glm::vec3 lightRayX{0}, lightRayY{0}, lightRayZ{0}, lightOrigin{0};
  glm::mat4 lightView{1.0f};

  // cameraProj: a perspective projection with clip depth in [0, 1] (glm's *_ZO, D3D's); depth 1
  // is the far plane (sky). Throws std::invalid_argument for other projections (orthographic,
  // reversed Z). nearZ/farZ (the range used when no pixel is covered) come from the float matrix;
  // a caller that knows them exactly may overwrite them.
  static AnalysisFrame Make(const glm::mat4& cameraView, const glm::mat4& cameraProj, const glm::mat4& lightView,
                            uint32_t width, uint32_t height);

  // SdsmViewDepth and SdsmLightPosition, operation for operation.
  float ViewDepth(float depth) const;
  glm::vec3 LightPosition(uint32_t x, uint32_t y, float viewDepth) const;
};

struct LightBounds {
  glm::vec3 min{0.0f}, max{0.0f};  // light-view space
  uint32_t samples = 0;            // 0: no receiver in this partition (min/max meaningless)
  bool empty() const { return samples == 0; }
};

// The analysis results buffer (SDSM_W_* in shaders-hlsl/sdsm/analysis.hlsli).
constexpr uint32_t kResultWords = 96, kResultBytes = kResultWords * 4;
constexpr uint32_t kWordMin = 0, kWordMax = 1, kWordSamples = 2, kWordPartitions = 3, kWordSplits = 4, kWordBounds = 20;

struct AnalysisResults {
  float zMin = 0, zMax = 0;      // tight view-depth range; zMin > zMax when nothing is visible
  uint32_t samples = 0;          // non-sky pixels
  uint32_t partitionCount = 0;   // K
  std::vector<float> splits;     // K + 1
  std::vector<LightBounds> bounds;  // K
  bool covered() const { return zMin <= zMax; }
};
AnalysisResults DecodeResults(const uint32_t* words);
std::vector<uint32_t> EncodeResults(const AnalysisResults& results);  // kResultWords words

// Light view -> clip of an orthographic shadow projection covering `bounds` grown by `dilation`
// (world units, on every side; the light view is orthonormal so world and light units agree).
// Depth 0 at the top of the box (towards the light), 1 at its bottom; casters above the top are
// to be rendered with depth clipping off (pancaked onto the near plane).
glm::mat4 PartitionProjection(const LightBounds& bounds, float dilation);

// The light-space box of the camera frustum between view depths zNear and zFar: the
// conservative bounds of a partition when its analysed bounds are not available (no readback).
LightBounds FrustumSliceBounds(const glm::mat4& cameraView, const glm::mat4& cameraProj, const glm::mat4& lightView,
                               float zNear, float zFar);

}  // namespace sp::tech::sdsm
