// The raw Vulkan side of every case, as a careful engine records it: pipelines created up front
// (one per state combination), descriptor sets written once (one per texture/sampler or UAV
// combination), constants in a persistently mapped ring bound by dynamic offset, one command
// buffer and one submit per iteration.
#include <cstring>
#include <stdexcept>

#include "bench-cases.h"
#include "raw-vulkan.h"

namespace spbench {
namespace {

VkDeviceSize AlignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

// Per-draw constants: written at `slot * stride` of a mapped buffer, bound by dynamic offset.
class Ring {
 public:
  Ring(RawVulkan& vk, VkDeviceSize elementSize, uint32_t count)
      : size_(elementSize), stride_(AlignUp(elementSize, vk.uniformAlignment())) {
    buffer_ = vk.CreateBuffer(stride_ * count, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  }
  uint32_t Push(const void* value) {
    std::memcpy(buffer_.mapped + offset_, value, size_);
    uint32_t at = uint32_t(offset_);
    offset_ += stride_;
    return at;
  }
  void Reset() { offset_ = 0; }
  VkDescriptorBufferInfo Info() const { return {buffer_.buffer, 0, size_}; }

 private:
  RawVulkan::Buffer buffer_;
  VkDeviceSize size_, stride_, offset_ = 0;
};

struct BlendVariant {
  VkBool32 enable;
  VkBlendFactor src, dst;
};
BlendVariant Blend(uint32_t i) {
  if (i == 1) return {VK_TRUE, VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA};
  if (i == 2) return {VK_TRUE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE};
  return {VK_FALSE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO};
}

class VkGraphics : public Case {
 public:
  static constexpr VkFormat kColor = VK_FORMAT_R8G8B8A8_UNORM, kDepth = VK_FORMAT_D32_SFLOAT;

  VkGraphics(RawVulkan& vk, const sp::ShaderBytecode* ps, uint32_t draws)
      : vk_(vk), ring_(vk, sizeof(DrawConstants), draws), ps_(ps) {
    const Shaders& s = GetShaders();
    frame_ = vk.CreateFrame();
    if (ps) color_ = vk.CreateImage(kColor, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_ASPECT_COLOR_BIT, kTargetSize, VK_IMAGE_LAYOUT_UNDEFINED);
    depth_ = vk.CreateImage(kDepth, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, kTargetSize, VK_IMAGE_LAYOUT_UNDEFINED);
    for (uint32_t m = 0; m < 2; ++m) {
      const Mesh& mesh = GetMesh(m);
      vb_[m] = vk.CreateBuffer(mesh.positions.size() * 4, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, mesh.positions.data());
      ib_[m] = vk.CreateBuffer(mesh.indices.size() * 2, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, mesh.indices.data());
    }
    vsModule_ = vk.CreateModule(s.vs.spirv);
    if (ps) psModule_ = vk.CreateModule(ps->spirv);
    // Set numbers are the toolchain's (one set per stage): VS in set 0, PS in set 1.
    setLayouts_.push_back(vk.CreateSetLayout(s.vs.reflection, VK_SHADER_STAGE_VERTEX_BIT));
    if (ps) setLayouts_.push_back(vk.CreateSetLayout(ps->reflection, VK_SHADER_STAGE_FRAGMENT_BIT));
    VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    lci.setLayoutCount = uint32_t(setLayouts_.size());
    lci.pSetLayouts = setLayouts_.data();
    vkCreatePipelineLayout(vk.device(), &lci, nullptr, &layout_);
    vsSet_ = vk.AllocateSet(setLayouts_[0]);
    WriteSet(vsSet_, s.vs.reflection, nullptr, VK_NULL_HANDLE, nullptr);
  }

  void Wait() override {
    vk_.Wait(frame_);
    ring_.Reset();
  }

