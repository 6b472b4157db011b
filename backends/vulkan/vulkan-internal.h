// Private declarations of the Vulkan 1.3 backend. The backend-neutral core (rhi/src) validates every
// call before it reaches this code, so nothing here re-checks D3D11 rules; what is checked is what
// only the driver knows (limits, format features), reported as sp::Error naming the call.
#pragma once
#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "backend.h"
#include "shader-bindings.h"

namespace sp::vk {

using namespace sp::detail;

class VulkanDevice;
class VulkanContext;
struct VkViewObj;

// ---------------------------------------------------------------------------------------------
// Errors (vulkan-device.cpp)

const char* ResultName(VkResult r);
[[noreturn]] void ThrowVk(VkResult r, const char* call, const std::string& object, const char* what);
inline void Check(VkResult r, const char* call, const std::string& object, const char* what) {
  if (r != VK_SUCCESS) ThrowVk(r, call, object, what);
}
[[noreturn]] void Throw(ErrorId id, const char* call, const std::string& object, const std::string& detail);
std::string DescribeObject(const Object* o);

// ---------------------------------------------------------------------------------------------
// Formats (vulkan-formats.cpp)

// The Vulkan format of a typed DXGI format. Depth-read view formats (R24_UNORM_X8_TYPELESS, ...)
// give the depth format they read. VK_FORMAT_UNDEFINED when there is none.
VkFormat VkFormatOf(FORMAT f);
// The format a texture's VkImage is created with: the family's depth format for BIND_DEPTH_STENCIL
// (and for families that only exist as depth), a representative member for TYPELESS families.
VkFormat ImageFormatOf(const TextureShape& s);
VkImageAspectFlags AspectsOf(VkFormat f);
bool IsDepthStencilFormat(VkFormat f);
bool IsIntegerFormat(FORMAT f);
VkCompareOp CompareOp(COMPARISON_FUNC f);
// The layout a depth-stencil view is rendered in, from its read-only flags.
VkImageLayout DsvLayout(const VkViewObj& v);

// ---------------------------------------------------------------------------------------------
// Memory (vulkan-memory.cpp)

enum class MemoryKind : uint8_t { Device, Upload, Readback };

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, size = 0;
  uint8_t* mapped = nullptr;
  void* block = nullptr;  // owning block; null for a dedicated allocation
};

// Best-fit free list over [0, size) with coalescing, O(log n) per call.
class RangeAllocator {
 public:
  explicit RangeAllocator(VkDeviceSize size);
  bool Allocate(VkDeviceSize size, VkDeviceSize align, VkDeviceSize* offset);
  void Free(VkDeviceSize offset, VkDeviceSize size);
  bool Empty() const { return used_ == 0; }

 private:
  void Insert(VkDeviceSize offset, VkDeviceSize size);
  void Erase(std::map<VkDeviceSize, VkDeviceSize>::iterator it);
  std::map<VkDeviceSize, VkDeviceSize> byOffset_;        // offset -> size
  std::set<std::pair<VkDeviceSize, VkDeviceSize>> bySize_;  // (size, offset)
  VkDeviceSize used_ = 0;
};

// A range of a VkBuffer. Buffers are sub-allocated from large VkBuffers created with every usage,
// so one D3D buffer is (VkBuffer, offset) everywhere (descriptors, copies, vertex bindings).
struct BufferRange {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, size = 0;
  uint8_t* mapped = nullptr;
  void* block = nullptr;  // owning pool block; null when the VkBuffer is dedicated
  Allocation memory;      // memory of a dedicated VkBuffer
  explicit operator bool() const { return buffer != VK_NULL_HANDLE; }
};

class Allocator {
 public:
  Allocator();
  ~Allocator();
  void Init(VulkanDevice* dev);
  void Shutdown();
  Allocation AllocateImage(const VkMemoryRequirements& req, const char* call, const std::string& object);
  void Free(Allocation& a);
  // dedicated: a VkBuffer of its own (offset 0), for drivers that ignore binding offsets somewhere.
  BufferRange AllocateBuffer(VkDeviceSize size, MemoryKind kind, const char* call, const std::string& object, bool dedicated = false);
  // A range of an existing block, or false when a new block (and so a name for its errors) is needed.
  bool SuballocateBuffer(VkDeviceSize size, MemoryKind kind, BufferRange* out);
  void Free(BufferRange& r);
  VkDeviceSize BufferAlignment() const { return bufferAlign_; }

