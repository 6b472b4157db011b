// Batches: one command buffer, fence, descriptor pools and upload-ring chunks per submission,
// recycled when the fence signals. Objects remember the serial of the last batch that used
// them; destruction and reuse of memory wait for that serial.
#include <algorithm>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

constexpr VkDeviceSize kChunkSize = 4ull << 20;
constexpr uint64_t kWorkPerSubmit = 4096;  // draws, dispatches, copies (uploads count per 64 KiB)

VkDeviceSize AlignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

}  // namespace

VulkanContext::VulkanContext(VulkanDevice* dev) : dev_(dev) {}

VulkanContext::~VulkanContext() {
  VkDevice d = dev_->device;
  try {
    Submit();
  } catch (const Error& e) {
    dev_->Message(MessageSeverity::Error, std::string("final submission failed: ") + e.what());
  }
  vkDeviceWaitIdle(d);
  Poll();
  // Whatever is still in flight after a failed submission is finished now.
  while (!inFlight_.empty()) {
    dev_->completedSerial = std::max(dev_->completedSerial, inFlight_.front()->serial);
    RecycleBatch(std::move(inFlight_.front()));
    inFlight_.pop_front();
  }
  if (cur_) {
    vkEndCommandBuffer(cur_->cmd);
    RecycleBatch(std::move(cur_));
  }
  dev_->completedSerial = dev_->recordingSerial;
  dev_->RunDeferred();
  for (auto& b : freeBatches_) {
    vkDestroyCommandPool(d, b->pool, nullptr);
    vkDestroyFence(d, b->fence, nullptr);
  }
  freeBatches_.clear();
  for (VkDescriptorPool p : freePools_) vkDestroyDescriptorPool(d, p, nullptr);
  freePools_.clear();
  for (BufferRange& c : freeChunks_) dev_->alloc.Free(c);
  freeChunks_.clear();
  dev_->ctx = nullptr;
}

