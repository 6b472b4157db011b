// samples/shadow-map: the smallest complete ShadowPort program. A D3D11-style device, a depth
// map with a comparison sampler, two passes (depth from the light, then the scene from the camera
// with SampleCmp), and a PNG. The same code runs on Vulkan and on OpenGL.
//
//   shadow-map [--backend vulkan|gl] [--size N] [--out shadow-map.png]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <sp/rhi/rhi.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace {

struct Vertex {
  glm::vec3 pos, normal, color;
};

// The cbuffer Frame of shadow-map.hlsl, with D3D11's packing (float4x4 = 64 bytes, float3 +
// float in one 16-byte register). glm matrices are column-major like HLSL's default packing.
struct FrameConstants {
  glm::mat4 viewProj;
  glm::mat4 lightViewProj;
  glm::vec3 toLight;
  float ambient;
};

// The scene: a 16 x 16 ground and three boxes (min corner, max corner, colour). The image test
// (tests/samples) ray-traces the same boxes to know where the shadows must be.
struct Box {
  glm::vec3 lo, hi, color;
};
const Box kGround = {{-8, -0.1f, -8}, {8, 0, 8}, {0.75f, 0.75f, 0.75f}};
const Box kBoxes[] = {
    {{-4, 0, -1}, {-2, 3, 1}, {0.8f, 0.3f, 0.25f}},
    {{1.75f, 0, -2.75f}, {3.25f, 2, -1.25f}, {0.3f, 0.7f, 0.3f}},
    {{-0.5f, 0, 2.5f}, {2.5f, 1, 3.5f}, {0.25f, 0.4f, 0.8f}},
};
const glm::vec3 kToLight = glm::normalize(glm::vec3(-0.6f, 0.6f, 0.4f));
const glm::vec3 kEye(0, 12, 14);
const float kFovY = glm::radians(45.0f);
const float kAmbient = 0.25f;
const uint32_t kShadowMapSize = 1024;

void AddBox(const Box& b, std::vector<Vertex>& v, std::vector<uint16_t>& idx) {
  // Six faces, four corners each, so every face has its own normal.
  const glm::vec3 n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  glm::vec3 c = (b.lo + b.hi) * 0.5f, h = (b.hi - b.lo) * 0.5f;
  for (const glm::vec3& f : n) {
    glm::vec3 u = f.x != 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 w = glm::cross(f, u);
    auto base = uint16_t(v.size());
    for (glm::vec2 s : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      v.push_back({c + h * (f + s.x * u + s.y * w), f, b.color});
    for (int k : {0, 1, 2, 0, 2, 3}) idx.push_back(uint16_t(base + k));
  }
}

sp::ShaderBytecode Compile(const char* target, const char* entry) {
  sp::hlsl::CompileOptions o;
  o.target = target;
  o.entryPoint = entry;
  return sp::hlsl::CompileFile(SAMPLE_DIR "/shadow-map.hlsl", o);
}

}  // namespace

