// ID3D11DeviceContext mirror (the immediate context).
//
// The context keeps D3D11's binding model: per-stage slots for constant buffers, shader resources,
// samplers; output-merger targets and UAVs; input-assembler buffers; fixed-function state objects.
// Like D3D11 it hides barriers, layout transitions, descriptors, pipeline objects and upload rings,
// and it unbinds a resource from input slots when it is bound for output (and refuses an input
// binding of a resource currently bound for output), reporting a warning as the debug layer does.
//
// Bound objects are kept alive by the context (as D3D11 holds references).
#pragma once
#include <array>
#include <initializer_list>
#include <sp/rhi/device.h>

namespace sp {

enum PRIMITIVE_TOPOLOGY : uint32_t {
  PRIMITIVE_TOPOLOGY_UNDEFINED = 0,
  PRIMITIVE_TOPOLOGY_POINTLIST = 1,
  PRIMITIVE_TOPOLOGY_LINELIST = 2,
  PRIMITIVE_TOPOLOGY_LINESTRIP = 3,
  PRIMITIVE_TOPOLOGY_TRIANGLELIST = 4,
  PRIMITIVE_TOPOLOGY_TRIANGLESTRIP = 5,
};

struct VIEWPORT {
  float TopLeftX = 0, TopLeftY = 0, Width = 0, Height = 0, MinDepth = 0, MaxDepth = 1;
};

struct RECT {
  int32_t left = 0, top = 0, right = 0, bottom = 0;
};

struct BOX {
  uint32_t left = 0, top = 0, front = 0, right = 0, bottom = 0, back = 0;
};

enum CLEAR_FLAG : uint32_t { CLEAR_DEPTH = 0x1, CLEAR_STENCIL = 0x2 };

enum MAP : uint32_t {
  MAP_READ = 1,
  MAP_WRITE = 2,
  MAP_READ_WRITE = 3,
  MAP_WRITE_DISCARD = 4,
  MAP_WRITE_NO_OVERWRITE = 5,
};
enum MAP_FLAG : uint32_t { MAP_FLAG_DO_NOT_WAIT = 0x100000 };

struct MAPPED_SUBRESOURCE {
  void* pData = nullptr;
  uint32_t RowPitch = 0;
  uint32_t DepthPitch = 0;
};

inline constexpr uint32_t KEEP_RENDER_TARGETS_AND_DEPTH_STENCIL = 0xffffffffu;
inline constexpr uint32_t KEEP_UNORDERED_ACCESS_VIEWS = 0xffffffffu;

// Everything bound to one shader stage.
struct StageBindings {
  Ref<Shader> shader;
  std::array<Ref<Buffer>, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT> constantBuffers;
  std::array<Ref<ShaderResourceView>, COMMONSHADER_INPUT_RESOURCE_SLOT_COUNT> shaderResources;
  std::array<Ref<SamplerState>, COMMONSHADER_SAMPLER_SLOT_COUNT> samplers;
};

// The complete D3D11 pipeline state as the core tracks it. Backends read it at draw/dispatch.
struct PipelineState {
  std::array<StageBindings, SHADER_STAGE_COUNT> stages;
  // Output-merger UAVs (pixel shader, OMSetRenderTargetsAndUnorderedAccessViews) and compute UAVs.
  std::array<Ref<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT> pixelUavs;
  std::array<Ref<UnorderedAccessView>, PS_CS_UAV_REGISTER_COUNT> computeUavs;

  Ref<InputLayout> inputLayout;
  PRIMITIVE_TOPOLOGY topology = PRIMITIVE_TOPOLOGY_UNDEFINED;
  std::array<Ref<Buffer>, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexBuffers;
  std::array<uint32_t, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexStrides{};
  std::array<uint32_t, IA_VERTEX_INPUT_RESOURCE_SLOT_COUNT> vertexOffsets{};
  Ref<Buffer> indexBuffer;
  FORMAT indexFormat = FORMAT_UNKNOWN;
  uint32_t indexOffset = 0;