 protected:
  // Writes a stage's set: its cbuffer at the ring, and the given texture, sampler, UAV.
  void WriteSet(VkDescriptorSet set, const sp::ShaderReflection& r, const RawVulkan::Image* texture, VkSampler sampler,
                const RawVulkan::Buffer* uav) {
    std::vector<VkWriteDescriptorSet> w;
    VkDescriptorBufferInfo cb = ring_.Info();
    VkDescriptorImageInfo img{VK_NULL_HANDLE, texture ? texture->view : VK_NULL_HANDLE, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo smp{sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
    VkDescriptorBufferInfo ub{uav ? uav->buffer : VK_NULL_HANDLE, 0, VK_WHOLE_SIZE};
    for (const sp::CBufferInfo& c : r.cbuffers) {
      VkWriteDescriptorSet x{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, c.vkBinding, 0, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC};
      x.pBufferInfo = &cb;
      w.push_back(x);
    }
    for (const sp::ShaderResourceBinding& s : r.resources) {
      VkWriteDescriptorSet x{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, s.vkBinding, 0, 1};
      if (s.type == sp::ShaderResourceType::Texture) x.descriptorType = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, x.pImageInfo = &img;
      else if (s.type == sp::ShaderResourceType::Sampler) x.descriptorType = VK_DESCRIPTOR_TYPE_SAMPLER, x.pImageInfo = &smp;
      else x.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, x.pBufferInfo = &ub;
      w.push_back(x);
    }
    vkUpdateDescriptorSets(vk_.device(), uint32_t(w.size()), w.data(), 0, nullptr);
  }

  VkPipeline CreatePipeline(uint32_t raster, uint32_t depth, uint32_t blend) {
    const Shaders& s = GetShaders();
    VkPipelineShaderStageCreateInfo stages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vsModule_, EntryPointName(s.vs.spirv)},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, psModule_,
         ps_ ? EntryPointName(ps_->spirv) : nullptr}};
    VkVertexInputBindingDescription vbind{0, 12, VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attr{s.vs.reflection.FindInput("POSITION", 0)->location, 0, VK_FORMAT_R32G32B32_SFLOAT, 0};
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO, nullptr, 0, 1, &vbind, 1, &attr};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = raster == 1 ? VK_CULL_MODE_FRONT_BIT : raster == 2 ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    rs.frontFace = VK_FRONT_FACE_CLOCKWISE;
    rs.depthBiasEnable = raster == 3;
    rs.depthBiasConstantFactor = float(kShadowDepthBias);
    rs.depthBiasSlopeFactor = kShadowSlopeBias;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = depth != 2;
    ds.depthWriteEnable = depth == 0;
    ds.depthCompareOp = depth == 1 ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_LESS;
    BlendVariant bv = Blend(blend);
    VkPipelineColorBlendAttachmentState att{bv.enable, bv.src, bv.dst, VK_BLEND_OP_ADD, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ZERO, VK_BLEND_OP_ADD, 0xf};
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = ps_ ? 1 : 0;
    cb.pAttachments = &att;
    VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, nullptr, 0, 2, dyn};
    VkFormat color = kColor;
    VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    ri.colorAttachmentCount = ps_ ? 1 : 0;
    ri.pColorAttachmentFormats = &color;
    ri.depthAttachmentFormat = kDepth;
    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.pNext = &ri;
    ci.stageCount = ps_ ? 2 : 1;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dy;
    ci.layout = layout_;
    VkPipeline p;
    if (vkCreateGraphicsPipelines(vk_.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p) != VK_SUCCESS)
      throw std::runtime_error("raw Vulkan: vkCreateGraphicsPipelines failed");
    return p;
  }

  // Begins the command buffer and the pass (cleared targets), binds the pipeline, the mesh and
  // the vertex shader's set.
  VkCommandBuffer BeginPass(VkPipeline pipeline) {
    vk_.Begin(frame_);
    VkCommandBuffer cmd = frame_.cmd;
    // The targets are cleared each iteration, so their previous contents are discarded.
    VkImageMemoryBarrier b[2];
    uint32_t n = 0;
    auto barrier = [&](VkImage image, VkImageAspectFlags aspect, VkImageLayout layout, VkAccessFlags access) {
      b[n] = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      b[n].dstAccessMask = access;
      b[n].newLayout = layout;
      b[n].srcQueueFamilyIndex = b[n].dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b[n].image = image;
      b[n].subresourceRange = {aspect, 0, 1, 0, 1};
      ++n;
    };
    if (ps_) barrier(color_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    barrier(depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                             VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         0, 0, nullptr, 0, nullptr, n, b);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = color_.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.clearValue.color = {{0, 0, 0, 1}};
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depth_.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {kTargetSize, kTargetSize}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = ps_ ? 1 : 0;
    ri.pColorAttachments = &color;
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &ri);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    VkViewport viewport{0, 0, float(kTargetSize), float(kTargetSize), 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    VkRect2D scissor{{0, 0}, {kTargetSize, kTargetSize}};
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    SetMesh(cmd, 0);
    return cmd;
  }

  void EndPass() {
    vkCmdEndRendering(frame_.cmd);
    vk_.Submit(frame_);
  }

  void SetMesh(VkCommandBuffer cmd, uint32_t m) {
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb_[m].buffer, &offset);
    vkCmdBindIndexBuffer(cmd, ib_[m].buffer, 0, VK_INDEX_TYPE_UINT16);
  }

