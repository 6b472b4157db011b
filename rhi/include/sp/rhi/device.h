// ID3D11Device mirror. Create with sp::CreateDevice; every Create* validates its arguments the way
// D3D11 (and its debug layer) does and throws sp::Error naming the call and the object. The
// D3D11-shaped overloads (descs by pointer, out-pointers) report the same failures as an HRESULT.
//
// Threading: like a D3D11 device created with D3D11_CREATE_DEVICE_SINGLETHREADED. The OpenGL
// backend's context is current on the creating thread only.
#pragma once
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <unordered_set>
#include <sp/rhi/common.h>
#include <sp/rhi/query.h>
#include <sp/rhi/resource.h>
#include <sp/rhi/shader.h>
#include <sp/rhi/state.h>
#include <sp/rhi/view.h>

namespace sp {

class DeviceContext;

namespace detail {
class DeviceBackend;
class NullResources;
struct DeviceAccess;
}  // namespace detail

// Null: no driver and no GPU work; every call is validated by the core and then dropped (see
// backends/null/null-internal.h). For validation and misuse tests, not for pictures.
enum class Backend : uint8_t { Vulkan, OpenGL, Null };
const char* BackendName(Backend b);       // "vulkan", "gl", "null"
bool ParseBackend(std::string_view s, Backend* out);

using MessageCallback = std::function<void(MessageSeverity, std::string_view)>;

struct DeviceDesc {
  Backend backend = Backend::Vulkan;
  // Vulkan validation layers / GL debug output (KHR_debug, synchronous). Messages of Error
  // severity are counted (ValidationErrorCount) and passed to messageCallback.
  bool debug = true;
  MessageCallback messageCallback;  // null: warnings and errors go to stderr
  // A shader register read by a draw or dispatch with nothing bound reads zeros as in D3D11
  // (samplers: D3D11's default sampler state; UAVs: writes are dropped), with one warning per
  // shader and register. true: such a draw or dispatch throws SP_UNBOUND_RESOURCE instead.
  bool strictUnboundResources = false;
  // Where the shaders the device compiles for itself (depth-bias calibration) are cached.
  // Empty: the toolchain's default (hlsl::CompileOptions::cacheDir).
  std::filesystem::path shaderCacheDir;
  // Start the device as if the driver lacked vsRenderTargetArrayIndex (not enabled, reported
  // false), so the refusals and per-face fallbacks can be exercised on a driver that has it.
  bool disableVsRenderTargetArrayIndex = false;
  // Start the device as if the driver lacked depth-bias clamping (reported false), to exercise
  // CreateRasterizerState's refusal of a non-zero DepthBiasClamp.
  bool disableDepthBiasClamp = false;
  // An Xlib Display* whose windows the device will present to (sp::CreateSwapChain). Null: the
  // headless device (EGL surfaceless display; Vulkan without surface extensions). Set: GL runs on
  // an EGL display of this X display (EGL_PLATFORM_X11_KHR), Vulkan enables VK_KHR_surface,
  // VK_KHR_xlib_surface and VK_KHR_swapchain. Rendering is the same either way.
  void* x11Display = nullptr;
};

// What the device is, and what it measured about the driver when it started.
struct DeviceInfo {
  Backend backend = Backend::Vulkan;
  std::string apiVersion;   // "Vulkan 1.3.230", "OpenGL 4.5 (Core Profile) Mesa 22.3.6"
  std::string deviceName;   // "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string driverName;   // "Mesa 22.3.6"
  // Factor applied to D3D11 DepthBias to get the driver's constant bias, per depth format,
  // measured at device creation by rendering a biased quad (see docs/porting.md).
  float depthBiasScaleD16 = 1.0f;
  float depthBiasScaleD24 = 1.0f;
  float depthBiasScaleD32 = 1.0f;
  bool validationEnabled = false;
  uint64_t timestampFrequency = 0;  // ticks per second
  uint32_t maxMsaaSamples = 1;      // largest of 1, 2, 4, 8 supported for colour and depth
  // A vertex shader may write SV_RenderTargetArrayIndex and SV_ViewportArrayIndex (D3D11.3's
  // D3D11_FEATURE_DATA_D3D11_OPTIONS3::VPAndRTArrayIndexFromAnyShaderFeedingRasterizer):
  // Vulkan 1.2 shaderOutputLayer + shaderOutputViewportIndex (VK_EXT_shader_viewport_index_layer
  // enabled too when offered), GL_ARB_shader_viewport_layer_array. Without it CreateVertexShader
  // refuses such a shader.
  bool vsRenderTargetArrayIndex = false;
  // RASTERIZER_DESC::DepthBiasClamp is honoured (Vulkan's depthBiasClamp feature, GL 4.6 or
  // GL_EXT_polygon_offset_clamp); without it CreateRasterizerState refuses a non-zero clamp
  // rather than draw with an unclamped bias.
  bool depthBiasClamp = false;
};

enum FORMAT_SUPPORT : uint32_t {
  FORMAT_SUPPORT_BUFFER = 0x1,
  FORMAT_SUPPORT_IA_VERTEX_BUFFER = 0x2,
  FORMAT_SUPPORT_IA_INDEX_BUFFER = 0x4,
  FORMAT_SUPPORT_TEXTURE1D = 0x10,
  FORMAT_SUPPORT_TEXTURE2D = 0x20,
  FORMAT_SUPPORT_TEXTURE3D = 0x40,
  FORMAT_SUPPORT_TEXTURECUBE = 0x80,
  FORMAT_SUPPORT_SHADER_LOAD = 0x100,
  FORMAT_SUPPORT_SHADER_SAMPLE = 0x200,
  FORMAT_SUPPORT_SHADER_SAMPLE_COMPARISON = 0x400,
  FORMAT_SUPPORT_MIP = 0x1000,
  FORMAT_SUPPORT_RENDER_TARGET = 0x4000,
  FORMAT_SUPPORT_BLENDABLE = 0x8000,
  FORMAT_SUPPORT_DEPTH_STENCIL = 0x10000,
  FORMAT_SUPPORT_MULTISAMPLE_RESOLVE = 0x40000,
  FORMAT_SUPPORT_TYPED_UNORDERED_ACCESS_VIEW = 0x400000,
  FORMAT_SUPPORT_MULTISAMPLE_RENDERTARGET = 0x200000,
  FORMAT_SUPPORT_MULTISAMPLE_LOAD = 0x100000,
  FORMAT_SUPPORT_SHADER_GATHER = 0x800000,
  FORMAT_SUPPORT_SHADER_GATHER_COMPARISON = 0x8000000,
};

class Device {
 public:
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  Ref<Buffer> CreateBuffer(const BUFFER_DESC& desc, const SUBRESOURCE_DATA* initialData = nullptr);
  // initialData: one SUBRESOURCE_DATA per subresource (mip-major within each array slice), or null.
  Ref<Texture1D> CreateTexture1D(const TEXTURE1D_DESC& desc, const SUBRESOURCE_DATA* initialData = nullptr);
  Ref<Texture2D> CreateTexture2D(const TEXTURE2D_DESC& desc, const SUBRESOURCE_DATA* initialData = nullptr);
  Ref<Texture3D> CreateTexture3D(const TEXTURE3D_DESC& desc, const SUBRESOURCE_DATA* initialData = nullptr);