  Ref<RasterizerState> rasterizerState;  // null = D3D11 defaults
  std::array<VIEWPORT, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> viewports{};
  uint32_t numViewports = 0;
  std::array<RECT, VIEWPORT_AND_SCISSORRECT_OBJECT_COUNT_PER_PIPELINE> scissorRects{};
  uint32_t numScissorRects = 0;

  Ref<DepthStencilState> depthStencilState;  // null = D3D11 defaults
  uint32_t stencilRef = 0;
  Ref<BlendState> blendState;                // null = D3D11 defaults
  std::array<float, 4> blendFactor{1, 1, 1, 1};
  uint32_t sampleMask = 0xffffffffu;

  std::array<Ref<RenderTargetView>, SIMULTANEOUS_RENDER_TARGET_COUNT> renderTargets;
  uint32_t numRenderTargets = 0;  // as passed to OMSetRenderTargets
  Ref<DepthStencilView> depthStencil;

  const RASTERIZER_DESC& rasterizer() const;
  const DEPTH_STENCIL_DESC& depthStencilDesc() const;
  const BLEND_DESC& blend() const;
  StageBindings& stage(ShaderStage s) { return stages[size_t(s)]; }
  const StageBindings& stage(ShaderStage s) const { return stages[size_t(s)]; }
};

// Dirty bits the core sets between draws so backends rebuild only what changed.
enum DirtyFlag : uint32_t {
  DIRTY_SHADERS = 1u << 0,
  DIRTY_INPUT_LAYOUT = 1u << 1,  // layout or topology
  DIRTY_VERTEX_BUFFERS = 1u << 2,
  DIRTY_INDEX_BUFFER = 1u << 3,
  DIRTY_RASTERIZER = 1u << 4,
  DIRTY_VIEWPORTS = 1u << 5,  // viewports or scissors
  DIRTY_DEPTH_STENCIL = 1u << 6,
  DIRTY_BLEND = 1u << 7,
  DIRTY_RENDER_TARGETS = 1u << 8,
  DIRTY_BINDINGS_VS = 1u << 9,  // cbuffers, SRVs, samplers of a stage: 1 << (9 + stage)
  DIRTY_BINDINGS_PS = 1u << 10,
  DIRTY_BINDINGS_GS = 1u << 11,
  DIRTY_BINDINGS_CS = 1u << 12,
  DIRTY_PIXEL_UAVS = 1u << 13,
  DIRTY_COMPUTE_UAVS = 1u << 14,
  DIRTY_ALL = 0xffffffffu,
};

namespace detail {

struct DrawArgs {
  enum Kind : uint8_t { Draw, DrawIndexed, DrawInstancedIndirect, DrawIndexedInstancedIndirect } kind = Draw;
  uint32_t count = 0;          // vertices or indices per instance
  uint32_t instanceCount = 1;
  uint32_t start = 0;          // StartVertexLocation or StartIndexLocation
  int32_t baseVertex = 0;      // BaseVertexLocation (indexed)
  uint32_t startInstance = 0;
  Buffer* argsBuffer = nullptr;  // indirect
  uint32_t argsOffset = 0;
};

// What a backend implements for the immediate context. The core has validated every argument
// and resolved D3D11 defaults before calling.
class ContextBackend {
 public:
  virtual ~ContextBackend() = default;
  virtual void Draw(const PipelineState& state, uint32_t dirty, const DrawArgs& args) = 0;
  virtual void Dispatch(const PipelineState& state, uint32_t dirty, uint32_t x, uint32_t y, uint32_t z,
                        Buffer* argsBuffer, uint32_t argsOffset) = 0;
  virtual void ClearRenderTargetView(RenderTargetView* rtv, const float rgba[4]) = 0;
  virtual void ClearDepthStencilView(DepthStencilView* dsv, uint32_t clearFlags, float depth, uint8_t stencil) = 0;
  virtual void ClearUnorderedAccessViewUint(UnorderedAccessView* uav, const uint32_t values[4]) = 0;
  virtual void ClearUnorderedAccessViewFloat(UnorderedAccessView* uav, const float values[4]) = 0;
  virtual void CopyResource(Resource* dst, Resource* src) = 0;
  // srcBox is never null here (the core fills the whole subresource when D3D11's is null).
  virtual void CopySubresourceRegion(Resource* dst, uint32_t dstSubresource, uint32_t dstX, uint32_t dstY, uint32_t dstZ,
                                     Resource* src, uint32_t srcSubresource, const BOX& srcBox) = 0;
  virtual void UpdateSubresource(Resource* dst, uint32_t dstSubresource, const BOX& box, const void* data,
                                 uint32_t rowPitch, uint32_t depthPitch) = 0;
  // Returns false only for MAP_FLAG_DO_NOT_WAIT when the GPU still uses the resource.
  virtual bool Map(Resource* resource, uint32_t subresource, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) = 0;
  virtual void Unmap(Resource* resource, uint32_t subresource) = 0;
  virtual void GenerateMips(ShaderResourceView* srv) = 0;
  virtual void ResolveSubresource(Resource* dst, uint32_t dstSubresource, Resource* src, uint32_t srcSubresource, FORMAT format) = 0;
  virtual void CopyStructureCount(Buffer* dst, uint32_t dstOffset, UnorderedAccessView* src) = 0;
  // Sets the hidden counter of an append/consume UAV (the pUAVInitialCounts of D3D11).
  virtual void SetUavCounter(UnorderedAccessView* uav, uint32_t value) = 0;
  virtual void Begin(Query* query) = 0;
  virtual void End(Query* query) = 0;
  virtual bool GetData(Query* query, void* data, uint32_t size, uint32_t flags) = 0;
  virtual void Flush() = 0;
  // Blocks until the GPU finished all submitted work (not in D3D11; for tests and benchmarks).
  virtual void WaitIdle() = 0;
};

}  // namespace detail

class DeviceContext {
 public:
  DeviceContext(Device* device, std::unique_ptr<detail::ContextBackend> backend);
  ~DeviceContext();

