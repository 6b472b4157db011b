// The sp:: side of every case: what a D3D11 renderer ported to ShadowPort records. The same code
// runs on both backends.
#include <cstring>

#include "bench-cases.h"

namespace spbench {
namespace {

using namespace sp;

Ref<Buffer> MakeBuffer(Device& dev, uint32_t bind, const void* data, uint32_t size, USAGE usage = USAGE_DEFAULT,
                       uint32_t misc = 0, uint32_t stride = 0) {
  BUFFER_DESC d;
  d.ByteWidth = size;
  d.Usage = usage;
  d.BindFlags = bind;
  d.CPUAccessFlags = usage == USAGE_DYNAMIC ? uint32_t(CPU_ACCESS_WRITE) : 0u;
  d.MiscFlags = misc;
  d.StructureByteStride = stride;
  SUBRESOURCE_DATA init{data, 0, 0};
  return dev.CreateBuffer(d, data ? &init : nullptr);
}

template <class T>
void WriteDiscard(DeviceContext& ctx, Buffer* b, const T& value) {
  MAPPED_SUBRESOURCE m;
  ctx.Map(b, 0, MAP_WRITE_DISCARD, 0, &m);
  std::memcpy(m.pData, &value, sizeof(T));
  ctx.Unmap(b, 0);
}

// Everything the graphics cases share: targets, mesh buffers, shaders, input layout.
class SpGraphics : public Case {
 public:
  SpGraphics(Device& dev, bool depthOnly) : dev_(dev), ctx_(*dev.GetImmediateContext()), depthOnly_(depthOnly) {
    const Shaders& s = GetShaders();
    TEXTURE2D_DESC td;
    td.Width = td.Height = kTargetSize;
    td.Format = FORMAT_R8G8B8A8_UNORM;
    td.BindFlags = BIND_RENDER_TARGET;
    color_ = dev.CreateTexture2D(td);
    rtv_ = dev.CreateRenderTargetView(color_.get());
    td.Format = FORMAT_D32_FLOAT;
    td.BindFlags = BIND_DEPTH_STENCIL;
    depth_ = dev.CreateTexture2D(td);
    dsv_ = dev.CreateDepthStencilView(depth_.get());
    for (uint32_t m = 0; m < 2; ++m) {
      const Mesh& mesh = GetMesh(m);
      vb_[m] = MakeBuffer(dev, BIND_VERTEX_BUFFER, mesh.positions.data(), uint32_t(mesh.positions.size() * 4));
      ib_[m] = MakeBuffer(dev, BIND_INDEX_BUFFER, mesh.indices.data(), uint32_t(mesh.indices.size() * 2));
    }
    vs_ = dev.CreateVertexShader(s.vs);
    INPUT_ELEMENT_DESC el[] = {{"POSITION", 0, FORMAT_R32G32B32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0}};
    layout_ = dev.CreateInputLayout(el, 1, s.vs);
    DrawConstants c = MakeConstants(0);
    staticCb_ = MakeBuffer(dev, BIND_CONSTANT_BUFFER, &c, sizeof(c));
    dynamicCb_ = MakeBuffer(dev, BIND_CONSTANT_BUFFER, nullptr, sizeof(c), USAGE_DYNAMIC);
  }

  void Wait() override { ctx_.WaitIdle(); }

 protected:
  // The frame's fixed part: targets, clears, viewport, input assembly, vertex shader.
  void BeginPass(Buffer* cb) {
    RenderTargetView* rtvs[] = {rtv_.get()};
    ctx_.OMSetRenderTargets(depthOnly_ ? 0 : 1, rtvs, dsv_.get());
    if (!depthOnly_) {
      const float clear[4] = {0, 0, 0, 1};
      ctx_.ClearRenderTargetView(rtv_.get(), clear);
    }
    ctx_.ClearDepthStencilView(dsv_.get(), CLEAR_DEPTH, 1.0f, 0);
    VIEWPORT vp{0, 0, float(kTargetSize), float(kTargetSize), 0, 1};
    ctx_.RSSetViewports(1, &vp);
    ctx_.IASetInputLayout(layout_.get());
    ctx_.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    SetMesh(0);
    ctx_.VSSetShader(vs_.get());
    ctx_.VSSetConstantBuffers(0, {cb});
  }