 private:
  struct MemBlock;
  struct BufBlock;
  uint32_t FindType(uint32_t typeBits, MemoryKind kind, const char* call, const std::string& object) const;
  bool TakeRange(BufBlock& b, VkDeviceSize size, BufferRange* out);  // a range of b, if it has room
  Allocation AllocateDedicated(VkDeviceSize size, uint32_t type, const char* call, const std::string& object);

  VulkanDevice* dev_ = nullptr;
  VkDeviceSize bufferAlign_ = 256;
  std::vector<std::unique_ptr<MemBlock>> memBlocks_;
  std::vector<std::unique_ptr<BufBlock>> bufBlocks_;
};

// ---------------------------------------------------------------------------------------------
// Hazard tracking (vulkan-state-tracker.cpp)

// What the GPU last did to a buffer or one image subresource.
struct AccessState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 writeStages = 0;  // last write (or layout transition), 0 when none pending
  VkAccessFlags2 writeAccess = 0;
  VkPipelineStageFlags2 readStages = 0;   // reads since the last write (write-after-read hazards)
  VkPipelineStageFlags2 visibleStages = 0;  // where the last write has been made visible
  VkAccessFlags2 visibleAccess = 0;
};

struct Access {
  VkPipelineStageFlags2 stages = 0;
  VkAccessFlags2 access = 0;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
  bool write = false;
};

namespace access {
Access TransferRead();
Access TransferWrite();
Access ShaderRead(VkPipelineStageFlags2 stage, VkAccessFlags2 a, VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
Access ShaderWrite(VkPipelineStageFlags2 stage, VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED);
Access ColorAttachment();
Access DepthAttachment(VkImageLayout layout, bool write);
Access VertexInput();
Access IndexInput();
Access IndirectArgs();
}  // namespace access

// Barriers collected for one command, recorded as one vkCmdPipelineBarrier2.
class BarrierBatch {
 public:
  // Returns true when the access needed a barrier.
  bool Buffer(AccessState& s, const Access& a);
  bool Image(AccessState& s, const Access& a, VkImage image, VkImageAspectFlags aspects, uint32_t mip, uint32_t layer);
  bool Empty() const { return images_.empty() && srcStages_ == 0 && dstStages_ == 0; }
  void Record(VkCommandBuffer cmd);