  // desc == nullptr: a view of the whole resource in its own format, as in D3D11.
  Ref<ShaderResourceView> CreateShaderResourceView(Resource* resource, const SHADER_RESOURCE_VIEW_DESC* desc = nullptr);
  Ref<RenderTargetView> CreateRenderTargetView(Resource* resource, const RENDER_TARGET_VIEW_DESC* desc = nullptr);
  Ref<DepthStencilView> CreateDepthStencilView(Resource* resource, const DEPTH_STENCIL_VIEW_DESC* desc = nullptr);
  Ref<UnorderedAccessView> CreateUnorderedAccessView(Resource* resource, const UNORDERED_ACCESS_VIEW_DESC* desc = nullptr);

  Ref<SamplerState> CreateSamplerState(const SAMPLER_DESC& desc);
  Ref<RasterizerState> CreateRasterizerState(const RASTERIZER_DESC& desc);
  Ref<DepthStencilState> CreateDepthStencilState(const DEPTH_STENCIL_DESC& desc);
  Ref<BlendState> CreateBlendState(const BLEND_DESC& desc);

  // Elements are matched to the vertex shader's input signature by semantic, as in D3D11.
  Ref<InputLayout> CreateInputLayout(const INPUT_ELEMENT_DESC* elements, uint32_t numElements,
                                     const ShaderBytecode& vertexShaderBytecode);
  Ref<VertexShader> CreateVertexShader(const ShaderBytecode& bytecode);
  Ref<PixelShader> CreatePixelShader(const ShaderBytecode& bytecode);
  Ref<GeometryShader> CreateGeometryShader(const ShaderBytecode& bytecode);
  Ref<ComputeShader> CreateComputeShader(const ShaderBytecode& bytecode);
  // The void*/size overloads take ShaderBytecode::Serialize() blobs.
  Ref<VertexShader> CreateVertexShader(const void* bytecode, size_t length);
  Ref<PixelShader> CreatePixelShader(const void* bytecode, size_t length);
  Ref<ComputeShader> CreateComputeShader(const void* bytecode, size_t length);

