// A scene's geometry on the GPU: every mesh in one vertex and one index buffer, and the list of
// instance draws. Used by the lit pass and by every technique's shadow passes.
#pragma once
#include <sp/rhi/rhi.h>

#include <sp/scene/scene.h>

namespace sp::scene {

struct DrawItem {
  uint32_t instance = 0;
  uint32_t indexCount = 0;
  uint32_t firstIndex = 0;
  int32_t baseVertex = 0;
};

class GpuScene {
 public:
  GpuScene(Device& device, const Scene& scene);

  const Scene& scene() const { return scene_; }
  const std::vector<DrawItem>& draws() const { return draws_; }
  // Binds the vertex and index buffers and the triangle-list topology.
  void BindGeometry(DeviceContext& ctx) const;
  // POSITION float3 at 0, NORMAL float3 at 12, stride 24: matches scene::Vertex.
  static const INPUT_ELEMENT_DESC* InputElements(uint32_t* count);

 private:
  const Scene& scene_;
  Ref<Buffer> vertices_, indices_;
  std::vector<DrawItem> draws_;
};

}  // namespace sp::scene