 private:
  void Global(VkPipelineStageFlags2 src, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dst, VkAccessFlags2 dstAccess);
  VkPipelineStageFlags2 srcStages_ = 0, dstStages_ = 0;
  VkAccessFlags2 srcAccess_ = 0, dstAccess_ = 0;
  std::vector<VkImageMemoryBarrier2> images_;
};

// ---------------------------------------------------------------------------------------------
// Backend objects

struct TrackedObject : detail::BackendObject {
  VulkanDevice* dev = nullptr;
  uint64_t lastUse = 0;    // serial of the last batch that referenced the object
  uint64_t lastWrite = 0;  // serial of the last batch that wrote it on the GPU
};

struct VkBufferObj final : TrackedObject {
  const Buffer* owner = nullptr;
  BUFFER_DESC desc;
  MemoryKind kind = MemoryKind::Device;
  // Every version gets a VkBuffer of its own (offset 0): index buffers on drivers whose indexed
  // indirect draws ignore the binding offset (see CreateBuffer).
  bool ownVkBuffer = false;
  BufferRange range;  // current storage (a dynamic buffer's latest version)
  AccessState state;
  uint64_t contentVersion = 1;  // changes with every write, for repacked constant buffers
  struct RepackCache {
    uint64_t key, version, serial;
    VkBuffer buffer;
    VkDeviceSize offset;
  };
  std::vector<RepackCache> repackCache;
  struct Retired {
    BufferRange range;
    uint64_t busyUntil;
  };
  std::deque<Retired> retired;  // earlier versions, oldest first, reused once idle
  ~VkBufferObj() override;
};

struct VkTextureObj final : TrackedObject {
  const Texture* owner = nullptr;
  TextureShape shape;
  bool staging = false;
  // GPU image (not for staging textures)
  VkImage image = VK_NULL_HANDLE;
  Allocation memory;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspects = 0;
  uint32_t layers = 1;              // Vulkan array layers (1 for 3D)
  std::vector<AccessState> states;  // per subresource, D3D order: layer * mipLevels + mip
  AccessState& State(uint32_t mip, uint32_t layer) { return states[CalcSubresource(mip, layer, shape.mipLevels)]; }
  // Staging textures: memory laid out as D3D11 maps it, and for depth-stencil families the planes
  // Vulkan copies use (depth and stencil separately); the CPU layout is rebuilt from the planes on Map.
  struct Sub {
    VkDeviceSize offset = 0;  // in `main`
    uint32_t rowPitch = 0, depthPitch = 0;
    VkDeviceSize depthOffset = 0, stencilOffset = 0;  // in the planes
  };
  std::vector<Sub> subs;
  BufferRange main, depthPlane, stencilPlane;
  AccessState mainState, depthPlaneState, stencilPlaneState;
  bool usesPlanes = false;
  bool planesNewer = false;  // the GPU wrote the planes after the CPU layout was last rebuilt
  bool pendingSplit = false; // mapped for writing: the planes are rebuilt on Unmap
  // Dynamic textures: what Map(WRITE_DISCARD) hands out, uploaded on Unmap.
  std::map<uint32_t, std::vector<uint8_t>> mapScratch;
  ~VkTextureObj() override;
};

struct VkViewObj final : detail::BackendObject {
  enum Kind : uint8_t { SRV, RTV, DSV, UAV };
  VulkanDevice* dev = nullptr;
  const View* owner = nullptr;
  Kind kind = SRV;
  VkBufferObj* buffer = nullptr;
  VkTextureObj* texture = nullptr;
  uint64_t lastUse = 0;
  // Textures: subresources in Vulkan terms (3D: layer 0, slices of the W range only for RTVs).
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = 0;
  uint32_t firstMip = 0, mipCount = 1, firstLayer = 0, layerCount = 1;  // tracked subresources
  uint32_t renderLayers = 1;  // layers of an RTV/DSV (3D RTVs: W slices)
  bool depthReadOnly = false, stencilReadOnly = false;  // DSV flags
  // Buffers
  VkDeviceSize byteOffset = 0, byteSize = 0;
  bool texel = false;  // typed view (VkBufferView)
  struct TexelEntry {
    VkBuffer buffer;
    VkDeviceSize offset;
    VkBufferView view;
  };
  std::vector<TexelEntry> texelViews;  // one per buffer version the view was used with
  BufferRange counter;                // hidden counter of append/consume UAVs
  AccessState counterState;
  VkBufferView TexelView(const char* call);
  ~VkViewObj() override;
};

struct VkSamplerObj final : detail::BackendObject {
  VulkanDevice* dev = nullptr;
  VkSampler sampler = VK_NULL_HANDLE;
  uint64_t lastUse = 0;
  ~VkSamplerObj() override;
};

struct ShaderBinding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  RegisterClass cls = RegisterClass::ShaderResource;
  uint32_t reg = 0;
  ShaderResourceType resType = ShaderResourceType::Texture;
};

struct VkShaderObj final : detail::BackendObject {
  VulkanDevice* dev = nullptr;
  const Shader* owner = nullptr;
  uint64_t uid = 0;
  ShaderStage stage = ShaderStage::Vertex;
  bool instanceFromZero = false;  // `module` is the SV_InstanceID-from-0 variant (vertex shaders)
  VkShaderModule module = VK_NULL_HANDLE;
  VkShaderModule dualSourceModule = VK_NULL_HANDLE;  // SV_Target1 moved to location 0 index 1
  VkShaderModule pointSizeModule = VK_NULL_HANDLE;   // writes PointSize = 1 (D3D11 points)
  std::string entry;
  std::vector<ShaderBinding> bindings;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout computeLayout = VK_NULL_HANDLE;
  // From the bytecode's SPIR-V products (rhi/src/hlsl/target-spirv.cpp).
  std::vector<CBufferRepack> repacks;
  std::vector<SampledPair> sampledPairs;
  const CBufferRepack* RepackFor(uint32_t reg) const {
    for (const CBufferRepack& r : repacks)
      if (r.reg == reg) return &r;
    return nullptr;
  }
  uint32_t writtenTargets = 0;  // bit per SV_TargetN the pixel shader writes
  bool hasTarget1 = false;
  // Whether a draw that changed none of this stage's bindings may keep its descriptor set and only
  // move the dynamic offsets (see VulkanContext::KeepDescriptors): not with repacked cbuffers,
  // which are copied per draw. `rangeInSet`: a descriptor holds a buffer range that a
  // WRITE_DISCARD rename moves (storage or texel buffers).
  bool setKeptAcrossDraws = false;
  bool rangeInSet = false;
  VkShaderModule DualSourceModule();
  VkShaderModule PointSizeModule();
  ~VkShaderObj() override;
};