  Ref<Query> CreateQuery(const QUERY_DESC& desc);

  // --- D3D11 call shapes: `V_RETURN(dev->CreateTexture2D(&desc, NULL, &m_pTex))`.
  // The object comes back through an OutPtr (a COM-style T**, AddRef'd, or a Ref<T>*). On failure
  // *out is null, the result is HResultFromErrorId(error.id()), and the sp::Error's message goes
  // to the message callback as an Error (counted in ValidationErrorCount), as D3D11's debug
  // layer prints it. A null out-pointer only validates: S_FALSE when the call would succeed.
  // Class linkage is not supported: a non-null ClassLinkage fails with DXGI_ERROR_UNSUPPORTED.
  HRESULT CreateBuffer(const BUFFER_DESC* desc, const SUBRESOURCE_DATA* initialData, OutPtr<Buffer> buffer);
  HRESULT CreateTexture1D(const TEXTURE1D_DESC* desc, const SUBRESOURCE_DATA* initialData, OutPtr<Texture1D> texture);
  HRESULT CreateTexture2D(const TEXTURE2D_DESC* desc, const SUBRESOURCE_DATA* initialData, OutPtr<Texture2D> texture);
  HRESULT CreateTexture3D(const TEXTURE3D_DESC* desc, const SUBRESOURCE_DATA* initialData, OutPtr<Texture3D> texture);
  HRESULT CreateShaderResourceView(Resource* resource, const SHADER_RESOURCE_VIEW_DESC* desc, OutPtr<ShaderResourceView> view);
  HRESULT CreateRenderTargetView(Resource* resource, const RENDER_TARGET_VIEW_DESC* desc, OutPtr<RenderTargetView> view);
  HRESULT CreateDepthStencilView(Resource* resource, const DEPTH_STENCIL_VIEW_DESC* desc, OutPtr<DepthStencilView> view);
  HRESULT CreateUnorderedAccessView(Resource* resource, const UNORDERED_ACCESS_VIEW_DESC* desc, OutPtr<UnorderedAccessView> view);
  HRESULT CreateSamplerState(const SAMPLER_DESC* desc, OutPtr<SamplerState> state);
  HRESULT CreateRasterizerState(const RASTERIZER_DESC* desc, OutPtr<RasterizerState> state);
  HRESULT CreateDepthStencilState(const DEPTH_STENCIL_DESC* desc, OutPtr<DepthStencilState> state);
  HRESULT CreateBlendState(const BLEND_DESC* desc, OutPtr<BlendState> state);
  // bytecode/length: a ShaderBytecode::Serialize() blob (what blob->GetBufferPointer() and
  // GetBufferSize() give for ShadowPort's compiled shaders).
  HRESULT CreateInputLayout(const INPUT_ELEMENT_DESC* elements, uint32_t numElements, const void* vertexShaderBytecode,
                            size_t length, OutPtr<InputLayout> layout);
  HRESULT CreateVertexShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<VertexShader> shader);
  HRESULT CreatePixelShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<PixelShader> shader);
  HRESULT CreateGeometryShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<GeometryShader> shader);
  HRESULT CreateComputeShader(const void* bytecode, size_t length, ClassLinkage* linkage, OutPtr<ComputeShader> shader);
  HRESULT CreateQuery(const QUERY_DESC* desc, OutPtr<Query> query);

  DeviceContext* GetImmediateContext() { return context_.get(); }
  // D3D11's shape: the context with a COM reference (see DeviceContext::AddRef).
  void GetImmediateContext(DeviceContext** context);

  // D3D11 CheckFormatSupport / CheckMultisampleQualityLevels.
  uint32_t CheckFormatSupport(FORMAT format) const;
  uint32_t CheckMultisampleQualityLevels(FORMAT format, uint32_t sampleCount) const;
  // The HRESULT forms: E_FAIL (and 0) for a format the device cannot use at all, as D3D11.
  HRESULT CheckFormatSupport(FORMAT format, uint32_t* formatSupport) const;
  HRESULT CheckMultisampleQualityLevels(FORMAT format, uint32_t sampleCount, uint32_t* numQualityLevels) const;

  Backend GetBackend() const { return info_.backend; }
  const DeviceInfo& Info() const { return info_; }

  // Driver validation (Vulkan validation layers, GL debug output) and core errors reported
  // through Message(). Tests assert the count stays zero.
  uint64_t ValidationErrorCount() const { return validationErrors_; }
  std::string LastValidationError() const;
  void SetMessageCallback(MessageCallback cb) { callback_ = std::move(cb); }

  // Reports a message as D3D11's debug layer would; Error severity counts as a validation error.
  void Message(MessageSeverity severity, std::string_view text);

 private:
  friend Ref<Device> CreateDevice(const DeviceDesc& desc);
  friend class Object;
  friend class detail::DeviceBackend;
  friend struct detail::DeviceAccess;
  explicit Device(const DeviceDesc& desc);
  template <class T, class... A>
  Ref<T> Make(A&&... args);
  template <class T>
  Ref<T> CreateShaderOfStage(ShaderStage stage, const ShaderBytecode& bytecode, const char* call);
  void ValidateTextureShape(TextureShape& shape, const char* call, const std::string& object,
                            const SUBRESOURCE_DATA* init) const;
  // Measures the driver's constant depth-bias unit for D16, D24 and D32F by drawing a biased quad
  // (public API only) and sets info_.depthBiasScale*. Needs the immediate context.
  void CalibrateDepthBias();
  // Unbinds everything and releases the backend data of every object still alive, while the
  // backend can still free it.
  void ReleaseBackendData();

  DeviceInfo info_;
  bool strictUnboundResources_ = false;
  void* x11Display_ = nullptr;  // DeviceDesc::x11Display: the display swap chains may present to
  std::filesystem::path shaderCacheDir_;
  std::unique_ptr<detail::DeviceBackend> backend_;
  std::unique_ptr<DeviceContext> context_;
  std::unique_ptr<detail::NullResources> nullResources_;
  MessageCallback callback_;
  uint64_t validationErrors_ = 0;
  std::string lastValidationError_;
  mutable std::mutex liveMutex_;
  std::unordered_set<Object*> live_;
  uint64_t nextUid_ = 1;
};

template <class T, class... A>
Ref<T> Device::Make(A&&... args) {
  return Ref<T>(new T(this, std::forward<A>(args)...));
}

// Creates a device on the requested backend: the backend, then the immediate context, then the
// depth-bias calibration. Throws sp::Error(DEVICE_CREATION_FAILED) with the reason (no Vulkan
// driver, EGL cannot create a 4.5 core context, ...).
Ref<Device> CreateDevice(const DeviceDesc& desc);

}  // namespace sp