  RawVulkan& vk_;
  Ring ring_;
  const sp::ShaderBytecode* ps_;
  RawVulkan::Frame frame_;
  RawVulkan::Image color_, depth_;
  RawVulkan::Buffer vb_[2], ib_[2];
  VkShaderModule vsModule_ = VK_NULL_HANDLE, psModule_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSetLayout> setLayouts_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSet vsSet_ = VK_NULL_HANDLE;
};

class VkCBuffer : public VkGraphics {
 public:
  explicit VkCBuffer(RawVulkan& vk) : VkGraphics(vk, &GetShaders().psColor, kDraws) {
    pipeline_ = CreatePipeline(0, 0, 0);
    sets_[0] = vsSet_;
    sets_[1] = vk.AllocateSet(setLayouts_[1]);
    WriteSet(sets_[1], ps_->reflection, nullptr, VK_NULL_HANDLE, nullptr);
    for (uint32_t i = 0; i < kDraws; ++i) constants_.push_back(MakeConstants(i));
  }
  void Record() override {
    VkCommandBuffer cmd = BeginPass(pipeline_);
    for (uint32_t i = 0; i < kDraws; ++i) {
      uint32_t at = ring_.Push(&constants_[i]);
      uint32_t offsets[2] = {at, at};
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 2, sets_, 2, offsets);
      vkCmdDrawIndexed(cmd, kMeshIndices, 1, 0, 0, 0);
    }
    EndPass();
  }

 private:
  VkPipeline pipeline_;
  VkDescriptorSet sets_[2];
  std::vector<DrawConstants> constants_;
};

// The texture and state cases read one constant block, written once at the start of the ring.
class VkStaticConstants : public VkGraphics {
 public:
  VkStaticConstants(RawVulkan& vk, const sp::ShaderBytecode* ps) : VkGraphics(vk, ps, 1) {}

 protected:
  void BindVsSet(VkCommandBuffer cmd) {
    ring_.Reset();
    DrawConstants c = MakeConstants(0);
    uint32_t at = ring_.Push(&c);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &vsSet_, 1, &at);
  }
};

class VkTexture : public VkStaticConstants {
 public:
  explicit VkTexture(RawVulkan& vk) : VkStaticConstants(vk, &GetShaders().psTex) {
    pipeline_ = CreatePipeline(0, 0, 0);
    for (uint32_t i = 0; i < kTextures; ++i)
      textures_[i] = vk.CreateImage(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT, 4,
                                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    for (uint32_t i = 0; i < kSamplers; ++i) {
      VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
      sci.magFilter = sci.minFilter = i ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
      sci.mipmapMode = i ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
      sci.addressModeU = sci.addressModeV = sci.addressModeW =
          i ? VK_SAMPLER_ADDRESS_MODE_REPEAT : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
      sci.maxLod = VK_LOD_CLAMP_NONE;
      vkCreateSampler(vk.device(), &sci, nullptr, &samplers_[i]);
    }
    for (uint32_t t = 0; t < kTextures; ++t)
      for (uint32_t s = 0; s < kSamplers; ++s) {
        sets_[t][s] = vk.AllocateSet(setLayouts_[1]);
        WriteSet(sets_[t][s], ps_->reflection, &textures_[t], samplers_[s], nullptr);
      }
  }
  void Record() override {
    VkCommandBuffer cmd = BeginPass(pipeline_);
    BindVsSet(cmd);
    for (uint32_t i = 0; i < kDraws; ++i) {
      uint32_t zero = 0;
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 1, 1, &sets_[i % kTextures][(i / kTextures) % kSamplers], 1, &zero);
      vkCmdDrawIndexed(cmd, kMeshIndices, 1, 0, 0, 0);
    }
    EndPass();
  }

 private:
  VkPipeline pipeline_;
  RawVulkan::Image textures_[kTextures];
  VkSampler samplers_[kSamplers];
  VkDescriptorSet sets_[kTextures][kSamplers];
};

class VkState : public VkStaticConstants {
 public:
  explicit VkState(RawVulkan& vk) : VkStaticConstants(vk, &GetShaders().psColor) {
    for (uint32_t r = 0; r < kRasterStates; ++r)
      for (uint32_t d = 0; d < kDepthStates; ++d)
        for (uint32_t b = 0; b < kBlendStates; ++b) pipelines_[r][d][b] = CreatePipeline(r, d, b);
    psSet_ = vk.AllocateSet(setLayouts_[1]);
    WriteSet(psSet_, ps_->reflection, nullptr, VK_NULL_HANDLE, nullptr);
  }
  void Record() override {
    VkCommandBuffer cmd = BeginPass(pipelines_[0][0][0]);
    BindVsSet(cmd);
    uint32_t zero = 0;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 1, 1, &psSet_, 1, &zero);
    for (uint32_t i = 0; i < kDraws; ++i) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_[i % kRasterStates][i % kDepthStates][i % kBlendStates]);
      vkCmdDrawIndexed(cmd, kMeshIndices, 1, 0, 0, 0);
    }
    EndPass();
  }

 private:
  VkPipeline pipelines_[kRasterStates][kDepthStates][kBlendStates];
  VkDescriptorSet psSet_;
};