  void SetMesh(uint32_t m) {
    Buffer* vbs[] = {vb_[m].get()};
    uint32_t stride = 12, offset = 0;
    ctx_.IASetVertexBuffers(0, 1, vbs, &stride, &offset);
    ctx_.IASetIndexBuffer(ib_[m].get(), FORMAT_R16_UINT, 0);
  }

  Device& dev_;
  DeviceContext& ctx_;
  bool depthOnly_;
  Ref<Texture2D> color_, depth_;
  Ref<RenderTargetView> rtv_;
  Ref<DepthStencilView> dsv_;
  Ref<Buffer> vb_[2], ib_[2];
  Ref<VertexShader> vs_;
  Ref<InputLayout> layout_;
  Ref<Buffer> staticCb_, dynamicCb_;
};

class SpCBuffer : public SpGraphics {
 public:
  explicit SpCBuffer(Device& dev) : SpGraphics(dev, false) {
    ps_ = dev.CreatePixelShader(GetShaders().psColor);
    for (uint32_t i = 0; i < kDraws; ++i) constants_.push_back(MakeConstants(i));
  }
  void Record() override {
    BeginPass(dynamicCb_.get());
    ctx_.PSSetShader(ps_.get());
    ctx_.PSSetConstantBuffers(0, {dynamicCb_.get()});
    for (uint32_t i = 0; i < kDraws; ++i) {
      WriteDiscard(ctx_, dynamicCb_.get(), constants_[i]);
      ctx_.DrawIndexed(kMeshIndices, 0, 0);
    }
    ctx_.Flush();
  }

 private:
  Ref<PixelShader> ps_;
  std::vector<DrawConstants> constants_;
};

class SpTexture : public SpGraphics {
 public:
  explicit SpTexture(Device& dev) : SpGraphics(dev, false) {
    ps_ = dev.CreatePixelShader(GetShaders().psTex);
    for (uint32_t i = 0; i < kTextures; ++i) {
      TEXTURE2D_DESC td;
      td.Width = td.Height = 4;
      td.Format = FORMAT_R8G8B8A8_UNORM;
      td.BindFlags = BIND_SHADER_RESOURCE;
      std::vector<uint32_t> texels = TextureTexels(i);
      SUBRESOURCE_DATA init{texels.data(), 16, 0};
      textures_[i] = dev.CreateTexture2D(td, &init);
      srvs_[i] = dev.CreateShaderResourceView(textures_[i].get());
    }
    for (uint32_t i = 0; i < kSamplers; ++i) {
      SAMPLER_DESC sd;
      sd.Filter = i ? FILTER_MIN_MAG_MIP_POINT : FILTER_MIN_MAG_MIP_LINEAR;
      sd.AddressU = sd.AddressV = i ? TEXTURE_ADDRESS_WRAP : TEXTURE_ADDRESS_CLAMP;
      samplers_[i] = dev.CreateSamplerState(sd);
    }
  }
  void Record() override {
    BeginPass(staticCb_.get());
    ctx_.PSSetShader(ps_.get());
    ctx_.PSSetConstantBuffers(0, {staticCb_.get()});
    for (uint32_t i = 0; i < kDraws; ++i) {
      ctx_.PSSetShaderResources(0, {srvs_[i % kTextures].get()});
      ctx_.PSSetSamplers(0, {samplers_[(i / kTextures) % kSamplers].get()});
      ctx_.DrawIndexed(kMeshIndices, 0, 0);
    }
    ctx_.Flush();
  }

 private:
  Ref<PixelShader> ps_;
  Ref<Texture2D> textures_[kTextures];
  Ref<ShaderResourceView> srvs_[kTextures];
  Ref<SamplerState> samplers_[kSamplers];
};

class SpState : public SpGraphics {
 public:
  explicit SpState(Device& dev) : SpGraphics(dev, false) {
    ps_ = dev.CreatePixelShader(GetShaders().psColor);
    for (uint32_t i = 0; i < kRasterStates; ++i) raster_[i] = dev.CreateRasterizerState(RasterDesc(i));
    for (uint32_t i = 0; i < kDepthStates; ++i) depth_[i] = dev.CreateDepthStencilState(DepthDesc(i));
    for (uint32_t i = 0; i < kBlendStates; ++i) blend_[i] = dev.CreateBlendState(BlendDesc(i));
  }
  void Record() override {
    BeginPass(staticCb_.get());
    ctx_.PSSetShader(ps_.get());
    ctx_.PSSetConstantBuffers(0, {staticCb_.get()});
    const float factor[4] = {1, 1, 1, 1};
    for (uint32_t i = 0; i < kDraws; ++i) {
      ctx_.RSSetState(raster_[i % kRasterStates].get());
      ctx_.OMSetDepthStencilState(depth_[i % kDepthStates].get(), 0);
      ctx_.OMSetBlendState(blend_[i % kBlendStates].get(), factor, 0xffffffffu);
      ctx_.DrawIndexed(kMeshIndices, 0, 0);
    }
    ctx_.RSSetState(nullptr);
    ctx_.OMSetDepthStencilState(nullptr, 0);
    ctx_.OMSetBlendState(nullptr, nullptr, 0xffffffffu);
    ctx_.Flush();
  }

