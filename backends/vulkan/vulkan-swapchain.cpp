// Presentation: VK_KHR_xlib_surface + VK_KHR_swapchain. The back buffer is an ordinary texture;
// Present acquires a swap-chain image, copies (or, across channel orders and sizes, blits) the
// back buffer into it on the device's queue, and presents it. The swap chain is (re)created
// lazily at Present, at the window's current size, so a window resized before ResizeBuffers
// still shows the back buffer, stretched, as DXGI_SCALING_STRETCH does.
#define VK_USE_PLATFORM_XLIB_KHR
#include "vulkan-internal.h"

#include <vulkan/vulkan_xlib.h>

#include <algorithm>

namespace sp::vk {
namespace {

// The DXGI formats a surface format shows without conversion: the same bits per channel and
// the same encoding (a blit between UNORM and SRGB would decode or encode).
std::vector<FORMAT> DxgiFormatsOf(VkFormat f) {
  switch (f) {
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_UNORM: return {FORMAT_R8G8B8A8_UNORM, FORMAT_B8G8R8A8_UNORM};
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R8G8B8A8_SRGB: return {FORMAT_R8G8B8A8_UNORM_SRGB, FORMAT_B8G8R8A8_UNORM_SRGB};
    case VK_FORMAT_A2R10G10B10_UNORM_PACK32:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32: return {FORMAT_R10G10B10A2_UNORM};
    case VK_FORMAT_R16G16B16A16_SFLOAT: return {FORMAT_R16G16B16A16_FLOAT};
    default: return {};
  }
}

class VulkanSwapChain final : public detail::SwapChainBackend {
 public:
  VulkanSwapChain(VulkanDevice* dev, const SwapChainDesc& desc) : dev_(dev), window_(desc.window) {
    const char* call = "CreateSwapChain";
    VkXlibSurfaceCreateInfoKHR ci{VK_STRUCTURE_TYPE_XLIB_SURFACE_CREATE_INFO_KHR};
    ci.dpy = static_cast<Display*>(desc.window.x11Display);
    ci.window = Window(desc.window.x11Window);
    Check(vkCreateXlibSurfaceKHR(dev_->instance, &ci, nullptr, &surface_), call, "window surface", "vkCreateXlibSurfaceKHR");
    VkBool32 supported = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(dev_->physical, dev_->queueFamily, surface_, &supported);
    if (!supported) {
      vkDestroySurfaceKHR(dev_->instance, surface_, nullptr);
      Throw(ErrorId::NOT_SUPPORTED, call, dev_->props.deviceName, "the device's queue cannot present to this window");
    }
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(dev_->physical, surface_, &n, nullptr);
    surfaceFormats_.resize(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(dev_->physical, surface_, &n, surfaceFormats_.data());
    vkGetPhysicalDeviceSurfacePresentModesKHR(dev_->physical, surface_, &n, nullptr);
    modes_.resize(n);
    vkGetPhysicalDeviceSurfacePresentModesKHR(dev_->physical, surface_, &n, modes_.data());
  }

  ~VulkanSwapChain() override {
    // The queue may still wait on our semaphores or read the images.
    if (dev_->ctx) dev_->ctx->WaitIdle();
    vkQueueWaitIdle(dev_->queue);
    DestroySwapchain(swapchain_);
    for (VkSemaphore s : acquired_) vkDestroySemaphore(dev_->device, s, nullptr);
    vkDestroySurfaceKHR(dev_->instance, surface_, nullptr);
  }

  std::vector<FORMAT> Formats() const override {
    std::vector<FORMAT> out;
    for (const VkSurfaceFormatKHR& f : surfaceFormats_) {
      if (f.colorSpace != VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) continue;
      for (FORMAT d : DxgiFormatsOf(f.format))
        if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  void Configure(const SwapChainDesc& desc) override {
    bufferCount_ = desc.bufferCount;
    VkFormat want = VK_FORMAT_UNDEFINED;
    for (const VkSurfaceFormatKHR& f : surfaceFormats_) {
      if (f.colorSpace != VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) continue;
      std::vector<FORMAT> d = DxgiFormatsOf(f.format);
      if (std::find(d.begin(), d.end(), desc.format) == d.end()) continue;
      // The back buffer's own channel order first: then Present is a plain copy.
      if (want == VK_FORMAT_UNDEFINED || f.format == VkFormatOf(desc.format)) want = f.format;
    }
    if (want != format_) stale_ = true;
    format_ = want;
  }

  void Present(Texture2D& backBuffer, uint32_t syncInterval) override {
    VkSurfaceCapabilitiesKHR caps;
    VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(dev_->physical, surface_, &caps);
    if (r != VK_SUCCESS) ThrowVk(r, "Present", "window surface", "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = caps.currentExtent;
    const TextureShape& shape = backBuffer.Shape();
    if (extent.width == UINT32_MAX) extent = {shape.width, shape.height};
    // A window without area (minimised) shows nothing: DXGI returns DXGI_STATUS_OCCLUDED.
    if (extent.width == 0 || extent.height == 0) return;
    VkPresentModeKHR mode = ModeFor(syncInterval);
    if (stale_ || !swapchain_ || extent.width != extent_.width || extent.height != extent_.height || mode != mode_)
      Recreate(caps, extent, mode);

    uint32_t slot = next_++ % uint32_t(acquired_.size());
    // The semaphore is free again once the batch that waited on it has finished.
    dev_->ctx->WaitForSerial(acquiredSerial_[slot]);
    uint32_t index = 0;
    r = vkAcquireNextImageKHR(dev_->device, swapchain_, UINT64_MAX, acquired_[slot], VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
      stale_ = true;  // resized between the query and the acquisition: shown next time
      return;
    }
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) ThrowVk(r, "Present", "swap chain", "vkAcquireNextImageKHR");

    VulkanContext& ctx = *dev_->ctx;
    VkTextureObj& src = TextureOf(&backBuffer);
    ctx.UseImage(src, 0, 1, 0, 1, access::TransferRead());
    ctx.FlushBarriers();
    VkCommandBuffer cmd = ctx.Cmd();
    VkImage dst = images_[index];
    // Contents are overwritten whole: the old layout does not matter. The acquisition's
    // semaphore is waited on at the transfer stage, which this barrier's source scope covers.
    ImageBarrier(cmd, dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageSubresourceLayers layers{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    if (extent.width == shape.width && extent.height == shape.height && src.format == format_) {
      VkImageCopy region{layers, {0, 0, 0}, layers, {0, 0, 0}, {shape.width, shape.height, 1}};
      vkCmdCopyImage(cmd, src.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    } else {
      VkImageBlit region{};
      region.srcSubresource = layers;
      region.srcOffsets[1] = {int32_t(shape.width), int32_t(shape.height), 1};
      region.dstSubresource = layers;
      region.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
      const bool scaled = extent.width != shape.width || extent.height != shape.height;
      vkCmdBlitImage(cmd, src.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                     scaled ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
    }
    ImageBarrier(cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0);
    acquiredSerial_[slot] = ctx.SubmitForPresent(acquired_[slot], rendered_[index]);

    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &rendered_[index];
    pi.swapchainCount = 1;
    pi.pSwapchains = &swapchain_;
    pi.pImageIndices = &index;
    r = vkQueuePresentKHR(dev_->queue, &pi);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) stale_ = true;
    else if (r != VK_SUCCESS) ThrowVk(r, "Present", "swap chain", "vkQueuePresentKHR");
  }

 private:
  VkPresentModeKHR ModeFor(uint32_t syncInterval) const {
    auto has = [&](VkPresentModeKHR m) { return std::find(modes_.begin(), modes_.end(), m) != modes_.end(); };
    if (syncInterval == 0) {
      if (has(VK_PRESENT_MODE_IMMEDIATE_KHR)) return VK_PRESENT_MODE_IMMEDIATE_KHR;
      if (has(VK_PRESENT_MODE_MAILBOX_KHR)) return VK_PRESENT_MODE_MAILBOX_KHR;
    }
    return VK_PRESENT_MODE_FIFO_KHR;  // always offered
  }

  static void ImageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                           VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.imageMemoryBarrierCount = 1;
    di.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &di);
  }

  void Recreate(const VkSurfaceCapabilitiesKHR& caps, VkExtent2D extent, VkPresentModeKHR mode) {
    const char* call = "Present";
    // The old images and semaphores may still be in use by the queue.
    dev_->ctx->WaitIdle();
    vkQueueWaitIdle(dev_->queue);
    uint32_t count = std::max(bufferCount_, caps.minImageCount);
    if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);
    VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    ci.surface = surface_;
    ci.minImageCount = count;
    ci.imageFormat = format_;
    ci.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    ci.imageExtent = extent;
    ci.imageArrayLayers = 1;
    ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR) ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR : caps.currentTransform;
    ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR) ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                                                                                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    ci.presentMode = mode;
    ci.clipped = VK_TRUE;
    ci.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VkResult r = vkCreateSwapchainKHR(dev_->device, &ci, nullptr, &created);
    DestroySwapchain(swapchain_);
    swapchain_ = VK_NULL_HANDLE;
    if (r != VK_SUCCESS) ThrowVk(r, call, "swap chain", "vkCreateSwapchainKHR");
    swapchain_ = created;
    uint32_t n = 0;
    vkGetSwapchainImagesKHR(dev_->device, swapchain_, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(dev_->device, swapchain_, &n, images_.data());
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    rendered_.resize(n);
    for (VkSemaphore& s : rendered_) Check(vkCreateSemaphore(dev_->device, &si, nullptr, &s), call, "semaphore", "vkCreateSemaphore");
    // One more acquisition semaphore than images: one can be waited on while all images are held.
    for (VkSemaphore s : acquired_) vkDestroySemaphore(dev_->device, s, nullptr);
    acquired_.resize(n + 1);
    for (VkSemaphore& s : acquired_) Check(vkCreateSemaphore(dev_->device, &si, nullptr, &s), call, "semaphore", "vkCreateSemaphore");
    acquiredSerial_.assign(n + 1, 0);
    next_ = 0;
    extent_ = extent;
    mode_ = mode;
    stale_ = false;
  }

  void DestroySwapchain(VkSwapchainKHR s) {
    for (VkSemaphore r : rendered_) vkDestroySemaphore(dev_->device, r, nullptr);
    rendered_.clear();
    images_.clear();
    if (s) vkDestroySwapchainKHR(dev_->device, s, nullptr);
  }

  VulkanDevice* dev_;
  NativeWindow window_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  std::vector<VkSurfaceFormatKHR> surfaceFormats_;
  std::vector<VkPresentModeKHR> modes_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> rendered_;  // per image: the copy is done, present may read it
  std::vector<VkSemaphore> acquired_;  // per acquisition slot
  std::vector<uint64_t> acquiredSerial_;
  uint32_t next_ = 0;
  uint32_t bufferCount_ = 2;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  VkPresentModeKHR mode_ = VK_PRESENT_MODE_FIFO_KHR;
  bool stale_ = true;
};

}  // namespace

std::unique_ptr<detail::SwapChainBackend> VulkanDevice::CreateSwapChainBackend(const SwapChainDesc& desc, unsigned long) {
  if (!feat.present)
    Throw(ErrorId::INVALID_ARGUMENT, "CreateSwapChain", "vulkan", "the device was created without DeviceDesc::x11Display");
  return std::make_unique<VulkanSwapChain>(this, desc);
}

}  // namespace sp::vk