int main(int argc, char** argv) {
  sp::DeviceDesc dd;
  uint32_t size = 256;
  std::string out = "shadow-map.png";
  for (int i = 1; i < argc; i += 2) {
    std::string k = argv[i], v = i + 1 < argc ? argv[i + 1] : "";
    if (k == "--backend" && sp::ParseBackend(v, &dd.backend)) continue;
    if (k == "--size" && std::atoi(v.c_str()) > 0) { size = uint32_t(std::atoi(v.c_str())); continue; }
    if (k == "--out") { out = v; continue; }
    std::fprintf(stderr, "usage: shadow-map [--backend vulkan|gl] [--size N] [--out file.png]\n");
    return 2;
  }
  try {
    sp::Ref<sp::Device> device = sp::CreateDevice(dd);
    sp::DeviceContext* ctx = device->GetImmediateContext();

    // Geometry: one vertex and one index buffer for the ground and the boxes.
    std::vector<Vertex> vertices;
    std::vector<uint16_t> indices;
    AddBox(kGround, vertices, indices);
    for (const Box& b : kBoxes) AddBox(b, vertices, indices);
    sp::BUFFER_DESC bd;
    bd.Usage = sp::USAGE_IMMUTABLE;
    bd.BindFlags = sp::BIND_VERTEX_BUFFER;
    bd.ByteWidth = uint32_t(vertices.size() * sizeof(Vertex));
    sp::SUBRESOURCE_DATA init{vertices.data()};
    sp::Ref<sp::Buffer> vb = device->CreateBuffer(bd, &init);
    bd.BindFlags = sp::BIND_INDEX_BUFFER;
    bd.ByteWidth = uint32_t(indices.size() * sizeof(uint16_t));
    init.pSysMem = indices.data();
    sp::Ref<sp::Buffer> ib = device->CreateBuffer(bd, &init);

    // Shaders and the input layout.
    sp::ShaderBytecode vsShadowCode = Compile("vs_5_0", "VSShadow");
    sp::ShaderBytecode vsSceneCode = Compile("vs_5_0", "VSScene");
    sp::Ref<sp::VertexShader> vsShadow = device->CreateVertexShader(vsShadowCode);
    sp::Ref<sp::VertexShader> vsScene = device->CreateVertexShader(vsSceneCode);
    sp::Ref<sp::PixelShader> psScene = device->CreatePixelShader(Compile("ps_5_0", "PSScene"));
    const sp::INPUT_ELEMENT_DESC layout[] = {
        {"POSITION", 0, sp::FORMAT_R32G32B32_FLOAT, 0, 0, sp::INPUT_PER_VERTEX_DATA, 0},
        {"NORMAL", 0, sp::FORMAT_R32G32B32_FLOAT, 0, 12, sp::INPUT_PER_VERTEX_DATA, 0},
        {"COLOR", 0, sp::FORMAT_R32G32B32_FLOAT, 0, 24, sp::INPUT_PER_VERTEX_DATA, 0},
    };
    sp::Ref<sp::InputLayout> inputLayout = device->CreateInputLayout(layout, 3, vsSceneCode);

    // The shadow map: typeless so it is written as D32_FLOAT depth and read as R32_FLOAT.
    sp::TEXTURE2D_DESC td;
    td.Width = td.Height = kShadowMapSize;
    td.Format = sp::FORMAT_R32_TYPELESS;
    td.BindFlags = sp::BIND_DEPTH_STENCIL | sp::BIND_SHADER_RESOURCE;
    sp::Ref<sp::Texture2D> shadowMap = device->CreateTexture2D(td);
    sp::DEPTH_STENCIL_VIEW_DESC dsvd;
    dsvd.Format = sp::FORMAT_D32_FLOAT;
    dsvd.ViewDimension = sp::DSV_DIMENSION_TEXTURE2D;
    sp::Ref<sp::DepthStencilView> shadowDsv = device->CreateDepthStencilView(shadowMap.get(), &dsvd);
    sp::SHADER_RESOURCE_VIEW_DESC srvd;
    srvd.Format = sp::FORMAT_R32_FLOAT;
    srvd.ViewDimension = sp::SRV_DIMENSION_TEXTURE2D;
    srvd.Texture2D.MipLevels = 1;
    sp::Ref<sp::ShaderResourceView> shadowSrv = device->CreateShaderResourceView(shadowMap.get(), &srvd);

    // Comparison sampler: bilinear 2x2 PCF; outside the map counts as lit (border depth 1).
    sp::SAMPLER_DESC sd;
    sd.Filter = sp::FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    sd.AddressU = sd.AddressV = sd.AddressW = sp::TEXTURE_ADDRESS_BORDER;
    sd.ComparisonFunc = sp::COMPARISON_LESS_EQUAL;
    sp::Ref<sp::SamplerState> shadowSampler = device->CreateSamplerState(sd);

    // Rasterizer states. The boxes are closed, so nothing is culled; the shadow pass gets D3D11's
    // constant and slope-scaled depth bias against acne.
    sp::RASTERIZER_DESC rd;
    rd.CullMode = sp::CULL_NONE;
    sp::Ref<sp::RasterizerState> sceneRs = device->CreateRasterizerState(rd);
    rd.DepthBias = 1000;
    rd.SlopeScaledDepthBias = 2.0f;
    sp::Ref<sp::RasterizerState> shadowRs = device->CreateRasterizerState(rd);

    // The camera's colour and depth targets, and a staging copy to read the picture back.
    td.Width = td.Height = size;
    td.Format = sp::FORMAT_R8G8B8A8_UNORM;
    td.BindFlags = sp::BIND_RENDER_TARGET;
    sp::Ref<sp::Texture2D> color = device->CreateTexture2D(td);
    sp::Ref<sp::RenderTargetView> colorRtv = device->CreateRenderTargetView(color.get());
    td.Format = sp::FORMAT_D32_FLOAT;
    td.BindFlags = sp::BIND_DEPTH_STENCIL;
    sp::Ref<sp::Texture2D> depth = device->CreateTexture2D(td);
    sp::Ref<sp::DepthStencilView> depthDsv = device->CreateDepthStencilView(depth.get());
    td.Format = sp::FORMAT_R8G8B8A8_UNORM;
    td.BindFlags = 0;
    td.Usage = sp::USAGE_STAGING;
    td.CPUAccessFlags = sp::CPU_ACCESS_READ;
    sp::Ref<sp::Texture2D> readback = device->CreateTexture2D(td);

    // Matrices: right-handed world, D3D's [0, 1] clip depth.
    FrameConstants frame;
    frame.viewProj = glm::perspectiveRH_ZO(kFovY, 1.0f, 0.5f, 50.0f) *
                     glm::lookAtRH(kEye, glm::vec3(0), glm::vec3(0, 1, 0));
    frame.lightViewProj = glm::orthoRH_ZO(-12.0f, 12.0f, -12.0f, 12.0f, 1.0f, 40.0f) *
                          glm::lookAtRH(kToLight * 20.0f, glm::vec3(0), glm::vec3(0, 1, 0));
    frame.toLight = kToLight;
    frame.ambient = kAmbient;
    bd.Usage = sp::USAGE_DEFAULT;
    bd.BindFlags = sp::BIND_CONSTANT_BUFFER;
    bd.ByteWidth = sizeof(FrameConstants);
    init.pSysMem = &frame;
    sp::Ref<sp::Buffer> frameCb = device->CreateBuffer(bd, &init);

    // Everything both passes share.
    sp::Buffer* vbs[] = {vb.get()};
    uint32_t stride = sizeof(Vertex), offset = 0;
    ctx->IASetVertexBuffers(0, 1, vbs, &stride, &offset);
    ctx->IASetIndexBuffer(ib.get(), sp::FORMAT_R16_UINT, 0);
    ctx->IASetInputLayout(inputLayout.get());
    ctx->IASetPrimitiveTopology(sp::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    sp::Buffer* cbs[] = {frameCb.get()};
    ctx->VSSetConstantBuffers(0, 1, cbs);
    ctx->PSSetConstantBuffers(0, 1, cbs);

    // Pass 1: depth from the light.
    ctx->OMSetRenderTargets(0, nullptr, shadowDsv.get());
    ctx->ClearDepthStencilView(shadowDsv.get(), sp::CLEAR_DEPTH, 1.0f, 0);
    sp::VIEWPORT vp{0, 0, float(kShadowMapSize), float(kShadowMapSize), 0, 1};
    ctx->RSSetViewports(1, &vp);
    ctx->RSSetState(shadowRs.get());
    ctx->VSSetShader(vsShadow.get());
    ctx->PSSetShader(nullptr);
    ctx->DrawIndexed(uint32_t(indices.size()), 0, 0);

    // Pass 2: the scene from the camera. Binding the colour target unbinds nothing here, but the
    // shadow map must leave the output stage before it is read, as in D3D11.
    sp::RenderTargetView* rtvs[] = {colorRtv.get()};
    ctx->OMSetRenderTargets(1, rtvs, depthDsv.get());
    const float sky[4] = {0.55f, 0.7f, 0.9f, 1.0f};
    ctx->ClearRenderTargetView(colorRtv.get(), sky);
    ctx->ClearDepthStencilView(depthDsv.get(), sp::CLEAR_DEPTH, 1.0f, 0);
    vp.Width = vp.Height = float(size);
    ctx->RSSetViewports(1, &vp);
    ctx->RSSetState(sceneRs.get());
    ctx->VSSetShader(vsScene.get());
    ctx->PSSetShader(psScene.get());
    sp::ShaderResourceView* srvs[] = {shadowSrv.get()};
    ctx->PSSetShaderResources(0, 1, srvs);
    sp::SamplerState* samplers[] = {shadowSampler.get()};
    ctx->PSSetSamplers(0, 1, samplers);
    ctx->DrawIndexed(uint32_t(indices.size()), 0, 0);

    // Read the picture back (row 0 is the top row on both backends) and write it.
    ctx->CopyResource(readback.get(), color.get());
    sp::MAPPED_SUBRESOURCE m;
    ctx->Map(readback.get(), 0, sp::MAP_READ, 0, &m);
    bool written = stbi_write_png(out.c_str(), int(size), int(size), 4, m.pData, int(m.RowPitch)) != 0;
    ctx->Unmap(readback.get(), 0);
    if (!written) {
      std::fprintf(stderr, "shadow-map: cannot write %s\n", out.c_str());
      return 1;
    }
    std::printf("shadow-map: %s, %ux%u, wrote %s\n", device->Info().deviceName.c_str(), size, size, out.c_str());
    // DeviceDesc::debug is on by default: Vulkan validation layers / GL debug output.
    if (device->ValidationErrorCount() > 0) {
      std::fprintf(stderr, "shadow-map: %llu validation errors, last: %s\n",
                   (unsigned long long)device->ValidationErrorCount(), device->LastValidationError().c_str());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadow-map: %s\n", e.what());
    return 1;
  }
}