  // --- Input assembler
  void IASetInputLayout(InputLayout* layout);
  void IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY topology);
  void IASetVertexBuffers(uint32_t startSlot, uint32_t numBuffers, Buffer* const* buffers, const uint32_t* strides,
                          const uint32_t* offsets);
  void IASetIndexBuffer(Buffer* buffer, FORMAT format, uint32_t offset);

  // --- Shader stages (VS, PS, GS, CS)
  void VSSetShader(VertexShader* shader);
  void PSSetShader(PixelShader* shader);
  void GSSetShader(GeometryShader* shader);
  void CSSetShader(ComputeShader* shader);

  void VSSetConstantBuffers(uint32_t startSlot, uint32_t num, Buffer* const* buffers) { SetConstantBuffers(ShaderStage::Vertex, startSlot, num, buffers, "VSSetConstantBuffers"); }
  void PSSetConstantBuffers(uint32_t startSlot, uint32_t num, Buffer* const* buffers) { SetConstantBuffers(ShaderStage::Pixel, startSlot, num, buffers, "PSSetConstantBuffers"); }
  void GSSetConstantBuffers(uint32_t startSlot, uint32_t num, Buffer* const* buffers) { SetConstantBuffers(ShaderStage::Geometry, startSlot, num, buffers, "GSSetConstantBuffers"); }
  void CSSetConstantBuffers(uint32_t startSlot, uint32_t num, Buffer* const* buffers) { SetConstantBuffers(ShaderStage::Compute, startSlot, num, buffers, "CSSetConstantBuffers"); }
  void VSSetShaderResources(uint32_t startSlot, uint32_t num, ShaderResourceView* const* views) { SetShaderResources(ShaderStage::Vertex, startSlot, num, views, "VSSetShaderResources"); }
  void PSSetShaderResources(uint32_t startSlot, uint32_t num, ShaderResourceView* const* views) { SetShaderResources(ShaderStage::Pixel, startSlot, num, views, "PSSetShaderResources"); }
  void GSSetShaderResources(uint32_t startSlot, uint32_t num, ShaderResourceView* const* views) { SetShaderResources(ShaderStage::Geometry, startSlot, num, views, "GSSetShaderResources"); }
  void CSSetShaderResources(uint32_t startSlot, uint32_t num, ShaderResourceView* const* views) { SetShaderResources(ShaderStage::Compute, startSlot, num, views, "CSSetShaderResources"); }
  void VSSetSamplers(uint32_t startSlot, uint32_t num, SamplerState* const* samplers) { SetSamplers(ShaderStage::Vertex, startSlot, num, samplers, "VSSetSamplers"); }
  void PSSetSamplers(uint32_t startSlot, uint32_t num, SamplerState* const* samplers) { SetSamplers(ShaderStage::Pixel, startSlot, num, samplers, "PSSetSamplers"); }
  void GSSetSamplers(uint32_t startSlot, uint32_t num, SamplerState* const* samplers) { SetSamplers(ShaderStage::Geometry, startSlot, num, samplers, "GSSetSamplers"); }
  void CSSetSamplers(uint32_t startSlot, uint32_t num, SamplerState* const* samplers) { SetSamplers(ShaderStage::Compute, startSlot, num, samplers, "CSSetSamplers"); }
  // pUAVInitialCounts: per view, the append/consume counter to set, or (uint32_t)-1 to keep it.
  void CSSetUnorderedAccessViews(uint32_t startSlot, uint32_t num, UnorderedAccessView* const* views,
                                 const uint32_t* initialCounts = nullptr);