 private:
  Ref<PixelShader> ps_;
  Ref<RasterizerState> raster_[kRasterStates];
  Ref<DepthStencilState> depth_[kDepthStates];
  Ref<BlendState> blend_[kBlendStates];
};

class SpShadow : public SpGraphics {
 public:
  explicit SpShadow(Device& dev) : SpGraphics(dev, true) {
    raster_ = dev.CreateRasterizerState(RasterDesc(3));
    for (uint32_t i = 0; i < kShadowDraws; ++i) constants_.push_back(MakeConstants(i));
  }
  void Record() override {
    BeginPass(dynamicCb_.get());
    ctx_.PSSetShader(nullptr);
    ctx_.RSSetState(raster_.get());
    for (uint32_t i = 0; i < kShadowDraws; ++i) {
      if (i % kShadowMeshRun == 0) SetMesh((i / kShadowMeshRun) & 1);
      WriteDiscard(ctx_, dynamicCb_.get(), constants_[i]);
      if (i % kShadowInstanceEvery == 0)
        ctx_.DrawIndexedInstanced(kMeshIndices, kShadowInstances, 0, 0, 0);
      else
        ctx_.DrawIndexed(kMeshIndices, 0, 0);
    }
    ctx_.RSSetState(nullptr);
    ctx_.Flush();
  }

 private:
  Ref<RasterizerState> raster_;
  std::vector<DrawConstants> constants_;
};

class SpCompute : public Case {
 public:
  explicit SpCompute(Device& dev) : ctx_(*dev.GetImmediateContext()) {
    cs_ = dev.CreateComputeShader(GetShaders().cs);
    for (uint32_t i = 0; i < kUavs; ++i) {
      buffers_[i] = MakeBuffer(dev, BIND_UNORDERED_ACCESS, nullptr, kUavElements * 4, USAGE_DEFAULT,
                               RESOURCE_MISC_BUFFER_STRUCTURED, 4);
      uavs_[i] = dev.CreateUnorderedAccessView(buffers_[i].get());
    }
    DispatchConstants c{};
    cb_ = MakeBuffer(dev, BIND_CONSTANT_BUFFER, &c, sizeof(c), USAGE_DYNAMIC);
  }
  void Record() override {
    ctx_.CSSetShader(cs_.get());
    ctx_.CSSetConstantBuffers(0, {cb_.get()});
    for (uint32_t i = 0; i < kDispatches; ++i) {
      WriteDiscard(ctx_, cb_.get(), DispatchConstants{i, {}});
      ctx_.CSSetUnorderedAccessViews(0, {uavs_[i % kUavs].get()});
      ctx_.Dispatch(1, 1, 1);
    }
    ctx_.CSSetUnorderedAccessViews(0, {nullptr});
    ctx_.Flush();
  }
  void Wait() override { ctx_.WaitIdle(); }

 private:
  DeviceContext& ctx_;
  Ref<ComputeShader> cs_;
  Ref<Buffer> buffers_[kUavs], cb_;
  Ref<UnorderedAccessView> uavs_[kUavs];
};

}  // namespace

std::unique_ptr<Case> MakeSpCase(CaseId id, Device& dev) {
  switch (id) {
    case CaseId::CBuffer: return std::make_unique<SpCBuffer>(dev);
    case CaseId::Texture: return std::make_unique<SpTexture>(dev);
    case CaseId::State: return std::make_unique<SpState>(dev);
    case CaseId::Compute: return std::make_unique<SpCompute>(dev);
    default: return std::make_unique<SpShadow>(dev);
  }
}

}  // namespace spbench
