// The Vulkan device: instance and validation messenger, physical device choice, features, queue,
// DeviceInfo, deferred destruction and the layout/pipeline caches.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {

const char* ResultName(VkResult r) {
  switch (r) {
#define SP_R(x) \
  case x: return #x;
    SP_R(VK_SUCCESS) SP_R(VK_NOT_READY) SP_R(VK_TIMEOUT) SP_R(VK_INCOMPLETE) SP_R(VK_ERROR_OUT_OF_HOST_MEMORY)
    SP_R(VK_ERROR_OUT_OF_DEVICE_MEMORY) SP_R(VK_ERROR_INITIALIZATION_FAILED) SP_R(VK_ERROR_DEVICE_LOST)
    SP_R(VK_ERROR_MEMORY_MAP_FAILED) SP_R(VK_ERROR_LAYER_NOT_PRESENT) SP_R(VK_ERROR_EXTENSION_NOT_PRESENT)
    SP_R(VK_ERROR_FEATURE_NOT_PRESENT) SP_R(VK_ERROR_INCOMPATIBLE_DRIVER) SP_R(VK_ERROR_TOO_MANY_OBJECTS)
    SP_R(VK_ERROR_FORMAT_NOT_SUPPORTED) SP_R(VK_ERROR_FRAGMENTED_POOL) SP_R(VK_ERROR_OUT_OF_POOL_MEMORY)
    SP_R(VK_ERROR_UNKNOWN)
#undef SP_R
    default: return "VkResult(?)";
  }
}

void ThrowVk(VkResult r, const char* call, const std::string& object, const char* what) {
  ErrorId id = ErrorId::DEVICE_API_ERROR;
  std::string detail = std::string(what) + " returned " + ResultName(r) + " (" + std::to_string(int(r)) + ")";
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY) {
    id = ErrorId::OUT_OF_MEMORY;
    detail += ": the device ran out of memory";
  } else if (r == VK_ERROR_FORMAT_NOT_SUPPORTED) {
    id = ErrorId::FORMAT_UNSUPPORTED;
  }
  throw Error(id, call, object, detail);
}

void Throw(ErrorId id, const char* call, const std::string& object, const std::string& detail) {
  throw Error(id, call, object, detail);
}

std::string DescribeObject(const Object* o) { return o ? o->Describe() : std::string("null"); }

namespace {

bool HasExtension(const std::vector<VkExtensionProperties>& exts, const char* name) {
  return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

VKAPI_ATTR VkBool32 VKAPI_CALL OnDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  // Performance notes and INFO/VERBOSE chatter are not D3D debug-layer material.
  if (type == VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) return VK_FALSE;
  MessageSeverity s;
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) s = MessageSeverity::Error;
  else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) s = MessageSeverity::Warning;
  else return VK_FALSE;
  std::string text = "Vulkan validation: ";
  if (data->pMessageIdName) text += std::string("[") + data->pMessageIdName + "] ";
  if (data->pMessage) text += data->pMessage;
  static_cast<VulkanDevice*>(user)->Message(s, text);
  return VK_FALSE;
}

std::string Lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

VulkanDevice::VulkanDevice(Device& core, const DeviceDesc& desc) : DeviceBackend(core) {
  try {
    CreateInstance(desc.debug, desc.x11Display != nullptr);
    PickPhysicalDevice();
    CreateLogicalDevice(!desc.disableVsRenderTargetArrayIndex);
    if (desc.disableDepthBiasClamp) info_.depthBiasClamp = false;
    FillInfo();
    alloc.Init(this);
    VkPipelineCacheCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    Check(vkCreatePipelineCache(device, &pci, nullptr, &pipelineCache), "CreateDevice", "vulkan", "vkCreatePipelineCache");
  } catch (...) {
    Teardown();
    throw;
  }
}

std::unique_ptr<detail::ContextBackend> VulkanDevice::CreateContextBackend() {
  auto context = std::make_unique<VulkanContext>(this);
  ctx = context.get();
  return context;
}

VulkanDevice::~VulkanDevice() { Teardown(); }