// One Vulkan query. Vulkan allows one active occlusion query per command buffer while D3D11
// nests and overlaps them, so occlusion is counted in segments shared by every D3D11 query active
// while the segment ran (a new segment starts at each Begin, End and submission).
struct QuerySegment {
  VulkanDevice* dev = nullptr;
  VkQueryPool pool = VK_NULL_HANDLE;
  uint64_t serial = 0;
  ~QuerySegment();
};

struct VkQueryObj final : detail::BackendObject {
  VulkanDevice* dev = nullptr;
  QUERY type = QUERY_EVENT;
  std::vector<std::shared_ptr<QuerySegment>> segments;  // summed by GetData
  bool active = false;                                  // between Begin and End
  bool issued = false;             // End was called
  uint64_t endSerial = 0;
  uint64_t lastUse = 0;
  ~VkQueryObj() override;
};

// ---------------------------------------------------------------------------------------------
// The device

struct Features {
  bool depthClipEnable = false;
  bool customBorderColor = false;
  bool robustness2 = false;
  bool nullDescriptor = false;
  bool samplerMinmax = false;
  bool divisor = false, divisorZero = false;
  bool depthClamp = false, depthBiasClamp = false;
  bool fillModeNonSolid = false, dualSrcBlend = false, independentBlend = false;
  bool anisotropy = false, cubeArray = false, occlusionPrecise = false;
  bool storageWriteWithoutFormat = false, storageReadWithoutFormat = false;
  bool drawIndirectFirstInstance = false, debugUtils = false, drawParameters = false;
  // Mesa 22.3 lavapipe ignores the index buffer's binding offset in vkCmdDrawIndexedIndirect.
  bool indirectIgnoresIndexOffset = false;
  bool present = false;  // VK_KHR_surface, VK_KHR_xlib_surface, VK_KHR_swapchain (DeviceDesc::x11Display)
};

// The device backend. The core (sp::Device) owns it, and destroys it only after the immediate
// context and every object's Vulkan data are gone.
class VulkanDevice final : public detail::DeviceBackend {
 public:
  VulkanDevice(Device& core, const DeviceDesc& desc);
  ~VulkanDevice() override;

  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkPhysicalDeviceProperties props{};
  VkPhysicalDeviceVulkan13Properties props13{};
  VkPhysicalDeviceMemoryProperties memProps{};
  Features feat;
  Allocator alloc;
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;
  VulkanContext* ctx = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName = nullptr;

  // Batches are numbered; objects remember the serial of the last batch that used them.
  uint64_t recordingSerial = 1;  // the batch being recorded
  uint64_t completedSerial = 0;  // every batch up to this one has finished
  void Defer(uint64_t serial, std::function<void()> destroy);
  void RunDeferred();
  void Name(VkObjectType type, uint64_t handle, const std::string& name);

  // Descriptor set and pipeline layouts, shared by shaders with the same bindings.
  VkDescriptorSetLayout SetLayout(const std::vector<ShaderBinding>& bindings, VkShaderStageFlags stages);
  VkPipelineLayout PipelineLayout(const std::vector<VkDescriptorSetLayout>& sets);
  // Pipelines, keyed by a byte string of everything that shapes them.
  VkPipeline FindPipeline(const std::string& key) const;
  void AddPipeline(const std::string& key, VkPipeline p, uint64_t shaderA, uint64_t shaderB);
  void ForgetShader(uint64_t uid);
  uint32_t SampleCountsFor(VkFormat f) const;
  VkFormatFeatureFlags2 OptimalFeatures(VkFormat f) const;