  // Convenience forms: ctx->PSSetShaderResources(0, {srvA.get(), srvB.get()}).
  void VSSetConstantBuffers(uint32_t s, std::initializer_list<Buffer*> l) { VSSetConstantBuffers(s, uint32_t(l.size()), l.begin()); }
  void PSSetConstantBuffers(uint32_t s, std::initializer_list<Buffer*> l) { PSSetConstantBuffers(s, uint32_t(l.size()), l.begin()); }
  void CSSetConstantBuffers(uint32_t s, std::initializer_list<Buffer*> l) { CSSetConstantBuffers(s, uint32_t(l.size()), l.begin()); }
  void VSSetShaderResources(uint32_t s, std::initializer_list<ShaderResourceView*> l) { VSSetShaderResources(s, uint32_t(l.size()), l.begin()); }
  void PSSetShaderResources(uint32_t s, std::initializer_list<ShaderResourceView*> l) { PSSetShaderResources(s, uint32_t(l.size()), l.begin()); }
  void CSSetShaderResources(uint32_t s, std::initializer_list<ShaderResourceView*> l) { CSSetShaderResources(s, uint32_t(l.size()), l.begin()); }
  void VSSetSamplers(uint32_t s, std::initializer_list<SamplerState*> l) { VSSetSamplers(s, uint32_t(l.size()), l.begin()); }
  void PSSetSamplers(uint32_t s, std::initializer_list<SamplerState*> l) { PSSetSamplers(s, uint32_t(l.size()), l.begin()); }
  void CSSetSamplers(uint32_t s, std::initializer_list<SamplerState*> l) { CSSetSamplers(s, uint32_t(l.size()), l.begin()); }
  void CSSetUnorderedAccessViews(uint32_t s, std::initializer_list<UnorderedAccessView*> l) { CSSetUnorderedAccessViews(s, uint32_t(l.size()), l.begin()); }

  // --- Rasterizer
  void RSSetState(RasterizerState* state);
  void RSSetViewports(uint32_t num, const VIEWPORT* viewports);
  void RSSetScissorRects(uint32_t num, const RECT* rects);

  // --- Output merger
  void OMSetRenderTargets(uint32_t numViews, RenderTargetView* const* rtvs, DepthStencilView* dsv);
  void OMSetRenderTargetsAndUnorderedAccessViews(uint32_t numRTVs, RenderTargetView* const* rtvs, DepthStencilView* dsv,
                                                 uint32_t uavStartSlot, uint32_t numUAVs, UnorderedAccessView* const* uavs,
                                                 const uint32_t* uavInitialCounts);
  void OMSetDepthStencilState(DepthStencilState* state, uint32_t stencilRef);
  void OMSetBlendState(BlendState* state, const float blendFactor[4], uint32_t sampleMask);