void VulkanContext::BeginBatch() {
  const char* call = "DeviceContext";
  std::unique_ptr<Batch> b;
  if (!freeBatches_.empty()) {
    b = std::move(freeBatches_.back());
    freeBatches_.pop_back();
  } else {
    b = std::make_unique<Batch>();
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pci.queueFamilyIndex = dev_->queueFamily;
    Check(vkCreateCommandPool(dev_->device, &pci, nullptr, &b->pool), call, "command pool", "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = b->pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    Check(vkAllocateCommandBuffers(dev_->device, &ai, &b->cmd), call, "command buffer", "vkAllocateCommandBuffers");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    Check(vkCreateFence(dev_->device, &fci, nullptr, &b->fence), call, "fence", "vkCreateFence");
  }
  b->serial = dev_->recordingSerial;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  Check(vkBeginCommandBuffer(b->cmd, &bi), call, "command buffer", "vkBeginCommandBuffer");
  cur_ = std::move(b);
  ResetCommandBufferState();
  // Occlusion queries cannot span command buffers: each batch gets its own segment.
  StartSegment();
}

void VulkanContext::ResetCommandBufferState() {
  rendering_ = false;
  pass_ = {};
  boundPipeline_ = VK_NULL_HANDLE;
  boundCompute_ = VK_NULL_HANDLE;
  for (auto& s : gfxSets_) s = {};
  computeSet_ = {};
  setCache_.clear();  // its sets come from the previous batch's pools
  dynamicStateValid_ = false;
  boundVertex_.clear();
  vertexEpoch_ = 0;
  boundIndex_ = {};
  chunk_ = {};
  chunkUsed_ = 0;
}

VkCommandBuffer VulkanContext::Cmd() {
  if (!cur_) BeginBatch();
  EndRendering();
  return cur_->cmd;
}

void VulkanContext::EndRendering() {
  if (rendering_ && cur_) vkCmdEndRendering(cur_->cmd);
  rendering_ = false;
}

void VulkanContext::FlushBarriers() {
  if (barriers_.Empty()) return;
  barriers_.Record(Cmd());
}

void VulkanContext::UseBuffer(VkBufferObj& b, const Access& a) {
  barriers_.Buffer(b.state, a);
  b.lastUse = dev_->recordingSerial;
  if (a.write) {
    b.lastWrite = dev_->recordingSerial;
    b.contentVersion++;
  }
}

void VulkanContext::UseRange(AccessState& s, const Access& a) { barriers_.Buffer(s, a); }

void VulkanContext::UseImage(VkTextureObj& t, uint32_t mip0, uint32_t mips, uint32_t layer0, uint32_t layers, const Access& a) {
  for (uint32_t m = mip0; m < mip0 + mips; ++m)
    for (uint32_t l = layer0; l < layer0 + layers; ++l) barriers_.Image(t.State(m, l), a, t.image, t.aspects, m, l);
  t.lastUse = dev_->recordingSerial;
  if (a.write) t.lastWrite = dev_->recordingSerial;
}

void VulkanContext::UseView(VkViewObj& v, const Access& a) {
  v.lastUse = dev_->recordingSerial;
  if (v.texture) {
    UseImage(*v.texture, v.firstMip, v.mipCount, v.firstLayer, v.layerCount, a);
  } else if (v.buffer) {
    UseBuffer(*v.buffer, a);
  }
}

UploadSpan VulkanContext::Upload(VkDeviceSize size, VkDeviceSize align) {
  if (!cur_) BeginBatch();
  VkDeviceSize offset = AlignUp(chunkUsed_, align);
  if (!chunk_ || offset + size > chunk_.size) {
    VkDeviceSize want = std::max(kChunkSize, AlignUp(size, 256));
    if (want == kChunkSize && !freeChunks_.empty()) {
      chunk_ = freeChunks_.back();
      freeChunks_.pop_back();
    } else {
      chunk_ = dev_->alloc.AllocateBuffer(want, MemoryKind::Upload, "UpdateSubresource", "upload ring");
    }
    cur_->chunks.push_back(chunk_);
    offset = 0;
  }
  chunkUsed_ = offset + size;
  work_ += size >> 16;
  return {chunk_.buffer, chunk_.offset + offset, chunk_.mapped + offset};
}

VkDescriptorSet VulkanContext::AllocateSet(VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (!cur_->descriptorPools.empty()) {
    ai.descriptorPool = cur_->descriptorPools.back();
    VkResult r = vkAllocateDescriptorSets(dev_->device, &ai, &set);
    if (r == VK_SUCCESS) return set;
    if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL) ThrowVk(r, "Draw", "descriptor set", "vkAllocateDescriptorSets");
  }
  VkDescriptorPool pool;
  if (!freePools_.empty()) {
    pool = freePools_.back();
    freePools_.pop_back();
  } else {
    const VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2048},       {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 2048},
        {VK_DESCRIPTOR_TYPE_SAMPLER, 1024},              {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 512},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1024},       {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 512},
        {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 512},  {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 2048},
    };
    VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pci.maxSets = 512;
    pci.poolSizeCount = uint32_t(std::size(sizes));
    pci.pPoolSizes = sizes;
    Check(vkCreateDescriptorPool(dev_->device, &pci, nullptr, &pool), "Draw", "descriptor pool", "vkCreateDescriptorPool");
  }
  cur_->descriptorPools.push_back(pool);
  ai.descriptorPool = pool;
  Check(vkAllocateDescriptorSets(dev_->device, &ai, &set), "Draw", "descriptor set", "vkAllocateDescriptorSets");
  return set;
}