  std::unique_ptr<detail::BackendObject> CreateBufferBackend(Buffer& buffer, const SUBRESOURCE_DATA* init) override;
  std::unique_ptr<detail::BackendObject> CreateTextureBackend(Texture& texture, const SUBRESOURCE_DATA* init) override;
  std::unique_ptr<detail::BackendObject> CreateViewBackend(View& view) override;
  std::unique_ptr<detail::BackendObject> CreateSamplerBackend(SamplerState& sampler) override;
  std::unique_ptr<detail::BackendObject> CreateShaderBackend(Shader& shader) override;
  std::unique_ptr<detail::BackendObject> CreateQueryBackend(Query& query) override;
  std::unique_ptr<detail::ContextBackend> CreateContextBackend() override;
  std::unique_ptr<detail::SwapChainBackend> CreateSwapChainBackend(const SwapChainDesc& desc, unsigned long visualId) override;
  uint32_t FormatSupportBackend(FORMAT format) const override;
  uint32_t MaxSampleCountBackend(FORMAT format) const override;
  bool SampleCountSupportedBackend(FORMAT format, uint32_t count) const override;

 private:
  void CreateInstance(bool debug, bool present);
  void PickPhysicalDevice();
  void CreateLogicalDevice(bool allowLayerOutput);
  void FillInfo();
  void Teardown();

  std::multimap<uint64_t, std::function<void()>> deferred_;
  std::map<std::string, VkDescriptorSetLayout> setLayouts_;
  std::map<std::vector<VkDescriptorSetLayout>, VkPipelineLayout> pipelineLayouts_;
  struct PipelineEntry {
    VkPipeline pipeline;
    uint64_t shaderA, shaderB;
  };
  std::unordered_map<std::string, PipelineEntry> pipelines_;
  mutable std::unordered_map<uint32_t, uint32_t> formatSupport_;
  mutable std::unordered_map<uint32_t, VkFormatFeatureFlags2> formatFeatures_;
};

// Backend creation helpers (vulkan-buffer.cpp, vulkan-texture.cpp, vulkan-views.cpp, ...).
std::unique_ptr<VkBufferObj> CreateBufferObj(VulkanDevice* dev, Buffer& buffer, const SUBRESOURCE_DATA* init);
std::unique_ptr<VkTextureObj> CreateTextureObj(VulkanDevice* dev, Texture& texture, const SUBRESOURCE_DATA* init);
std::unique_ptr<VkViewObj> CreateViewObj(VulkanDevice* dev, View& view);
std::unique_ptr<VkSamplerObj> CreateSamplerObj(VulkanDevice* dev, SamplerState& sampler);
std::unique_ptr<VkShaderObj> CreateShaderObj(VulkanDevice* dev, Shader& shader);
std::unique_ptr<VkQueryObj> CreateQueryObj(VulkanDevice* dev, Query& query);
void ReleaseBufferRange(VulkanDevice* dev, BufferRange& r, uint64_t serial);
// Staging depth-stencil textures: D3D11's packed CPU layout <-> the planes Vulkan copies use.
void MergePlanes(VkTextureObj& t);
void SplitPlanes(VkTextureObj& t);

inline VkBufferObj& BufferOf(const Resource* r) { return detail::BackendAs<VkBufferObj>(r); }
inline VkTextureObj& TextureOf(const Resource* r) { return detail::BackendAs<VkTextureObj>(r); }
inline VkViewObj& ViewOf(const View* v) { return detail::BackendAs<VkViewObj>(v); }

// ---------------------------------------------------------------------------------------------
// The immediate context

struct UploadSpan {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  uint8_t* ptr = nullptr;
};

// One resolved descriptor: what a binding points at, compared between draws to skip rewrites.
struct DescriptorItem {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = 0;
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkSampler sampler = VK_NULL_HANDLE;
  VkBufferView texel = VK_NULL_HANDLE;
  bool operator==(const DescriptorItem&) const = default;
};

// What selects a graphics pipeline, as uids of the bound objects (see recentPipelines_).
struct PipelineIdentity {
  std::array<uint64_t, 6> objects{};  // VS, PS, input layout, rasterizer, depth-stencil, blend
  std::array<uint64_t, SIMULTANEOUS_RENDER_TARGET_COUNT + 1> targets{};
  VkPipelineLayout layout = VK_NULL_HANDLE;
  uint32_t topology = 0, sampleMask = 0, numRenderTargets = 0;
  bool operator==(const PipelineIdentity&) const = default;
};

