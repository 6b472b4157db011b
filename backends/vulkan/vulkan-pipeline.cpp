// Graphics and compute pipelines, built at draw time from the D3D11 state and cached by a byte key
// of everything that shapes them. Viewport, scissor, depth bias, blend factor, stencil reference,
// primitive restart and vertex strides are dynamic, so those D3D11 calls never create pipelines.
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

VkPrimitiveTopology Topology(PRIMITIVE_TOPOLOGY t) {
  switch (t) {
    case PRIMITIVE_TOPOLOGY_POINTLIST: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    case PRIMITIVE_TOPOLOGY_LINELIST: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    case PRIMITIVE_TOPOLOGY_LINESTRIP: return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
    case PRIMITIVE_TOPOLOGY_TRIANGLESTRIP: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    default: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  }
}

VkBlendFactor Factor(BLEND b) {
  switch (b) {
    case BLEND_ZERO: return VK_BLEND_FACTOR_ZERO;
    case BLEND_ONE: return VK_BLEND_FACTOR_ONE;
    case BLEND_SRC_COLOR: return VK_BLEND_FACTOR_SRC_COLOR;
    case BLEND_INV_SRC_COLOR: return VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
    case BLEND_SRC_ALPHA: return VK_BLEND_FACTOR_SRC_ALPHA;
    case BLEND_INV_SRC_ALPHA: return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    case BLEND_DEST_ALPHA: return VK_BLEND_FACTOR_DST_ALPHA;
    case BLEND_INV_DEST_ALPHA: return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
    case BLEND_DEST_COLOR: return VK_BLEND_FACTOR_DST_COLOR;
    case BLEND_INV_DEST_COLOR: return VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR;
    case BLEND_SRC_ALPHA_SAT: return VK_BLEND_FACTOR_SRC_ALPHA_SATURATE;
    case BLEND_BLEND_FACTOR: return VK_BLEND_FACTOR_CONSTANT_COLOR;
    case BLEND_INV_BLEND_FACTOR: return VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR;
    case BLEND_SRC1_COLOR: return VK_BLEND_FACTOR_SRC1_COLOR;
    case BLEND_INV_SRC1_COLOR: return VK_BLEND_FACTOR_ONE_MINUS_SRC1_COLOR;
    case BLEND_SRC1_ALPHA: return VK_BLEND_FACTOR_SRC1_ALPHA;
    case BLEND_INV_SRC1_ALPHA: return VK_BLEND_FACTOR_ONE_MINUS_SRC1_ALPHA;
  }
  return VK_BLEND_FACTOR_ONE;
}

VkBlendOp Op(BLEND_OP o) {
  switch (o) {
    case BLEND_OP_SUBTRACT: return VK_BLEND_OP_SUBTRACT;
    case BLEND_OP_REV_SUBTRACT: return VK_BLEND_OP_REVERSE_SUBTRACT;
    case BLEND_OP_MIN: return VK_BLEND_OP_MIN;
    case BLEND_OP_MAX: return VK_BLEND_OP_MAX;
    default: return VK_BLEND_OP_ADD;
  }
}

VkStencilOp StencilOp(STENCIL_OP o) {
  switch (o) {
    case STENCIL_OP_ZERO: return VK_STENCIL_OP_ZERO;
    case STENCIL_OP_REPLACE: return VK_STENCIL_OP_REPLACE;
    case STENCIL_OP_INCR_SAT: return VK_STENCIL_OP_INCREMENT_AND_CLAMP;
    case STENCIL_OP_DECR_SAT: return VK_STENCIL_OP_DECREMENT_AND_CLAMP;
    case STENCIL_OP_INVERT: return VK_STENCIL_OP_INVERT;
    case STENCIL_OP_INCR: return VK_STENCIL_OP_INCREMENT_AND_WRAP;
    case STENCIL_OP_DECR: return VK_STENCIL_OP_DECREMENT_AND_WRAP;
    default: return VK_STENCIL_OP_KEEP;
  }
}

VkStencilOpState StencilState(const DEPTH_STENCILOP_DESC& f, const DEPTH_STENCIL_DESC& d) {
  VkStencilOpState s{};
  s.failOp = StencilOp(f.StencilFailOp);
  s.passOp = StencilOp(f.StencilPassOp);
  s.depthFailOp = StencilOp(f.StencilDepthFailOp);
  s.compareOp = CompareOp(f.StencilFunc);
  s.compareMask = d.StencilReadMask;
  s.writeMask = d.StencilWriteMask;
  return s;
}