// The core has destroyed the context and released every object's Vulkan data before this runs;
// their destruction is deferred until the GPU is done with them, which is now.
void VulkanDevice::Teardown() {
  if (device) {
    vkDeviceWaitIdle(device);
    completedSerial = recordingSerial;
    RunDeferred();
    for (auto& [key, e] : pipelines_) vkDestroyPipeline(device, e.pipeline, nullptr);
    pipelines_.clear();
    for (auto& [key, l] : pipelineLayouts_) vkDestroyPipelineLayout(device, l, nullptr);
    pipelineLayouts_.clear();
    for (auto& [key, l] : setLayouts_) vkDestroyDescriptorSetLayout(device, l, nullptr);
    setLayouts_.clear();
    if (pipelineCache) vkDestroyPipelineCache(device, pipelineCache, nullptr);
    pipelineCache = VK_NULL_HANDLE;
    alloc.Shutdown();
    vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
  }
  if (messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
    messenger = VK_NULL_HANDLE;
  }
  if (instance) vkDestroyInstance(instance, nullptr);
  instance = VK_NULL_HANDLE;
}

void VulkanDevice::CreateInstance(bool debug, bool present) {
  const char* call = "CreateDevice";
  uint32_t loaderVersion = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&loaderVersion);
  if (loaderVersion < VK_API_VERSION_1_3)
    Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", "the Vulkan loader supports only " + std::to_string(VK_API_VERSION_MAJOR(loaderVersion)) + "." +
                                                                 std::to_string(VK_API_VERSION_MINOR(loaderVersion)) + "; Vulkan 1.3 is required");
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());

  std::vector<const char*> enabledLayers, enabledExts;
  bool validation = false;
  if (debug) {
    validation = std::any_of(layers.begin(), layers.end(), [](const VkLayerProperties& l) { return std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0; });
    if (validation) enabledLayers.push_back("VK_LAYER_KHRONOS_validation");
    else Message(MessageSeverity::Warning, "VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers); running without validation");
  }
  feat.debugUtils = HasExtension(exts, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (validation && !feat.debugUtils) {
    // The layer provides the extension itself.
    uint32_t m = 0;
    vkEnumerateInstanceExtensionProperties("VK_LAYER_KHRONOS_validation", &m, nullptr);
    std::vector<VkExtensionProperties> le(m);
    vkEnumerateInstanceExtensionProperties("VK_LAYER_KHRONOS_validation", &m, le.data());
    feat.debugUtils = HasExtension(le, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  if (validation && feat.debugUtils) enabledExts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (present) {
    // Named as strings: their headers need Xlib's, which only the swap-chain code includes.
    for (const char* name : {"VK_KHR_surface", "VK_KHR_xlib_surface"}) {
      if (!HasExtension(exts, name))
        Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", std::string("DeviceDesc::x11Display is set but the Vulkan loader lacks ") + name);
      enabledExts.push_back(name);
    }
    feat.present = true;
  }
  info_.validationEnabled = validation && feat.debugUtils;

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "ShadowPort";
  app.pEngineName = "ShadowPort";
  app.apiVersion = VK_API_VERSION_1_3;
  VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  mci.pfnUserCallback = OnDebugMessage;
  mci.pUserData = this;
  // SHADOWPORT_VK_SYNC_VALIDATION=1 adds the synchronization validator (slow; for backend work).
  VkValidationFeatureEnableEXT syncFeature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT vf{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  vf.enabledValidationFeatureCount = 1;
  vf.pEnabledValidationFeatures = &syncFeature;
  const char* sync = std::getenv("SHADOWPORT_VK_SYNC_VALIDATION");
  if (info_.validationEnabled && sync && std::strcmp(sync, "1") == 0) mci.pNext = &vf;

  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = uint32_t(enabledLayers.size());
  ici.ppEnabledLayerNames = enabledLayers.data();
  ici.enabledExtensionCount = uint32_t(enabledExts.size());
  ici.ppEnabledExtensionNames = enabledExts.data();
  if (info_.validationEnabled) ici.pNext = &mci;
  VkResult r = vkCreateInstance(&ici, nullptr, &instance);
  if (r != VK_SUCCESS)
    Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", std::string("vkCreateInstance returned ") + ResultName(r) + " (is a Vulkan driver installed?)");
  if (info_.validationEnabled) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    mci.pNext = nullptr;
    if (create) Check(create(instance, &mci, nullptr, &messenger), call, "vulkan", "vkCreateDebugUtilsMessengerEXT");
  }
  if (feat.debugUtils && info_.validationEnabled)
    setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
}

void VulkanDevice::PickPhysicalDevice() {
  const char* call = "CreateDevice";
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(instance, &n, devices.data());
  if (devices.empty()) Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", "no Vulkan physical device (install mesa-vulkan-drivers for lavapipe)");

  auto usable = [](VkPhysicalDevice pd, VkPhysicalDeviceProperties& p) {
    vkGetPhysicalDeviceProperties(pd, &p);
    if (p.apiVersion < VK_API_VERSION_1_3) return false;
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> q(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, q.data());
    return std::any_of(q.begin(), q.end(), [](const VkQueueFamilyProperties& f) {
      return (f.queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT);
    });
  };
  std::string names;
  for (VkPhysicalDevice pd : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    names += (names.empty() ? "" : ", ") + std::string(p.deviceName);
  }

  if (const char* sel = std::getenv("SHADOWPORT_VK_DEVICE"); sel && *sel) {
    std::string s = sel;
    bool isIndex = std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
    for (size_t i = 0; i < devices.size(); ++i) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devices[i], &p);
      bool match = isIndex ? std::stoul(s) == i : Lower(p.deviceName).find(Lower(s)) != std::string::npos;
      if (!match) continue;
      if (!usable(devices[i], p))
        Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", "SHADOWPORT_VK_DEVICE selects '" + std::string(p.deviceName) + "', which lacks Vulkan 1.3 or a graphics+compute queue");
      physical = devices[i];
      break;
    }
    if (!physical) Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", "SHADOWPORT_VK_DEVICE='" + s + "' matches none of: " + names);
  } else {
    auto rank = [](VkPhysicalDeviceType t) {
      switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
      }
    };
    int best = -1;
    for (VkPhysicalDevice pd : devices) {
      VkPhysicalDeviceProperties p;
      if (!usable(pd, p)) continue;
      if (rank(p.deviceType) > best) {
        best = rank(p.deviceType);
        physical = pd;
      }
    }
    if (!physical) Throw(ErrorId::DEVICE_CREATION_FAILED, call, "vulkan", "no physical device supports Vulkan 1.3 with a graphics+compute queue (found: " + names + ")");
  }
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props13 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
  p2.pNext = &props13;
  vkGetPhysicalDeviceProperties2(physical, &p2);
  props = p2.properties;
  props13.pNext = nullptr;
  vkGetPhysicalDeviceMemoryProperties(physical, &memProps);
}