class VulkanContext final : public detail::ContextBackend {
 public:
  explicit VulkanContext(VulkanDevice* dev);
  ~VulkanContext() override;

  void Draw(const PipelineState& state, uint32_t dirty, const detail::DrawArgs& args) override;
  void Dispatch(const PipelineState& state, uint32_t dirty, uint32_t x, uint32_t y, uint32_t z, Buffer* argsBuffer,
                uint32_t argsOffset) override;
  void ClearRenderTargetView(RenderTargetView* rtv, const float rgba[4]) override;
  void ClearDepthStencilView(DepthStencilView* dsv, uint32_t clearFlags, float depth, uint8_t stencil) override;
  void ClearUnorderedAccessView(UnorderedAccessView* uav, const detail::UavClearValue& value) override;
  void CopyResource(Resource* dst, Resource* src) override;
  void CopySubresourceRegion(Resource* dst, const detail::Subresource& dstSub, uint32_t dstX, uint32_t dstY, uint32_t dstZ, Resource* src,
                             const detail::Subresource& srcSub, const BOX& srcBox) override;
  void UpdateSubresource(Resource* dst, const detail::Subresource& dstSub, const BOX& box, const void* data, uint32_t rowPitch,
                         uint32_t depthPitch) override;
  bool Map(Resource* resource, const detail::Subresource& sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out) override;
  void Unmap(Resource* resource, const detail::Subresource& sub) override;
  void GenerateMips(ShaderResourceView* srv) override;
  void ResolveSubresource(Resource* dst, const detail::Subresource& dstSub, Resource* src, const detail::Subresource& srcSub, FORMAT format) override;
  void CopyStructureCount(Buffer* dst, uint32_t dstOffset, UnorderedAccessView* src) override;
  void SetUavCounter(UnorderedAccessView* uav, uint32_t value) override;
  void Begin(Query* query) override;
  void End(Query* query) override;
  bool GetData(Query* query, void* data, uint32_t size, uint32_t flags) override;
  void Flush() override;
  void WaitIdle() override;

  // --- Recording, used by the device for creation-time uploads and by the transfer code.
  VkCommandBuffer Cmd();  // the current command buffer, outside dynamic rendering
  void EndRendering();
  UploadSpan Upload(VkDeviceSize size, VkDeviceSize align = 16);
  void UseBuffer(VkBufferObj& b, const Access& a);
  void UseRange(AccessState& s, const Access& a);  // a buffer range without an owner object
  void UseImage(VkTextureObj& t, uint32_t mip0, uint32_t mips, uint32_t layer0, uint32_t layers, const Access& a);
  void UseView(VkViewObj& v, const Access& a);
  void FlushBarriers();  // records pending barriers; ends rendering when some are needed
  void Submit();
  // Submits the current batch waiting for `wait` (at the transfer stage) and signalling `signal`:
  // a swap-chain image's acquisition and presentation. Returns the batch's serial.
  uint64_t SubmitForPresent(VkSemaphore wait, VkSemaphore signal);
  void WaitForSerial(uint64_t serial);
  bool IsBusy(uint64_t serial);  // polls; true while the batch has not finished
  void Poll();
  void CountWork(uint32_t n = 1) { work_ += n; }
  void ForgetQuery(VkQueryObj* q);  // a query destroyed between Begin and End
  struct RepackedConstants {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0, size = 0;
  };
  RepackedConstants RepackConstants(VkBufferObj& b, const CBufferRepack& rp, uint64_t key, VkPipelineStageFlags2 stage);
  void SubmitIfBusy();  // submits when enough work accumulated

  // Transfer helpers (vulkan-transfer.cpp)
  void UploadToBuffer(VkBufferObj& b, VkDeviceSize offset, const void* data, VkDeviceSize size);
  void UploadToImage(VkTextureObj& t, const detail::Subresource& sub, const BOX& box, const void* data, uint32_t rowPitch, uint32_t depthPitch);
  void ZeroImage(VkTextureObj& t);
  void ZeroBuffer(VkBufferObj& b);

