// The hand-written Vulkan 1.3 side: its own instance and device on the same driver (no layers:
// the sp:: device of the benchmark is created without validation too), and the few helpers a
// small engine has (buffers, images, shader modules, descriptor layouts read from reflection,
// one command buffer and fence per case).
#pragma once
#include <vulkan/vulkan.h>

#include <functional>
#include <vector>
#include <sp/rhi/shader.h>

namespace spbench {

class RawVulkan {
 public:
  RawVulkan();
  ~RawVulkan();
  RawVulkan(const RawVulkan&) = delete;
  RawVulkan& operator=(const RawVulkan&) = delete;

  struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    uint8_t* mapped = nullptr;  // every buffer is host-visible and coherent, mapped for its life
  };
  struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
  };
  // One command buffer re-recorded every iteration, its pool and the fence of its submission.
  struct Frame {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
  };

  VkDevice device() const { return device_; }
  VkDeviceSize uniformAlignment() const { return uboAlign_; }

  Buffer CreateBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* data = nullptr);
  // Optimal tiling, left in `layout` (contents undefined: they do not change what is recorded).
  Image CreateImage(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, uint32_t size, VkImageLayout layout);
  VkShaderModule CreateModule(const std::vector<uint32_t>& spirv);
  // The descriptor set layout of one stage's set: cbuffers as dynamic uniform buffers (a ring of
  // constants bound by offset), textures, samplers and structured UAVs at the toolchain's bindings.
  VkDescriptorSetLayout CreateSetLayout(const sp::ShaderReflection& r, VkShaderStageFlags stages);
  VkDescriptorSet AllocateSet(VkDescriptorSetLayout layout);

  Frame CreateFrame();
  void Begin(Frame& f);
  void Submit(Frame& f);  // ends the command buffer and submits it with the frame's fence
  void Wait(Frame& f);    // waits for the fence and resets the fence and the pool

 private:
  uint32_t MemoryType(uint32_t bits, VkMemoryPropertyFlags props) const;
  void OneShot(const std::function<void(VkCommandBuffer)>& record);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t family_ = 0;
  VkDeviceSize uboAlign_ = 256;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory_{};
};

// The name of the SPIR-V module's (single) entry point.
const char* EntryPointName(const std::vector<uint32_t>& spirv);

}  // namespace spbench