void VulkanDevice::CreateLogicalDevice(bool allowLayerOutput) {
  const char* call = "CreateDevice";
  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> qf(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &qn, qf.data());
  for (uint32_t i = 0; i < qn; ++i) {
    if ((qf[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
      queueFamily = i;
      break;
    }
  }
  if (qf[queueFamily].timestampValidBits == 0)
    Message(MessageSeverity::Warning, "the Vulkan queue has no timestamp support; TIMESTAMP queries will read 0");

  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, exts.data());

  // What the driver has.
  VkPhysicalDeviceDepthClipEnableFeaturesEXT clip{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT};
  VkPhysicalDeviceCustomBorderColorFeaturesEXT border{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CUSTOM_BORDER_COLOR_FEATURES_EXT};
  VkPhysicalDeviceRobustness2FeaturesEXT robust{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
  VkPhysicalDeviceVertexAttributeDivisorFeaturesEXT divisor{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_ATTRIBUTE_DIVISOR_FEATURES_EXT};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f11;
  f11.pNext = &f12;
  f12.pNext = &f13;
  void** tail = &f13.pNext;
  auto chain = [&](bool present, auto& s) {
    if (!present) return;
    *tail = &s;
    tail = &s.pNext;
  };
  bool hasClip = HasExtension(exts, VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME);
  bool hasBorder = HasExtension(exts, VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME);
  bool hasRobust = HasExtension(exts, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME);
  bool hasDivisor = HasExtension(exts, VK_EXT_VERTEX_ATTRIBUTE_DIVISOR_EXTENSION_NAME);
  chain(hasClip, clip);
  chain(hasBorder, border);
  chain(hasRobust, robust);
  chain(hasDivisor, divisor);
  vkGetPhysicalDeviceFeatures2(physical, &f2);
  if (!f13.dynamicRendering || !f13.synchronization2)
    Throw(ErrorId::DEVICE_CREATION_FAILED, call, props.deviceName, "the device lacks dynamicRendering or synchronization2 (Vulkan 1.3 core features)");

  // What is enabled: everything D3D11 semantics need that exists.
  const VkPhysicalDeviceFeatures& a = f2.features;
  VkPhysicalDeviceFeatures e{};
  e.robustBufferAccess = a.robustBufferAccess;
  e.samplerAnisotropy = a.samplerAnisotropy;
  e.depthClamp = a.depthClamp;
  e.depthBiasClamp = a.depthBiasClamp;
  e.fillModeNonSolid = a.fillModeNonSolid;
  e.independentBlend = a.independentBlend;
  e.dualSrcBlend = a.dualSrcBlend;
  e.imageCubeArray = a.imageCubeArray;
  e.fragmentStoresAndAtomics = a.fragmentStoresAndAtomics;
  e.shaderStorageImageWriteWithoutFormat = a.shaderStorageImageWriteWithoutFormat;
  e.shaderStorageImageReadWithoutFormat = a.shaderStorageImageReadWithoutFormat;
  e.shaderStorageImageExtendedFormats = a.shaderStorageImageExtendedFormats;
  e.shaderImageGatherExtended = a.shaderImageGatherExtended;
  e.drawIndirectFirstInstance = a.drawIndirectFirstInstance;
  e.occlusionQueryPrecise = a.occlusionQueryPrecise;
  e.shaderClipDistance = a.shaderClipDistance;
  e.shaderCullDistance = a.shaderCullDistance;
  e.sampleRateShading = a.sampleRateShading;
  e.fullDrawIndexUint32 = a.fullDrawIndexUint32;
  e.shaderFloat64 = a.shaderFloat64;
  f2.features = e;

  VkPhysicalDeviceVulkan11Features e11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  e11.shaderDrawParameters = f11.shaderDrawParameters;
  VkPhysicalDeviceVulkan12Features e12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  e12.hostQueryReset = f12.hostQueryReset;
  e12.samplerFilterMinmax = f12.samplerFilterMinmax;
  e12.samplerMirrorClampToEdge = f12.samplerMirrorClampToEdge;
  e12.scalarBlockLayout = f12.scalarBlockLayout;
  e12.uniformBufferStandardLayout = f12.uniformBufferStandardLayout;
  e12.separateDepthStencilLayouts = f12.separateDepthStencilLayouts;
  // glslang declares a vertex shader's SV_RenderTargetArrayIndex with the EXT capability
  // (ShaderViewportIndexLayerEXT), which Vulkan ties to the extension; Vulkan 1.2's features
  // cover ShaderLayer / ShaderViewportIndex. Enable both where offered.
  const bool layerOutput = allowLayerOutput && f12.shaderOutputLayer && f12.shaderOutputViewportIndex;
  e12.shaderOutputLayer = layerOutput;
  e12.shaderOutputViewportIndex = layerOutput;
  VkPhysicalDeviceVulkan13Features e13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  e13.dynamicRendering = VK_TRUE;
  e13.synchronization2 = VK_TRUE;
  e13.robustImageAccess = f13.robustImageAccess;
  e13.maintenance4 = f13.maintenance4;
  e13.shaderDemoteToHelperInvocation = f13.shaderDemoteToHelperInvocation;
  e13.shaderTerminateInvocation = f13.shaderTerminateInvocation;
  if (!f12.hostQueryReset) Throw(ErrorId::DEVICE_CREATION_FAILED, call, props.deviceName, "the device lacks hostQueryReset (Vulkan 1.2 core)");

  f2.pNext = &e11;
  e11.pNext = &e12;
  e12.pNext = &e13;
  tail = &e13.pNext;
  std::vector<const char*> enabled;
  if (hasClip && clip.depthClipEnable) {
    chain(true, clip);
    enabled.push_back(VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME);
    feat.depthClipEnable = true;
  }
  if (hasBorder && border.customBorderColors && border.customBorderColorWithoutFormat) {
    chain(true, border);
    enabled.push_back(VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME);
    feat.customBorderColor = true;
  }
  if (hasRobust) {
    // robustBufferAccess2 needs robustBufferAccess; D3D11 reads 0 out of bounds either way.
    if (!e.robustBufferAccess) robust.robustBufferAccess2 = VK_FALSE;
    if (!e13.robustImageAccess) robust.robustImageAccess2 = VK_FALSE;
    if (robust.robustBufferAccess2 || robust.robustImageAccess2 || robust.nullDescriptor) {
      chain(true, robust);
      enabled.push_back(VK_EXT_ROBUSTNESS_2_EXTENSION_NAME);
      feat.robustness2 = robust.robustBufferAccess2;
      feat.nullDescriptor = robust.nullDescriptor;
    }
  }
  if (hasDivisor && divisor.vertexAttributeInstanceRateDivisor) {
    chain(true, divisor);
    enabled.push_back(VK_EXT_VERTEX_ATTRIBUTE_DIVISOR_EXTENSION_NAME);
    feat.divisor = true;
    feat.divisorZero = divisor.vertexAttributeInstanceRateZeroDivisor;
  }
  if (feat.present) {
    if (!HasExtension(exts, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
      Throw(ErrorId::DEVICE_CREATION_FAILED, call, props.deviceName, "DeviceDesc::x11Display is set but the device lacks VK_KHR_swapchain");
    enabled.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  }
  if (layerOutput && HasExtension(exts, VK_EXT_SHADER_VIEWPORT_INDEX_LAYER_EXTENSION_NAME))
    enabled.push_back(VK_EXT_SHADER_VIEWPORT_INDEX_LAYER_EXTENSION_NAME);
  info_.vsRenderTargetArrayIndex = layerOutput;
  feat.samplerMinmax = e12.samplerFilterMinmax;
  feat.depthClamp = e.depthClamp;
  feat.depthBiasClamp = e.depthBiasClamp;
  info_.depthBiasClamp = feat.depthBiasClamp;
  feat.fillModeNonSolid = e.fillModeNonSolid;
  feat.dualSrcBlend = e.dualSrcBlend;
  feat.independentBlend = e.independentBlend;
  feat.anisotropy = e.samplerAnisotropy;
  feat.cubeArray = e.imageCubeArray;
  feat.occlusionPrecise = e.occlusionQueryPrecise;
  feat.storageWriteWithoutFormat = e.shaderStorageImageWriteWithoutFormat;
  feat.storageReadWithoutFormat = e.shaderStorageImageReadWithoutFormat;
  feat.drawIndirectFirstInstance = e.drawIndirectFirstInstance;
  feat.drawParameters = e11.shaderDrawParameters;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &f2;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = uint32_t(enabled.size());
  dci.ppEnabledExtensionNames = enabled.data();
  VkResult r = vkCreateDevice(physical, &dci, nullptr, &device);
  if (r != VK_SUCCESS) Throw(ErrorId::DEVICE_CREATION_FAILED, call, props.deviceName, std::string("vkCreateDevice returned ") + ResultName(r));
  vkGetDeviceQueue(device, queueFamily, 0, &queue);
}

void VulkanDevice::FillInfo() {
  info_.apiVersion = "Vulkan " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." + std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) +
                     "." + std::to_string(VK_API_VERSION_PATCH(props.apiVersion));
  info_.deviceName = props.deviceName;
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  p2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(physical, &p2);
  feat.indirectIgnoresIndexOffset = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
  info_.driverName = driver.driverInfo[0] ? std::string(driver.driverInfo) : std::string(driver.driverName);
  if (driver.driverInfo[0] && driver.driverName[0] && info_.driverName.find("Mesa") == std::string::npos &&
      std::strstr(driver.driverInfo, driver.driverName) == nullptr)
    info_.driverName = std::string(driver.driverName) + " " + driver.driverInfo;
  info_.timestampFrequency = props.limits.timestampPeriod > 0 ? uint64_t(1e9 / double(props.limits.timestampPeriod) + 0.5) : 0;
  VkSampleCountFlags counts = props.limits.framebufferColorSampleCounts & props.limits.framebufferDepthSampleCounts;
  info_.maxMsaaSamples = 1;
  for (uint32_t s : {2u, 4u, 8u})
    if (counts & s) info_.maxMsaaSamples = s;
}

// ---------------------------------------------------------------------------------------------
// Deferred destruction

void VulkanDevice::Defer(uint64_t serial, std::function<void()> destroy) {
  if (serial <= completedSerial || !device) {
    destroy();
    return;
  }
  deferred_.emplace(serial, std::move(destroy));
}

void VulkanDevice::RunDeferred() {
  while (!deferred_.empty() && deferred_.begin()->first <= completedSerial) {
    auto fn = std::move(deferred_.begin()->second);
    deferred_.erase(deferred_.begin());
    fn();
  }
}

void VulkanDevice::Name(VkObjectType type, uint64_t handle, const std::string& name) {
  if (!setObjectName || name.empty()) return;
  VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  ni.objectType = type;
  ni.objectHandle = handle;
  ni.pObjectName = name.c_str();
  setObjectName(device, &ni);
}

// ---------------------------------------------------------------------------------------------
// Layout and pipeline caches

VkDescriptorSetLayout VulkanDevice::SetLayout(const std::vector<ShaderBinding>& bindings, VkShaderStageFlags stages) {
  std::string key(reinterpret_cast<const char*>(&stages), sizeof(stages));
  std::vector<VkDescriptorSetLayoutBinding> vb;
  for (const ShaderBinding& b : bindings) {
    key.append(reinterpret_cast<const char*>(&b.binding), sizeof(b.binding));
    key.append(reinterpret_cast<const char*>(&b.type), sizeof(b.type));
    vb.push_back({b.binding, b.type, 1, stages, nullptr});
  }
  auto it = setLayouts_.find(key);
  if (it != setLayouts_.end()) return it->second;
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = uint32_t(vb.size());
  ci.pBindings = vb.data();
  VkDescriptorSetLayout l;
  Check(vkCreateDescriptorSetLayout(device, &ci, nullptr, &l), "CreateShader", "descriptor set layout", "vkCreateDescriptorSetLayout");
  setLayouts_[key] = l;
  return l;
}

VkPipelineLayout VulkanDevice::PipelineLayout(const std::vector<VkDescriptorSetLayout>& sets) {
  auto it = pipelineLayouts_.find(sets);
  if (it != pipelineLayouts_.end()) return it->second;
  VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  ci.setLayoutCount = uint32_t(sets.size());
  ci.pSetLayouts = sets.data();
  VkPipelineLayout l;
  Check(vkCreatePipelineLayout(device, &ci, nullptr, &l), "Draw", "pipeline layout", "vkCreatePipelineLayout");
  pipelineLayouts_[sets] = l;
  return l;
}

VkPipeline VulkanDevice::FindPipeline(const std::string& key) const {
  auto it = pipelines_.find(key);
  return it == pipelines_.end() ? VK_NULL_HANDLE : it->second.pipeline;
}

void VulkanDevice::AddPipeline(const std::string& key, VkPipeline p, uint64_t shaderA, uint64_t shaderB) {
  pipelines_[key] = {p, shaderA, shaderB};
}

void VulkanDevice::ForgetShader(uint64_t uid) {
  for (auto it = pipelines_.begin(); it != pipelines_.end();) {
    if (it->second.shaderA == uid || it->second.shaderB == uid) {
      VkPipeline p = it->second.pipeline;
      VkDevice d = device;
      Defer(recordingSerial, [d, p] { vkDestroyPipeline(d, p, nullptr); });
      it = pipelines_.erase(it);
    } else {
      ++it;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Backend hooks

std::unique_ptr<detail::BackendObject> VulkanDevice::CreateBufferBackend(Buffer& buffer, const SUBRESOURCE_DATA* init) {
  return CreateBufferObj(this, buffer, init);
}
std::unique_ptr<detail::BackendObject> VulkanDevice::CreateTextureBackend(Texture& texture, const SUBRESOURCE_DATA* init) {
  return CreateTextureObj(this, texture, init);
}
std::unique_ptr<detail::BackendObject> VulkanDevice::CreateViewBackend(View& view) { return CreateViewObj(this, view); }
std::unique_ptr<detail::BackendObject> VulkanDevice::CreateSamplerBackend(SamplerState& sampler) { return CreateSamplerObj(this, sampler); }
std::unique_ptr<detail::BackendObject> VulkanDevice::CreateShaderBackend(Shader& shader) { return CreateShaderObj(this, shader); }
std::unique_ptr<detail::BackendObject> VulkanDevice::CreateQueryBackend(Query& query) { return CreateQueryObj(this, query); }

}  // namespace sp::vk

namespace sp::detail {
std::unique_ptr<DeviceBackend> CreateVulkanBackend(Device& core, const DeviceDesc& desc) { return std::make_unique<vk::VulkanDevice>(core, desc); }
}  // namespace sp::detail