  // --- Draw and dispatch
  void Draw(uint32_t vertexCount, uint32_t startVertexLocation);
  void DrawIndexed(uint32_t indexCount, uint32_t startIndexLocation, int32_t baseVertexLocation);
  void DrawInstanced(uint32_t vertexCountPerInstance, uint32_t instanceCount, uint32_t startVertexLocation,
                     uint32_t startInstanceLocation);
  void DrawIndexedInstanced(uint32_t indexCountPerInstance, uint32_t instanceCount, uint32_t startIndexLocation,
                            int32_t baseVertexLocation, uint32_t startInstanceLocation);
  void DrawInstancedIndirect(Buffer* bufferForArgs, uint32_t alignedByteOffsetForArgs);
  void DrawIndexedInstancedIndirect(Buffer* bufferForArgs, uint32_t alignedByteOffsetForArgs);
  void Dispatch(uint32_t threadGroupCountX, uint32_t threadGroupCountY, uint32_t threadGroupCountZ);
  void DispatchIndirect(Buffer* bufferForArgs, uint32_t alignedByteOffsetForArgs);

  // --- Clears, copies, updates
  void ClearRenderTargetView(RenderTargetView* rtv, const float colorRGBA[4]);
  void ClearDepthStencilView(DepthStencilView* dsv, uint32_t clearFlags, float depth, uint8_t stencil);
  void ClearUnorderedAccessViewUint(UnorderedAccessView* uav, const uint32_t values[4]);
  void ClearUnorderedAccessViewFloat(UnorderedAccessView* uav, const float values[4]);
  void CopyResource(Resource* dst, Resource* src);
  void CopySubresourceRegion(Resource* dst, uint32_t dstSubresource, uint32_t dstX, uint32_t dstY, uint32_t dstZ,
                             Resource* src, uint32_t srcSubresource, const BOX* srcBox);
  void UpdateSubresource(Resource* dst, uint32_t dstSubresource, const BOX* dstBox, const void* srcData,
                         uint32_t srcRowPitch, uint32_t srcDepthPitch);
  void CopyStructureCount(Buffer* dstBuffer, uint32_t dstAlignedByteOffset, UnorderedAccessView* srcView);
  // Returns false only when MAP_FLAG_DO_NOT_WAIT is set and the GPU still uses the resource
  // (D3D11's DXGI_ERROR_WAS_STILL_DRAWING).
  bool Map(Resource* resource, uint32_t subresource, MAP mapType, uint32_t mapFlags, MAPPED_SUBRESOURCE* mapped);
  void Unmap(Resource* resource, uint32_t subresource);
  void GenerateMips(ShaderResourceView* srv);
  void ResolveSubresource(Resource* dst, uint32_t dstSubresource, Resource* src, uint32_t srcSubresource, FORMAT format);

  // --- Queries
  void Begin(Query* query);
  void End(Query* query);
  // Returns true when the data is available (S_OK) and false while it is not (S_FALSE).
  bool GetData(Query* query, void* data, uint32_t dataSize, uint32_t getDataFlags);

  void ClearState();
  void Flush();
  // Not in D3D11: wait for the GPU to finish everything submitted so far.
  void WaitIdle();

  const PipelineState& State() const { return state_; }
  Device* GetDevice() const { return device_; }

 private:
  void SetConstantBuffers(ShaderStage stage, uint32_t start, uint32_t num, Buffer* const* buffers, const char* call);
  void SetShaderResources(ShaderStage stage, uint32_t start, uint32_t num, ShaderResourceView* const* views, const char* call);
  void SetSamplers(ShaderStage stage, uint32_t start, uint32_t num, SamplerState* const* samplers, const char* call);
  void SetShader(ShaderStage stage, Shader* shader, const char* call);
  void DoDraw(const detail::DrawArgs& args, const char* call);

  friend class ContextHazards;
  friend class DrawValidator;
  Device* device_;
  std::unique_ptr<detail::ContextBackend> backend_;
  PipelineState state_;
  uint32_t dirty_ = DIRTY_ALL;
  std::vector<std::pair<Resource*, uint32_t>> mapped_;  // currently mapped subresources
  std::vector<Query*> activeQueries_;                   // between Begin and End
};

}  // namespace sp