 private:
  struct Batch {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    uint64_t serial = 0;
    std::vector<VkDescriptorPool> descriptorPools;
    std::vector<BufferRange> chunks;  // upload ring chunks
  };
  struct StageDescriptors {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    std::vector<DescriptorItem> items;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipelineLayout boundWith = VK_NULL_HANDLE;
    std::vector<uint32_t> dynamicOffsets;  // of the dynamic cbuffers, in binding order, as last bound
    uint64_t shaderUid = 0;                // whose bindings `items` was resolved from (0: none)
    uint64_t viewRenames = 0;              // VulkanContext::viewRenames_ at that time
  };
  struct RenderPassKey {
    std::array<uint64_t, SIMULTANEOUS_RENDER_TARGET_COUNT + 1> views{};  // view uids (0 = none)
    uint32_t dsvFlags = 0;
    bool operator==(const RenderPassKey&) const = default;
  };

  // vulkan-submit.cpp
  void BeginBatch();
  void RecycleBatch(std::unique_ptr<Batch> b);
  VkDescriptorSet AllocateSet(VkDescriptorSetLayout layout);
  // vulkan-descriptors.cpp
  void ResolveDescriptors(const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, std::vector<DescriptorItem>& out, std::vector<uint32_t>& dynamicOffsets,
                          const char* call);
  void TrackStageResources(const PipelineState& s, ShaderStage stage, const VkShaderObj& sh);
  void CheckSampling(const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, uint32_t dirty, const char* call);
  // Writes (or finds in the batch's cache) the set holding `items` into sd; true when sd must be
  // bound again (new set, other pipeline layout or new dynamic offsets). Swaps `items` and
  // `dynamicOffsets` out.
  bool PrepareDescriptors(StageDescriptors& sd, VkDescriptorSetLayout layout, std::vector<DescriptorItem>& items,
                          std::vector<uint32_t>& dynamicOffsets, VkPipelineLayout pipeLayout);
  // The stage's set for this draw: kept, with fresh dynamic offsets, when none of the stage's
  // bindings changed (KeepDescriptors), else resolved and prepared again. True when sd must be
  // bound again.
  bool StageDescriptorsFor(StageDescriptors& sd, const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, uint32_t dirty,
                           VkPipelineLayout pipeLayout, const char* call);
  bool KeepDescriptors(StageDescriptors& sd, const PipelineState& s, ShaderStage stage, const VkShaderObj& sh, uint32_t dirty);
  // Binds first's set at firstSet, and second's (when given) at firstSet + 1 in the same call.
  void BindSets(VkPipelineBindPoint point, VkPipelineLayout pipeLayout, uint32_t firstSet, const StageDescriptors* first,
                const StageDescriptors* second = nullptr);
  VkImageLayout SrvLayout(const PipelineState& s, const VkViewObj& v) const;
  // vulkan-pipeline.cpp
  VkPipeline GraphicsPipeline(const PipelineState& s, VkPipelineLayout layout, const char* call);
  VkPipeline CachedGraphicsPipeline(const PipelineState& s, uint32_t dirty, uint64_t vsUid, uint64_t psUid, VkPipelineLayout layout,
                                    const char* call);
  VkPipeline ComputePipeline(const VkShaderObj& cs, const char* call);
  // vulkan-context.cpp
  void BeginRendering(const PipelineState& s);
  void TrackAttachments(const PipelineState& s);
  void SetDynamicState(const PipelineState& s);
  void BindVertexBuffers(const PipelineState& s, uint32_t dirty);
  void ResetCommandBufferState();
  // vulkan-transfer.cpp
  void CopyImageToStaging(VkTextureObj& src, const detail::Subresource& srcSub, VkTextureObj& dst, const detail::Subresource& dstSub, const BOX& box, uint32_t x,
                          uint32_t y, uint32_t z);
  void CopyStagingToImage(VkTextureObj& src, const detail::Subresource& srcSub, VkTextureObj& dst, const detail::Subresource& dstSub, const BOX& box, uint32_t x,
                          uint32_t y, uint32_t z);
  void CopyStagingToStaging(VkTextureObj& src, const detail::Subresource& srcSub, VkTextureObj& dst, const detail::Subresource& dstSub, const BOX& box, uint32_t x,
                            uint32_t y, uint32_t z);
  void CopyImageToImage(VkTextureObj& src, const detail::Subresource& srcSub, VkTextureObj& dst, const detail::Subresource& dstSub, const BOX& box, uint32_t x,
                        uint32_t y, uint32_t z);
  bool MapStaging(VkTextureObj& t, uint32_t sub, MAP type, uint32_t flags, MAPPED_SUBRESOURCE* out);
  bool WaitForMap(TrackedObject& o, MAP type, uint32_t flags);
  void Rename(VkBufferObj& b);
  // vulkan-clear.cpp
  void ClearImageViaCopy(VkViewObj& v, const uint8_t* texel, uint32_t texelSize);

