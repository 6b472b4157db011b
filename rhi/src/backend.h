// What a backend implements and what it may see of the core (private to the library: backends
// and the core include it, applications cannot).
//
// The core's sp::Device owns a detail::DeviceBackend and, through the immediate context, a
// detail::ContextBackend. sp::CreateDevice creates the backend, then the context, then runs the
// depth-bias calibration; ~Device destroys the context, releases the backend data of every object
// still alive and only then the backend. Backends never see an invalid call: the core validates,
// resolves D3D11's defaults and substitutes its null resources for unbound registers first.
#pragma once
#include <memory>
#include <string_view>

#include <sp/rhi/context.h>
#include <sp/rhi/swapchain.h>
#include <vector>

#include "clear-values.h"
#include "pipeline-state.h"
#include "subresource.h"

namespace sp::detail {

// What a backend attaches to a core object (VkImage, GL texture name, ...). The core owns the
// object; the backend owns this.
struct BackendObject {
  virtual ~BackendObject() = default;
};

// The core's private parts of sp::Object, for the core and the backends.
struct ObjectAccess {
  static BackendObject* Get(const Object& o) { return o.backend_.get(); }
  static void Attach(Object& o, std::unique_ptr<BackendObject> b) { o.backend_ = std::move(b); }
  static void Release(Object& o) { o.backend_.reset(); }
};

// A backend's data of an object: BackendAs<GLTexture>(texture), with a raw or shared pointer.
template <class T, class P>
T& BackendAs(const P& object) {
  return static_cast<T&>(*ObjectAccess::Get(*object));
}

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
  // Both D3D11 UAV clears, already packed into the bits the view's memory must hold.
  virtual void ClearUnorderedAccessView(UnorderedAccessView* uav, const UavClearValue& value) = 0;
  virtual void CopyResource(Resource* dst, Resource* src) = 0;
  // srcBox is never null here (the core fills the whole subresource when D3D11's is null).
  // Subresources arrive validated and decomposed (subresource.h); a buffer's is BufferSubresource.
  virtual void CopySubresourceRegion(Resource* dst, const Subresource& dstSub, uint32_t dstX, uint32_t dstY, uint32_t dstZ,
                                     Resource* src, const Subresource& srcSub, const BOX& srcBox) = 0;
  virtual void UpdateSubresource(Resource* dst, const Subresource& dstSub, const BOX& box, const void* data,
                                 uint32_t rowPitch, uint32_t depthPitch) = 0;
  // Returns false only for MAP_FLAG_DO_NOT_WAIT when the GPU still uses the resource.
  virtual bool Map(Resource* resource, const Subresource& sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) = 0;
  virtual void Unmap(Resource* resource, const Subresource& sub) = 0;
  virtual void GenerateMips(ShaderResourceView* srv) = 0;
  virtual void ResolveSubresource(Resource* dst, const Subresource& dstSub, Resource* src, const Subresource& srcSub, FORMAT format) = 0;
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

// What a backend implements for the device. It does not derive from sp::Device: the core owns it
// and calls these hooks with validated, normalised arguments (full view descs, resolved defaults).
class DeviceBackend {
 public:
  explicit DeviceBackend(Device& core);
  virtual ~DeviceBackend() = default;
  DeviceBackend(const DeviceBackend&) = delete;
  DeviceBackend& operator=(const DeviceBackend&) = delete;

  virtual std::unique_ptr<BackendObject> CreateBufferBackend(Buffer& buffer, const SUBRESOURCE_DATA* init) = 0;
  virtual std::unique_ptr<BackendObject> CreateTextureBackend(Texture& texture, const SUBRESOURCE_DATA* init) = 0;
  virtual std::unique_ptr<BackendObject> CreateViewBackend(View& view) = 0;
  virtual std::unique_ptr<BackendObject> CreateSamplerBackend(SamplerState& sampler) = 0;
  virtual std::unique_ptr<BackendObject> CreateShaderBackend(Shader& shader) = 0;
  virtual std::unique_ptr<BackendObject> CreateQueryBackend(Query& query) = 0;
  // Called once, after the backend is constructed; the core wraps it in the immediate context.
  virtual std::unique_ptr<ContextBackend> CreateContextBackend() = 0;
  virtual uint32_t FormatSupportBackend(FORMAT format) const = 0;
  virtual uint32_t MaxSampleCountBackend(FORMAT format) const = 0;
  // Whether exactly `count` samples (a power of two) are supported: drivers may offer 4x but not
  // 2x (Mesa's software rasterizers), which a maximum alone cannot say.
  virtual bool SampleCountSupportedBackend(FORMAT format, uint32_t count) const { return count <= MaxSampleCountBackend(format); }
  // visualId: the X visual of the window (GL picks the EGLConfig that matches it). The default
  // refuses (the null backend cannot present).
  virtual std::unique_ptr<SwapChainBackend> CreateSwapChainBackend(const SwapChainDesc& desc, unsigned long visualId);

  // The core device this backend serves, and what backends report through it.
  Device& Core() const { return core_; }
  const DeviceInfo& Info() const { return info_; }
  void Message(MessageSeverity severity, std::string_view text) const;
  uint32_t CheckFormatSupport(FORMAT format) const { return FormatSupportBackend(format); }

 protected:
  Device& core_;
  // The core's DeviceInfo: the backend fills in what it knows about the driver while it starts.
  DeviceInfo& info_;
};

// What a backend implements for a swap chain (sp::SwapChain owns it). The core has validated the
// desc, checked that the window exists, and owns the back buffer; the backend shows it.
class SwapChainBackend {
 public:
  virtual ~SwapChainBackend() = default;
  // The DXGI formats whose back buffers this window's surface can show without conversion.
  virtual std::vector<FORMAT> Formats() const = 0;
  // After ResizeBuffers (or at creation): the buffer count and format of what comes next.
  virtual void Configure(const SwapChainDesc& desc) = 0;
  // Copies the back buffer to the window (stretched when sizes differ) and presents it.
  virtual void Present(Texture2D& backBuffer, uint32_t syncInterval) = 0;
};

class NullResources;

// The core's private parts of sp::Device.
struct DeviceAccess {
  static bool StrictUnboundResources(const Device& d) { return d.strictUnboundResources_; }
  static void* X11Display(const Device& d) { return d.x11Display_; }
  static DeviceBackend& Backend(Device& d) { return *d.backend_; }
  static NullResources& Nulls(Device& d);  // made on first use
};

// Backend factories (backends/vulkan, backends/gl, backends/null). `core` is the device being
// created; it has no context yet.
std::unique_ptr<DeviceBackend> CreateVulkanBackend(Device& core, const DeviceDesc& desc);
std::unique_ptr<DeviceBackend> CreateGLBackend(Device& core, const DeviceDesc& desc);
std::unique_ptr<DeviceBackend> CreateNullBackend(Device& core, const DeviceDesc& desc);

}  // namespace sp::detail
