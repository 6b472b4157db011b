// ID3D11DeviceContext mirror (the immediate context).
//
// The context keeps D3D11's binding model: per-stage slots for constant buffers, shader resources,
// samplers; output-merger targets and UAVs; input-assembler buffers; fixed-function state objects.
// Like D3D11 it hides barriers, layout transitions, descriptors, pipeline objects and upload rings,
// and it unbinds a resource from input slots when it is bound for output (and refuses an input
// binding of a resource currently bound for output), reporting a warning as the debug layer does.
//
// Bound objects are kept alive by the context (as D3D11 holds references); the *Get* calls give
// them back as D3D11 does (COM-style pointers come AddRef'd).
#pragma once
#include <array>
#include <initializer_list>
#include <vector>
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

namespace detail {
struct PipelineState;
struct DrawArgs;
class ContextBackend;
class ContextHazards;
class DrawValidator;
class NullBindings;
}  // namespace detail


// Shader stages take a `ClassInstance* const*` and a count as in D3D11; dynamic linkage is not
// supported, so they must be null and 0 (anything else throws SP_NOT_SUPPORTED).
class DeviceContext {
 public:
  ~DeviceContext();
  DeviceContext(const DeviceContext&) = delete;
  DeviceContext& operator=(const DeviceContext&) = delete;

