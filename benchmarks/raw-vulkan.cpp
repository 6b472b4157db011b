#include "raw-vulkan.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace spbench {
namespace {

void Check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string("raw Vulkan: ") + what + " failed (" + std::to_string(r) + ")");
}

VkDescriptorType DescriptorType(sp::ShaderResourceType t) {
  switch (t) {
    case sp::ShaderResourceType::Texture: return VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    case sp::ShaderResourceType::Sampler: return VK_DESCRIPTOR_TYPE_SAMPLER;
    case sp::ShaderResourceType::RWStructuredBuffer: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    default: throw std::runtime_error("raw Vulkan: the benchmark shaders use textures, samplers and structured UAVs only");
  }
}

}  // namespace

const char* EntryPointName(const std::vector<uint32_t>& spirv) {
  for (size_t i = 5; i < spirv.size();) {
    uint32_t op = spirv[i] & 0xffff, count = spirv[i] >> 16;
    if (op == 15 /*OpEntryPoint*/) return reinterpret_cast<const char*>(&spirv[i + 3]);
    i += count ? count : 1;
  }
  throw std::runtime_error("raw Vulkan: SPIR-V without an entry point");
}

RawVulkan::RawVulkan() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "bench-rhi raw";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  Check(vkCreateInstance(&ici, nullptr, &instance_), "vkCreateInstance");
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance_, &n, nullptr);
  std::vector<VkPhysicalDevice> pds(n);
  vkEnumeratePhysicalDevices(instance_, &n, pds.data());
  for (VkPhysicalDevice pd : pds) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    if (p.apiVersion >= VK_API_VERSION_1_3) {
      physical_ = pd;
      uboAlign_ = p.limits.minUniformBufferOffsetAlignment;
      break;
    }
  }
  if (!physical_) throw std::runtime_error("raw Vulkan: no Vulkan 1.3 device");
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, families.data());
  for (family_ = 0; family_ < n; ++family_)
    if ((families[family_].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) break;
  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = family_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  // What the toolchain's SPIR-V may need (SV_InstanceID reads BaseInstance) and dynamic rendering.
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  f11.shaderDrawParameters = VK_TRUE;
  f11.pNext = &f13;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &f11;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  Check(vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, family_, 0, &queue_);
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 256},
                                  {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 256},
                                  {VK_DESCRIPTOR_TYPE_SAMPLER, 256},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 256}};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = 256;
  dpi.poolSizeCount = 4;
  dpi.pPoolSizes = sizes;
  Check(vkCreateDescriptorPool(device_, &dpi, nullptr, &pool_), "vkCreateDescriptorPool");
}

// The cases' objects are not destroyed one by one: the process ends after the benchmarks.
RawVulkan::~RawVulkan() {
  vkDeviceWaitIdle(device_);
  vkDestroyDescriptorPool(device_, pool_, nullptr);
  vkDestroyDevice(device_, nullptr);
  vkDestroyInstance(instance_, nullptr);
}

uint32_t RawVulkan::MemoryType(uint32_t bits, VkMemoryPropertyFlags props) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & props) == props) return i;
  throw std::runtime_error("raw Vulkan: no suitable memory type");
}

RawVulkan::Buffer RawVulkan::CreateBuffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* data) {
  Buffer b;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size;
  bci.usage = usage;
  Check(vkCreateBuffer(device_, &bci, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, b.buffer, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = MemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  Check(vkAllocateMemory(device_, &mai, nullptr, &b.memory), "vkAllocateMemory");
  vkBindBufferMemory(device_, b.buffer, b.memory, 0);
  void* p = nullptr;
  Check(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory");
  b.mapped = static_cast<uint8_t*>(p);
  if (data) std::memcpy(b.mapped, data, size);
  return b;
}

RawVulkan::Image RawVulkan::CreateImage(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, uint32_t size,
                                        VkImageLayout layout) {
  Image im;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = format;
  ici.extent = {size, size, 1};
  ici.mipLevels = 1;
  ici.arrayLayers = 1;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  Check(vkCreateImage(device_, &ici, nullptr, &im.image), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device_, im.image, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = MemoryType(req.memoryTypeBits, 0);
  Check(vkAllocateMemory(device_, &mai, nullptr, &im.memory), "vkAllocateMemory");
  vkBindImageMemory(device_, im.image, im.memory, 0);
  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = im.image;
  vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vci.format = format;
  vci.subresourceRange = {aspect, 0, 1, 0, 1};
  Check(vkCreateImageView(device_, &vci, nullptr, &im.view), "vkCreateImageView");
  if (layout != VK_IMAGE_LAYOUT_UNDEFINED) {
    OneShot([&](VkCommandBuffer cmd) {
      VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      b.newLayout = layout;
      b.image = im.image;
      b.subresourceRange = vci.subresourceRange;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                           nullptr, 1, &b);
    });
  }
  return im;
}

VkShaderModule RawVulkan::CreateModule(const std::vector<uint32_t>& spirv) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = spirv.size() * 4;
  ci.pCode = spirv.data();
  VkShaderModule m;
  Check(vkCreateShaderModule(device_, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}

VkDescriptorSetLayout RawVulkan::CreateSetLayout(const sp::ShaderReflection& r, VkShaderStageFlags stages) {
  std::vector<VkDescriptorSetLayoutBinding> b;
  for (const sp::CBufferInfo& c : r.cbuffers) b.push_back({c.vkBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, stages, nullptr});
  for (const sp::ShaderResourceBinding& s : r.resources) b.push_back({s.vkBinding, DescriptorType(s.type), 1, stages, nullptr});
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = uint32_t(b.size());
  ci.pBindings = b.data();
  VkDescriptorSetLayout l;
  Check(vkCreateDescriptorSetLayout(device_, &ci, nullptr, &l), "vkCreateDescriptorSetLayout");
  return l;
}

VkDescriptorSet RawVulkan::AllocateSet(VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  VkDescriptorSet s;
  Check(vkAllocateDescriptorSets(device_, &ai, &s), "vkAllocateDescriptorSets");
  return s;
}

RawVulkan::Frame RawVulkan::CreateFrame() {
  Frame f;
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = family_;
  Check(vkCreateCommandPool(device_, &pci, nullptr, &f.pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = f.pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  Check(vkAllocateCommandBuffers(device_, &ai, &f.cmd), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  Check(vkCreateFence(device_, &fci, nullptr, &f.fence), "vkCreateFence");
  return f;
}

void RawVulkan::Begin(Frame& f) {
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(f.cmd, &bi);
}

void RawVulkan::Submit(Frame& f) {
  Check(vkEndCommandBuffer(f.cmd), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &f.cmd;
  Check(vkQueueSubmit(queue_, 1, &si, f.fence), "vkQueueSubmit");
}

void RawVulkan::Wait(Frame& f) {
  Check(vkWaitForFences(device_, 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vkResetFences(device_, 1, &f.fence);
  vkResetCommandPool(device_, f.pool, 0);
}

void RawVulkan::OneShot(const std::function<void(VkCommandBuffer)>& record) {
  Frame f = CreateFrame();
  Begin(f);
  record(f.cmd);
  Submit(f);
  Wait(f);
  vkDestroyFence(device_, f.fence, nullptr);
  vkDestroyCommandPool(device_, f.pool, nullptr);
}

}  // namespace spbench