class VkShadow : public VkGraphics {
 public:
  explicit VkShadow(RawVulkan& vk) : VkGraphics(vk, nullptr, kShadowDraws) {
    pipeline_ = CreatePipeline(3, 0, 0);
    for (uint32_t i = 0; i < kShadowDraws; ++i) constants_.push_back(MakeConstants(i));
  }
  void Record() override {
    VkCommandBuffer cmd = BeginPass(pipeline_);
    for (uint32_t i = 0; i < kShadowDraws; ++i) {
      if (i % kShadowMeshRun == 0) SetMesh(cmd, (i / kShadowMeshRun) & 1);
      uint32_t at = ring_.Push(&constants_[i]);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &vsSet_, 1, &at);
      vkCmdDrawIndexed(cmd, kMeshIndices, i % kShadowInstanceEvery == 0 ? kShadowInstances : 1, 0, 0, 0);
    }
    EndPass();
  }

 private:
  VkPipeline pipeline_;
  std::vector<DrawConstants> constants_;
};

class VkCompute : public Case {
 public:
  explicit VkCompute(RawVulkan& vk) : vk_(vk), ring_(vk, sizeof(DispatchConstants), kDispatches) {
    const sp::ShaderBytecode& cs = GetShaders().cs;
    frame_ = vk.CreateFrame();
    VkDescriptorSetLayout setLayout = vk.CreateSetLayout(cs.reflection, VK_SHADER_STAGE_COMPUTE_BIT);
    VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    lci.setLayoutCount = 1;
    lci.pSetLayouts = &setLayout;
    vkCreatePipelineLayout(vk.device(), &lci, nullptr, &layout_);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT,
                vk.CreateModule(cs.spirv), EntryPointName(cs.spirv)};
    ci.layout = layout_;
    vkCreateComputePipelines(vk.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
    VkDescriptorBufferInfo cb = ring_.Info();
    for (uint32_t i = 0; i < kUavs; ++i) {
      buffers_[i] = vk.CreateBuffer(kUavElements * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
      sets_[i] = vk.AllocateSet(setLayout);
      VkDescriptorBufferInfo ub{buffers_[i].buffer, 0, VK_WHOLE_SIZE};
      VkWriteDescriptorSet w[2] = {
          {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, sets_[i], cs.reflection.cbuffers[0].vkBinding, 0, 1,
           VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, nullptr, &cb},
          {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, sets_[i], cs.reflection.resources[0].vkBinding, 0, 1,
           VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &ub}};
      vkUpdateDescriptorSets(vk.device(), 2, w, 0, nullptr);
    }
  }
  void Record() override {
    vk_.Begin(frame_);
    VkCommandBuffer cmd = frame_.cmd;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    for (uint32_t i = 0; i < kDispatches; ++i) {
      DispatchConstants c{i, {}};
      uint32_t at = ring_.Push(&c);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets_[i % kUavs], 1, &at);
      // D3D11 orders dispatches that write one UAV: the buffer written now was last written
      // kUavs dispatches ago, so one barrier per round of kUavs buffers is enough.
      if (i && i % kUavs == 0)
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &mb, 0,
                             nullptr, 0, nullptr);
      vkCmdDispatch(cmd, 1, 1, 1);
    }
    vk_.Submit(frame_);
  }
  void Wait() override {
    vk_.Wait(frame_);
    ring_.Reset();
  }

 private:
  RawVulkan& vk_;
  Ring ring_;
  RawVulkan::Frame frame_;
  VkPipelineLayout layout_;
  VkPipeline pipeline_;
  RawVulkan::Buffer buffers_[kUavs];
  VkDescriptorSet sets_[kUavs];
};

}  // namespace

std::unique_ptr<Case> MakeRawVulkanCase(CaseId id, RawVulkan& vk) {
  switch (id) {
    case CaseId::CBuffer: return std::make_unique<VkCBuffer>(vk);
    case CaseId::Texture: return std::make_unique<VkTexture>(vk);
    case CaseId::State: return std::make_unique<VkState>(vk);
    case CaseId::Compute: return std::make_unique<VkCompute>(vk);
    default: return std::make_unique<VkShadow>(vk);
  }
}

}  // namespace spbench