  VulkanDevice* dev_;
  std::unique_ptr<Batch> cur_;
  std::deque<std::unique_ptr<Batch>> inFlight_;
  std::vector<std::unique_ptr<Batch>> freeBatches_;
  std::vector<VkDescriptorPool> freePools_;
  std::vector<BufferRange> freeChunks_;
  BufferRange chunk_;  // current upload chunk
  VkDeviceSize chunkUsed_ = 0;
  uint64_t work_ = 0;
  BarrierBatch barriers_;
  VkSemaphore presentWait_ = VK_NULL_HANDLE, presentSignal_ = VK_NULL_HANDLE;  // for the next Submit only

  // Command-buffer state (reset with every new command buffer).
  bool rendering_ = false;
  RenderPassKey pass_;
  VkExtent2D passExtent_{};
  VkPipeline boundPipeline_ = VK_NULL_HANDLE;
  VkPipeline boundCompute_ = VK_NULL_HANDLE;
  std::array<StageDescriptors, 2> gfxSets_;  // VS (set 0), PS (set 1)
  StageDescriptors computeSet_;
  bool dynamicStateValid_ = false;  // false: lastDynamic_ says nothing (new command buffer)
  struct DynamicValues {
    VkViewport viewport{};
    VkRect2D scissor{};
    VkBool32 biasEnable = VK_FALSE;
    std::array<float, 3> bias{};  // constant, clamp, slope
    std::array<float, 4> blendFactor{};
    uint32_t stencilRef = 0;
    VkBool32 strip = VK_FALSE;
  };
  DynamicValues lastDynamic_;
  std::vector<std::tuple<uint32_t, VkBuffer, VkDeviceSize, VkDeviceSize, VkDeviceSize>> boundVertex_, wantVertex_;
  std::tuple<VkBuffer, VkDeviceSize, VkIndexType> boundIndex_{};
  VkPipeline currentPipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout currentLayout_ = VK_NULL_HANDLE;
  // Pipelines recently resolved, by the uids of what selects them (objects are immutable and uids
  // never reused): a state change back to a seen combination skips building and hashing the key.
  std::array<std::pair<PipelineIdentity, VkPipeline>, 64> recentPipelines_{};
  // The targets' part of the identity and its hash, redone only when the targets change: a state
  // change between draws into the same targets (bench-rhi's state case) paid for nine uids each.
  std::array<uint64_t, SIMULTANEOUS_RENDER_TARGET_COUNT + 1> pipelineTargets_{};
  uint64_t pipelineTargetsHash_ = 0;
  std::pair<uint64_t, uint64_t> layoutShaders_{};  // VS, PS uids currentLayout_ was looked up for
  std::vector<DescriptorItem> scratchItems_;
  // Sets written in this command buffer, by content: going back to a combination seen in the
  // batch (a material's textures, say) binds its set again instead of allocating and writing one.
  struct CachedSet {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    std::vector<DescriptorItem> items;
    VkDescriptorSet set = VK_NULL_HANDLE;
  };
  std::unordered_map<uint64_t, CachedSet> setCache_;
  std::vector<uint32_t> scratchOffsets_;
  std::vector<uint32_t> bindOffsets_;  // both graphics sets' dynamic offsets, for one bind call
  uint64_t viewRenames_ = 1;           // renames of buffers views may read (Rename): ranges in sets moved
  uint64_t vertexRenames_ = 1;         // renames of vertex and index buffers
  uint64_t vertexEpoch_ = 0;           // vertexRenames_ when boundVertex_ was resolved; 0: not in this batch
  std::array<std::array<RepackedConstants, COMMONSHADER_CONSTANT_BUFFER_API_SLOT_COUNT>, SHADER_STAGE_COUNT> repacked_{};
  std::vector<VkQueryObj*> activeQueries_;
  std::shared_ptr<QuerySegment> segment_;  // the occlusion query running now
  void StartSegment();
  void StopSegment();
};

}  // namespace sp::vk