class Key {
 public:
  template <class T>
  void put(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  std::string& str() { return bytes_; }

 private:
  std::string bytes_;
};

bool Blendable(VulkanDevice* dev, VkFormat f) {
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(dev->physical, f, &fp);
  return fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
}

}  // namespace

VkPipeline VulkanContext::GraphicsPipeline(const PipelineState& s, VkPipelineLayout layout, const char* call) {
  VkShaderObj& vs = detail::BackendAs<VkShaderObj>(s.stage(ShaderStage::Vertex).shader);
  VkShaderObj* ps = s.stage(ShaderStage::Pixel).shader ? &detail::BackendAs<VkShaderObj>(s.stage(ShaderStage::Pixel).shader) : nullptr;
  const RASTERIZER_DESC& rd = s.rasterizer();
  DEPTH_STENCIL_DESC dd = s.depthStencilDesc();
  const BLEND_DESC& bd = s.blend();

  uint32_t colorCount = 0;
  for (uint32_t i = 0; i < s.numRenderTargets && i < SIMULTANEOUS_RENDER_TARGET_COUNT; ++i)
    if (s.renderTargets[i]) colorCount = i + 1;
  std::array<VkFormat, SIMULTANEOUS_RENDER_TARGET_COUNT> formats{};
  uint32_t samples = 1;
  for (uint32_t i = 0; i < colorCount; ++i) {
    if (!s.renderTargets[i]) continue;
    const VkViewObj& v = ViewOf(s.renderTargets[i].get());
    formats[i] = v.format;
    samples = v.texture->shape.sampleCount;
  }
  VkFormat dsFormat = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags dsAspects = 0;
  if (s.depthStencil) {
    const VkViewObj& dv = ViewOf(s.depthStencil.get());
    dsFormat = dv.format;
    dsAspects = dv.texture->aspects;
    samples = dv.texture->shape.sampleCount;
    // A read-only aspect is bound in a read-only layout, where Vulkan forbids writes.
    if (dv.depthReadOnly) dd.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
    if (dv.stencilReadOnly) dd.StencilWriteMask = 0;
    if (!(dsAspects & VK_IMAGE_ASPECT_STENCIL_BIT)) dd.StencilEnable = false;
  } else {
    dd.DepthEnable = false;
    dd.StencilEnable = false;
  }
  if (!dd.DepthEnable) dd.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;

  std::array<VkPipelineColorBlendAttachmentState, SIMULTANEOUS_RENDER_TARGET_COUNT> blends{};
  bool dualSource = false;
  for (uint32_t i = 0; i < colorCount; ++i) {
    const RENDER_TARGET_BLEND_DESC& rt = bd.IndependentBlendEnable ? bd.RenderTarget[i] : bd.RenderTarget[0];
    VkPipelineColorBlendAttachmentState& b = blends[i];
    // Targets the pixel shader does not write keep their contents (a zero mask) where the
    // device allows attachments to differ.
    bool written = ps && (!dev_->feat.independentBlend || ((ps->writtenTargets & (1u << i)) && formats[i] != VK_FORMAT_UNDEFINED));
    b.colorWriteMask = written ? VkColorComponentFlags(rt.RenderTargetWriteMask) : 0;
    if (rt.BlendEnable && b.colorWriteMask && Blendable(dev_, formats[i])) {
      b.blendEnable = VK_TRUE;
      b.srcColorBlendFactor = Factor(rt.SrcBlend);
      b.dstColorBlendFactor = Factor(rt.DestBlend);
      b.colorBlendOp = Op(rt.BlendOp);
      b.srcAlphaBlendFactor = Factor(rt.SrcBlendAlpha);
      b.dstAlphaBlendFactor = Factor(rt.DestBlendAlpha);
      b.alphaBlendOp = Op(rt.BlendOpAlpha);
      if (i == 0) dualSource = BlendReadsSource1(rt);
    }
  }
  if (dualSource && !dev_->feat.dualSrcBlend) Throw(ErrorId::NOT_SUPPORTED, call, "BlendState", "dual-source blending (SRC1 factors) needs dualSrcBlend, which this device lacks");
  if (dualSource && colorCount > dev_->props.limits.maxFragmentDualSrcAttachments)
    Throw(ErrorId::NOT_SUPPORTED, call, "BlendState", "dual-source blending with " + std::to_string(colorCount) + " render targets bound; this device allows " +
                                                      std::to_string(dev_->props.limits.maxFragmentDualSrcAttachments));
  if (rd.FillMode == FILL_WIREFRAME && !dev_->feat.fillModeNonSolid)
    Throw(ErrorId::NOT_SUPPORTED, call, "RasterizerState", "FILL_WIREFRAME needs fillModeNonSolid, which this device lacks");

  static const std::vector<VertexAttribute> kNoAttributes;
  const std::vector<VertexAttribute>& attrs = s.inputLayout ? s.inputLayout->Attributes() : kNoAttributes;
  bool usesInputs = false;
  for (const SignatureElement& in : s.stage(ShaderStage::Vertex).shader->Reflection().inputs) usesInputs |= !in.systemValue;

  Key k;
  k.put(vs.uid);
  k.put(ps ? ps->uid : uint64_t(0));
  k.put(s.topology);
  if (usesInputs) {
    for (const VertexAttribute& a : attrs) {
      k.put(a.location), k.put(a.format), k.put(a.slot), k.put(a.offset), k.put(a.perInstance), k.put(a.stepRate);
    }
  }
  k.put(uint32_t(0xffffffff));
  k.put(rd.FillMode), k.put(rd.CullMode), k.put(rd.FrontCounterClockwise), k.put(rd.DepthClipEnable);
  k.put(dd.DepthEnable), k.put(dd.DepthWriteMask), k.put(dd.DepthFunc), k.put(dd.StencilEnable), k.put(dd.StencilReadMask), k.put(dd.StencilWriteMask);
  k.put(dd.FrontFace), k.put(dd.BackFace);
  k.put(bd.AlphaToCoverageEnable), k.put(s.sampleMask), k.put(colorCount), k.put(dualSource);
  for (uint32_t i = 0; i < colorCount; ++i) k.put(formats[i]), k.put(blends[i]);
  k.put(dsFormat), k.put(samples);
  if (VkPipeline p = dev_->FindPipeline(k.str())) return p;

  VkPipelineShaderStageCreateInfo stages[2]{};
  VkShaderModule vsModule = s.topology == PRIMITIVE_TOPOLOGY_POINTLIST ? vs.PointSizeModule() : vs.module;
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vsModule, vs.entry.c_str(), nullptr};
  uint32_t stageCount = 1;
  if (ps) {
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT,
                 dualSource && ps->hasTarget1 ? ps->DualSourceModule() : ps->module, ps->entry.c_str(), nullptr};
    stageCount = 2;
  }

  std::vector<VkVertexInputBindingDescription> vbind;
  std::vector<VkVertexInputAttributeDescription> vattr;
  std::vector<VkVertexInputBindingDivisorDescriptionEXT> divisors;
  if (usesInputs) {
    for (const VertexAttribute& a : attrs) {
      vattr.push_back({a.location, a.slot, VkFormatOf(a.format), a.offset});
      bool known = false;
      for (const auto& b : vbind) known |= b.binding == a.slot;
      if (known) continue;
      vbind.push_back({a.slot, 0, a.perInstance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
      if (a.perInstance && a.stepRate != 1) {
        if (!dev_->feat.divisor || (a.stepRate == 0 && !dev_->feat.divisorZero))
          Throw(ErrorId::NOT_SUPPORTED, call, DescribeObject(s.inputLayout.get()),
                "InstanceDataStepRate " + std::to_string(a.stepRate) + " needs VK_EXT_vertex_attribute_divisor" + (a.stepRate == 0 ? " with zero divisors" : ""));
        divisors.push_back({a.slot, a.stepRate});
      }
    }
  }
  VkPipelineVertexInputDivisorStateCreateInfoEXT div{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_DIVISOR_STATE_CREATE_INFO_EXT};
  div.vertexBindingDivisorCount = uint32_t(divisors.size());
  div.pVertexBindingDivisors = divisors.data();
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (!divisors.empty()) vi.pNext = &div;
  vi.vertexBindingDescriptionCount = uint32_t(vbind.size());
  vi.pVertexBindingDescriptions = vbind.data();
  vi.vertexAttributeDescriptionCount = uint32_t(vattr.size());
  vi.pVertexAttributeDescriptions = vattr.data();

  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = Topology(s.topology);
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};

  VkPipelineRasterizationDepthClipStateCreateInfoEXT clip{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_DEPTH_CLIP_STATE_CREATE_INFO_EXT};
  clip.depthClipEnable = rd.DepthClipEnable;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  if (dev_->feat.depthClipEnable && dev_->feat.depthClamp) {
    // D3D11 always clamps depth to the viewport range and clips only when DepthClipEnable.
    rs.pNext = &clip;
    rs.depthClampEnable = VK_TRUE;
  } else {
    rs.depthClampEnable = !rd.DepthClipEnable && dev_->feat.depthClamp;
  }
  rs.polygonMode = rd.FillMode == FILL_WIREFRAME ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
  rs.cullMode = rd.CullMode == CULL_FRONT ? VK_CULL_MODE_FRONT_BIT : rd.CullMode == CULL_BACK ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
  rs.frontFace = rd.FrontCounterClockwise ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE;
  rs.lineWidth = 1.0f;

  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VkSampleCountFlagBits(samples);
  VkSampleMask mask = s.sampleMask;
  ms.pSampleMask = &mask;
  ms.alphaToCoverageEnable = bd.AlphaToCoverageEnable && colorCount > 0;

  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = dd.DepthEnable;
  ds.depthWriteEnable = dd.DepthWriteMask == DEPTH_WRITE_MASK_ALL;
  ds.depthCompareOp = CompareOp(dd.DepthFunc);
  ds.stencilTestEnable = dd.StencilEnable;
  ds.front = StencilState(dd.FrontFace, dd);
  ds.back = StencilState(dd.BackFace, dd);

  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = colorCount;
  cb.pAttachments = blends.data();

  const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT_WITH_COUNT, VK_DYNAMIC_STATE_SCISSOR_WITH_COUNT, VK_DYNAMIC_STATE_DEPTH_BIAS,
                                VK_DYNAMIC_STATE_DEPTH_BIAS_ENABLE,   VK_DYNAMIC_STATE_BLEND_CONSTANTS,  VK_DYNAMIC_STATE_STENCIL_REFERENCE,
                                VK_DYNAMIC_STATE_PRIMITIVE_RESTART_ENABLE,   VK_DYNAMIC_STATE_VERTEX_INPUT_BINDING_STRIDE};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  // The stride state goes last: without vertex bindings it is left out, since the validation
  // layers then still demand a vkCmdBindVertexBuffers2 call.
  dy.dynamicStateCount = uint32_t(std::size(dyn)) - (vbind.empty() ? 1 : 0);
  dy.pDynamicStates = dyn;

  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = colorCount;
  ri.pColorAttachmentFormats = formats.data();
  ri.depthAttachmentFormat = (dsAspects & VK_IMAGE_ASPECT_DEPTH_BIT) ? dsFormat : VK_FORMAT_UNDEFINED;
  ri.stencilAttachmentFormat = (dsAspects & VK_IMAGE_ASPECT_STENCIL_BIT) ? dsFormat : VK_FORMAT_UNDEFINED;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &ri;
  ci.stageCount = stageCount;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = layout;
  VkPipeline p;
  VkResult r = vkCreateGraphicsPipelines(dev_->device, dev_->pipelineCache, 1, &ci, nullptr, &p);
  if (r != VK_SUCCESS)
    ThrowVk(r, call, DescribeObject(s.stage(ShaderStage::Vertex).shader.get()) + (ps ? " + " + DescribeObject(s.stage(ShaderStage::Pixel).shader.get()) : ""),
            "vkCreateGraphicsPipelines");
  dev_->AddPipeline(k.str(), p, vs.uid, ps ? ps->uid : 0);
  return p;
}

VkPipeline VulkanContext::ComputePipeline(const VkShaderObj& cs, const char* call) {
  Key k;
  k.put('C');
  k.put(cs.uid);
  if (VkPipeline p = dev_->FindPipeline(k.str())) return p;
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, cs.module, cs.entry.c_str(), nullptr};
  ci.layout = cs.computeLayout;
  VkPipeline p;
  Check(vkCreateComputePipelines(dev_->device, dev_->pipelineCache, 1, &ci, nullptr, &p), call, DescribeObject(cs.owner), "vkCreateComputePipelines");
  dev_->AddPipeline(k.str(), p, cs.uid, 0);
  return p;
}

}  // namespace sp::vk