  // --- Input assembler
  void IASetInputLayout(InputLayout* layout);
  void IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY topology);
  void IASetVertexBuffers(uint32_t startSlot, uint32_t numBuffers, Buffer* const* buffers, const uint32_t* strides,
                          const uint32_t* offsets);
  void IASetIndexBuffer(Buffer* buffer, FORMAT format, uint32_t offset);

  // --- Shader stages (VS, PS, GS, CS)
  void VSSetShader(VertexShader* shader, ClassInstance* const* classInstances = nullptr, uint32_t numClassInstances = 0);
  void PSSetShader(PixelShader* shader, ClassInstance* const* classInstances = nullptr, uint32_t numClassInstances = 0);
  void GSSetShader(GeometryShader* shader, ClassInstance* const* classInstances = nullptr, uint32_t numClassInstances = 0);
  void CSSetShader(ComputeShader* shader, ClassInstance* const* classInstances = nullptr, uint32_t numClassInstances = 0);

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

  // --- Reading the state back, as D3D11's *Get* calls: slots with nothing bound give null.
  void IAGetInputLayout(OutPtr<InputLayout> layout) const;
  void IAGetPrimitiveTopology(PRIMITIVE_TOPOLOGY* topology) const;
  void IAGetVertexBuffers(uint32_t startSlot, uint32_t numBuffers, OutPtr<Buffer> buffers, uint32_t* strides, uint32_t* offsets) const;
  void IAGetIndexBuffer(OutPtr<Buffer> buffer, FORMAT* format, uint32_t* offset) const;
  void VSGetShader(OutPtr<VertexShader> shader, ClassInstance** classInstances = nullptr, uint32_t* numClassInstances = nullptr) const;
  void PSGetShader(OutPtr<PixelShader> shader, ClassInstance** classInstances = nullptr, uint32_t* numClassInstances = nullptr) const;
  void GSGetShader(OutPtr<GeometryShader> shader, ClassInstance** classInstances = nullptr, uint32_t* numClassInstances = nullptr) const;
  void CSGetShader(OutPtr<ComputeShader> shader, ClassInstance** classInstances = nullptr, uint32_t* numClassInstances = nullptr) const;
  void VSGetConstantBuffers(uint32_t startSlot, uint32_t num, OutPtr<Buffer> buffers) const { GetConstantBuffers(ShaderStage::Vertex, startSlot, num, buffers, "VSGetConstantBuffers"); }
  void PSGetConstantBuffers(uint32_t startSlot, uint32_t num, OutPtr<Buffer> buffers) const { GetConstantBuffers(ShaderStage::Pixel, startSlot, num, buffers, "PSGetConstantBuffers"); }
  void GSGetConstantBuffers(uint32_t startSlot, uint32_t num, OutPtr<Buffer> buffers) const { GetConstantBuffers(ShaderStage::Geometry, startSlot, num, buffers, "GSGetConstantBuffers"); }
  void CSGetConstantBuffers(uint32_t startSlot, uint32_t num, OutPtr<Buffer> buffers) const { GetConstantBuffers(ShaderStage::Compute, startSlot, num, buffers, "CSGetConstantBuffers"); }
  void VSGetShaderResources(uint32_t startSlot, uint32_t num, OutPtr<ShaderResourceView> views) const { GetShaderResources(ShaderStage::Vertex, startSlot, num, views, "VSGetShaderResources"); }
  void PSGetShaderResources(uint32_t startSlot, uint32_t num, OutPtr<ShaderResourceView> views) const { GetShaderResources(ShaderStage::Pixel, startSlot, num, views, "PSGetShaderResources"); }
  void GSGetShaderResources(uint32_t startSlot, uint32_t num, OutPtr<ShaderResourceView> views) const { GetShaderResources(ShaderStage::Geometry, startSlot, num, views, "GSGetShaderResources"); }
  void CSGetShaderResources(uint32_t startSlot, uint32_t num, OutPtr<ShaderResourceView> views) const { GetShaderResources(ShaderStage::Compute, startSlot, num, views, "CSGetShaderResources"); }
  void VSGetSamplers(uint32_t startSlot, uint32_t num, OutPtr<SamplerState> samplers) const { GetSamplers(ShaderStage::Vertex, startSlot, num, samplers, "VSGetSamplers"); }
  void PSGetSamplers(uint32_t startSlot, uint32_t num, OutPtr<SamplerState> samplers) const { GetSamplers(ShaderStage::Pixel, startSlot, num, samplers, "PSGetSamplers"); }
  void GSGetSamplers(uint32_t startSlot, uint32_t num, OutPtr<SamplerState> samplers) const { GetSamplers(ShaderStage::Geometry, startSlot, num, samplers, "GSGetSamplers"); }
  void CSGetSamplers(uint32_t startSlot, uint32_t num, OutPtr<SamplerState> samplers) const { GetSamplers(ShaderStage::Compute, startSlot, num, samplers, "CSGetSamplers"); }
  void CSGetUnorderedAccessViews(uint32_t startSlot, uint32_t num, OutPtr<UnorderedAccessView> views) const;
  void RSGetState(OutPtr<RasterizerState> state) const;
  // viewports/rects null: *num receives how many are set; otherwise *num entries are written
  // (those beyond the set ones zeroed).
  void RSGetViewports(uint32_t* num, VIEWPORT* viewports) const;
  void RSGetScissorRects(uint32_t* num, RECT* rects) const;
  void OMGetRenderTargets(uint32_t numViews, OutPtr<RenderTargetView> rtvs, OutPtr<DepthStencilView> dsv) const;
  void OMGetRenderTargetsAndUnorderedAccessViews(uint32_t numRTVs, OutPtr<RenderTargetView> rtvs, OutPtr<DepthStencilView> dsv,
                                                 uint32_t uavStartSlot, uint32_t numUAVs, OutPtr<UnorderedAccessView> uavs) const;
  void OMGetDepthStencilState(OutPtr<DepthStencilState> state, uint32_t* stencilRef) const;
  void OMGetBlendState(OutPtr<BlendState> state, float blendFactor[4], uint32_t* sampleMask) const;

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
  // true (S_OK) when mapped; false (DXGI_ERROR_WAS_STILL_DRAWING) only when MAP_FLAG_DO_NOT_WAIT
  // is set and the GPU still uses the resource. Misuse throws sp::Error as everywhere else.
  CallStatus Map(Resource* resource, uint32_t subresource, MAP mapType, uint32_t mapFlags, MAPPED_SUBRESOURCE* mapped);
  void Unmap(Resource* resource, uint32_t subresource);
  void GenerateMips(ShaderResourceView* srv);
  void ResolveSubresource(Resource* dst, uint32_t dstSubresource, Resource* src, uint32_t srcSubresource, FORMAT format);

  // --- Queries
  void Begin(Query* query);
  void End(Query* query);
  // true (S_OK) when the data is available, false (S_FALSE) while it is not.
  CallStatus GetData(Query* query, void* data, uint32_t dataSize, uint32_t getDataFlags);

  void ClearState();
  void Flush();
  // Not in D3D11: wait for the GPU to finish everything submitted so far.
  void WaitIdle();

  Device* GetDevice() const { return device_; }

  // COM-style references for ported code (`pd3dDevice->GetImmediateContext(&ctx); ...
  // SAFE_RELEASE(ctx)`). The immediate context lives exactly as long as its device; these count
  // the references handed out so that an extra Release is reported, and nothing more.
  uint32_t AddRef() { return ++comRefs_; }
  uint32_t Release();

 private:
  friend class Device;
  friend Ref<Device> CreateDevice(const DeviceDesc& desc);
  friend class detail::ContextHazards;
  friend class detail::DrawValidator;
  friend class detail::NullBindings;
  DeviceContext(Device* device, std::unique_ptr<detail::ContextBackend> backend);
  void SetConstantBuffers(ShaderStage stage, uint32_t start, uint32_t num, Buffer* const* buffers, const char* call);
  void SetShaderResources(ShaderStage stage, uint32_t start, uint32_t num, ShaderResourceView* const* views, const char* call);
  void SetSamplers(ShaderStage stage, uint32_t start, uint32_t num, SamplerState* const* samplers, const char* call);
  void SetShader(ShaderStage stage, Shader* shader, ClassInstance* const* instances, uint32_t numInstances, const char* call);
  void GetConstantBuffers(ShaderStage stage, uint32_t start, uint32_t num, OutPtr<Buffer> out, const char* call) const;
  void GetShaderResources(ShaderStage stage, uint32_t start, uint32_t num, OutPtr<ShaderResourceView> out, const char* call) const;
  void GetSamplers(ShaderStage stage, uint32_t start, uint32_t num, OutPtr<SamplerState> out, const char* call) const;
  void DoDraw(const detail::DrawArgs& args, const char* call);
  void DoDispatch(uint32_t x, uint32_t y, uint32_t z, Buffer* argsBuffer, uint32_t argsOffset, const char* call);

  Device* device_;
  std::unique_ptr<detail::ContextBackend> backend_;
  std::unique_ptr<detail::PipelineState> state_;
  uint32_t dirty_;
  uint8_t validDraw_ = 0;         // the last draw's validation holds while no draw input is dirty: 1 not indexed, 2 indexed
  bool validDispatch_ = false;    // the same for dispatches and the compute inputs
  std::vector<std::pair<Resource*, uint32_t>> mapped_;  // currently mapped subresources
  std::vector<Query*> activeQueries_;                   // between Begin and End
  uint32_t comRefs_ = 0;
};

}  // namespace sp
