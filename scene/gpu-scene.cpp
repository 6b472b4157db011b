#include <sp/scene/gpu-scene.h>

#include <stdexcept>

namespace sp::scene {

GpuScene::GpuScene(Device& device, const Scene& scene) : scene_(scene) {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<DrawItem> meshItems;
  for (const Mesh& m : scene.meshes) {
    DrawItem d;
    d.firstIndex = uint32_t(indices.size());
    d.indexCount = uint32_t(m.indices.size());
    d.baseVertex = int32_t(vertices.size());
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
    meshItems.push_back(d);
  }
  if (vertices.empty() || indices.empty()) throw std::invalid_argument("scene '" + scene.name + "' has no geometry");
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    DrawItem d = meshItems.at(scene.instances[i].mesh);
    d.instance = i;
    if (d.indexCount) draws_.push_back(d);
  }
  BUFFER_DESC vd;
  vd.ByteWidth = uint32_t(vertices.size() * sizeof(Vertex));
  vd.Usage = USAGE_IMMUTABLE;
  vd.BindFlags = BIND_VERTEX_BUFFER;
  SUBRESOURCE_DATA vinit{vertices.data(), 0, 0};
  vertices_ = device.CreateBuffer(vd, &vinit);
  vertices_->SetDebugName(scene.name + " vertices");
  BUFFER_DESC id;
  id.ByteWidth = uint32_t(indices.size() * sizeof(uint32_t));
  id.Usage = USAGE_IMMUTABLE;
  id.BindFlags = BIND_INDEX_BUFFER;
  SUBRESOURCE_DATA iinit{indices.data(), 0, 0};
  indices_ = device.CreateBuffer(id, &iinit);
  indices_->SetDebugName(scene.name + " indices");
}

void GpuScene::BindGeometry(DeviceContext& ctx) const {
  Buffer* vb = vertices_.get();
  uint32_t stride = sizeof(Vertex), offset = 0;
  ctx.IASetVertexBuffers(0, 1, &vb, &stride, &offset);
  ctx.IASetIndexBuffer(indices_.get(), FORMAT_R32_UINT, 0);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
}

const INPUT_ELEMENT_DESC* GpuScene::InputElements(uint32_t* count) {
  static const INPUT_ELEMENT_DESC elements[] = {
      {"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
      {"NORMAL", 0, FORMAT_R32G32B32_FLOAT, 0, 12, INPUT_PER_VERTEX_DATA, 0},
  };
  *count = 2;
  return elements;
}

}  // namespace sp::scene