void VulkanContext::Submit() {
  if (!cur_) return;
  EndRendering();
  StopSegment();
  barriers_.Record(cur_->cmd);
  // Make every GPU write visible to Map (staging readback, query results are separate).
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cur_->cmd, &di);
  Check(vkEndCommandBuffer(cur_->cmd), "Flush", "command buffer", "vkEndCommandBuffer");
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cur_->cmd;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO}, signalInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  if (presentWait_) {
    waitInfo.semaphore = presentWait_;
    waitInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    si.waitSemaphoreInfoCount = 1;
    si.pWaitSemaphoreInfos = &waitInfo;
  }
  if (presentSignal_) {
    signalInfo.semaphore = presentSignal_;
    signalInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    si.signalSemaphoreInfoCount = 1;
    si.pSignalSemaphoreInfos = &signalInfo;
  }
  presentWait_ = presentSignal_ = VK_NULL_HANDLE;
  VkResult r = vkQueueSubmit2(dev_->queue, 1, &si, cur_->fence);
  std::unique_ptr<Batch> b = std::move(cur_);
  dev_->recordingSerial++;
  ResetCommandBufferState();
  work_ = 0;
  if (r != VK_SUCCESS) {
    vkResetCommandPool(dev_->device, b->pool, 0);
    freeBatches_.push_back(std::move(b));
    ThrowVk(r, "Flush", "queue", "vkQueueSubmit2");
  }
  inFlight_.push_back(std::move(b));
  Poll();
}

uint64_t VulkanContext::SubmitForPresent(VkSemaphore wait, VkSemaphore signal) {
  if (!cur_) BeginBatch();
  presentWait_ = wait;
  presentSignal_ = signal;
  uint64_t serial = dev_->recordingSerial;
  Submit();
  return serial;
}

void VulkanContext::SubmitIfBusy() {
  if (work_ >= kWorkPerSubmit) Submit();
}

void VulkanContext::RecycleBatch(std::unique_ptr<Batch> b) {
  vkResetCommandPool(dev_->device, b->pool, 0);
  vkResetFences(dev_->device, 1, &b->fence);
  for (VkDescriptorPool p : b->descriptorPools) {
    vkResetDescriptorPool(dev_->device, p, 0);
    freePools_.push_back(p);
  }
  b->descriptorPools.clear();
  for (BufferRange& c : b->chunks) {
    if (c.size == kChunkSize && freeChunks_.size() < 16) freeChunks_.push_back(c);
    else dev_->alloc.Free(c);
  }
  b->chunks.clear();
  freeBatches_.push_back(std::move(b));
}

void VulkanContext::Poll() {
  while (!inFlight_.empty()) {
    VkResult r = vkGetFenceStatus(dev_->device, inFlight_.front()->fence);
    if (r == VK_NOT_READY) break;
    if (r != VK_SUCCESS) ThrowVk(r, "Flush", "queue", "vkGetFenceStatus");
    dev_->completedSerial = std::max(dev_->completedSerial, inFlight_.front()->serial);
    RecycleBatch(std::move(inFlight_.front()));
    inFlight_.pop_front();
  }
  dev_->RunDeferred();
}

bool VulkanContext::IsBusy(uint64_t serial) {
  if (serial <= dev_->completedSerial) return false;
  // Used by the batch being recorded: busy without asking the driver (every Map of a buffer a draw
  // just read would poll the fences otherwise).
  if (serial >= dev_->recordingSerial) return true;
  Poll();
  return serial > dev_->completedSerial;
}

void VulkanContext::WaitForSerial(uint64_t serial) {
  if (serial <= dev_->completedSerial) return;
  if (serial >= dev_->recordingSerial) Submit();
  for (auto& b : inFlight_) {
    if (b->serial > serial) break;
    Check(vkWaitForFences(dev_->device, 1, &b->fence, VK_TRUE, UINT64_MAX), "Map", "queue", "vkWaitForFences");
  }
  Poll();
}

void VulkanContext::Flush() { Submit(); }

void VulkanContext::WaitIdle() {
  Submit();
  WaitForSerial(dev_->recordingSerial - 1);
}

}  // namespace sp::vk
