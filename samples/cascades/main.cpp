// samples/cascades: cascaded shadow maps written directly against ShadowPort's D3D11-style API,
// in the style of the DirectX SDK's CascadedShadowMaps11: a manager class with COM-style raw
// pointers, HRESULTs and V_RETURN, desc structs filled as D3D11 code fills them, Shader Model 4
// shaders compiled with D3DCompileFromFile's shape, one wide depth texture holding every cascade
// side by side. docs/porting.md walks through it as the worked example of a port: every line
// here is the D3D11 line with `D3D11_` / `DXGI_` / `ID3D11` / `CD3D11_` / `D3D` renamed.
//
//   cascades [--backend vulkan|gl] [--size N] [--cascades 1..4] [--visualize 0|1] [--out cascades.png]
#include <algorithm>
#include <cmath>
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

// DXUT's helpers, as the SDK samples define them.
#define V_RETURN(x)                                                                  \
  do {                                                                               \
    sp::HRESULT hr_ = (x);                                                           \
    if (sp::FAILED(hr_)) {                                                           \
      std::fprintf(stderr, "cascades: %s failed (0x%08x)\n", #x, unsigned(hr_));     \
      return hr_;                                                                    \
    }                                                                                \
  } while (0)
#define SAFE_RELEASE(p) \
  do {                  \
    if (p) {            \
      (p)->Release();   \
      (p) = nullptr;    \
    }                   \
  } while (0)
#define ARRAYSIZE(a) (sizeof(a) / sizeof((a)[0]))

namespace {

const int MAX_CASCADES = 4;

struct Vertex {
  glm::vec3 pos, normal, color;
};

// The scene: a long strip of ground with two rows of columns (the layout of the SDK sample's
// ShadowColumns). tests/samples/cascades.json holds the same boxes for the image test.
struct Box {
  glm::vec3 lo, hi, color;
};
std::vector<Box> MakeScene() {
  std::vector<Box> boxes = {{{-10, -0.1f, -70}, {10, 0, 10}, {0.75f, 0.75f, 0.75f}}};
  for (int k = 0; k < 10; ++k) {
    float z = -6.0f * k - 2.0f;
    boxes.push_back({{-4.5f, 0, z - 0.5f}, {-3.5f, 5, z + 0.5f}, {0.8f, 0.35f, 0.3f}});
    boxes.push_back({{3.5f, 0, z - 0.5f}, {4.5f, 5, z + 0.5f}, {0.3f, 0.45f, 0.8f}});
  }
  return boxes;
}
const glm::vec3 kToLight = glm::normalize(glm::vec3(-0.6f, 0.5f, 0.3f));
const glm::vec3 kEye(0, 4, 8), kLookAt(0, 1, -20);
const float kFovY = glm::radians(50.0f), kNear = 0.5f, kFar = 90.0f;
const float kAmbient = 0.25f;

// cbFrame and cbShadowPass of cascades.hlsl, with D3D11's packing.
struct CB_FRAME {
  glm::mat4 m_mViewProj;
  glm::mat4 m_mView;
  glm::mat4 m_mLightViewProj[MAX_CASCADES];
  glm::vec4 m_vCascadeEnd;
  glm::vec4 m_vToLight;
  int32_t m_nCascades;
  float m_fTexelSize;
  int32_t m_bVisualizeCascades;
  float m_fPad;
};
struct CB_SHADOW_PASS {
  glm::mat4 m_mShadowViewProj;
};

void AddBox(const Box& b, std::vector<Vertex>& v, std::vector<uint16_t>& idx) {
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

// The renderer: what the SDK sample's CascadedShadowsManager does, reduced to one fit (each
// cascade's light frustum around its slice of the view frustum, near and far planes from the
// scene's bounds so every caster is drawn) and interval-based cascade selection.
class CascadedShadowsManager {
 public:
  ~CascadedShadowsManager() { DestroyAndDeallocateShadowResources(); }

  sp::HRESULT Init(sp::Device* pd3dDevice, int nCascades, int iBufferSize, const std::vector<Box>& scene) {
    m_nCascades = nCascades;
    m_iBufferSize = iBufferSize;
    m_scene = scene;

    // Shaders, as D3D11-era code compiled them: Shader Model 4 targets, strictness, row-major
    // off (the HLSL's matrices are column-major, as glm stores them).
    const uint32_t dwShaderFlags = sp::hlsl::COMPILE_ENABLE_STRICTNESS;
    sp::hlsl::Blob* pVertexShaderBuffer = nullptr;
    sp::hlsl::Blob* pPixelShaderBuffer = nullptr;
    V_RETURN(CompileShaderFromFile("VSShadow", "vs_4_0", dwShaderFlags, &pVertexShaderBuffer));
    V_RETURN(pd3dDevice->CreateVertexShader(pVertexShaderBuffer->GetBufferPointer(), pVertexShaderBuffer->GetBufferSize(),
                                            nullptr, &m_pvsShadow));
    SAFE_RELEASE(pVertexShaderBuffer);
    V_RETURN(CompileShaderFromFile("VSScene", "vs_4_0", dwShaderFlags, &pVertexShaderBuffer));
    V_RETURN(pd3dDevice->CreateVertexShader(pVertexShaderBuffer->GetBufferPointer(), pVertexShaderBuffer->GetBufferSize(),
                                            nullptr, &m_pvsScene));
    V_RETURN(CompileShaderFromFile("PSScene", "ps_4_0", dwShaderFlags, &pPixelShaderBuffer));
    V_RETURN(pd3dDevice->CreatePixelShader(pPixelShaderBuffer->GetBufferPointer(), pPixelShaderBuffer->GetBufferSize(),
                                           nullptr, &m_ppsScene));
    SAFE_RELEASE(pPixelShaderBuffer);

    const sp::INPUT_ELEMENT_DESC layout[] = {
        {"POSITION", 0, sp::FORMAT_R32G32B32_FLOAT, 0, 0, sp::INPUT_PER_VERTEX_DATA, 0},
        {"NORMAL", 0, sp::FORMAT_R32G32B32_FLOAT, 0, 12, sp::INPUT_PER_VERTEX_DATA, 0},
        {"COLOR", 0, sp::FORMAT_R32G32B32_FLOAT, 0, 24, sp::INPUT_PER_VERTEX_DATA, 0},
    };
    V_RETURN(pd3dDevice->CreateInputLayout(layout, ARRAYSIZE(layout), pVertexShaderBuffer->GetBufferPointer(),
                                           pVertexShaderBuffer->GetBufferSize(), &m_pVertexLayout));
    SAFE_RELEASE(pVertexShaderBuffer);

    // Geometry.
    std::vector<Vertex> vertices;
    for (const Box& b : m_scene) AddBox(b, vertices, m_indices);
    sp::BUFFER_DESC bd = {uint32_t(vertices.size() * sizeof(Vertex)), sp::USAGE_IMMUTABLE, sp::BIND_VERTEX_BUFFER, 0, 0, 0};
    sp::SUBRESOURCE_DATA InitData = {vertices.data(), 0, 0};
    V_RETURN(pd3dDevice->CreateBuffer(&bd, &InitData, &m_pVertexBuffer));
    bd.ByteWidth = uint32_t(m_indices.size() * sizeof(uint16_t));
    bd.BindFlags = sp::BIND_INDEX_BUFFER;
    InitData.pSysMem = m_indices.data();
    V_RETURN(pd3dDevice->CreateBuffer(&bd, &InitData, &m_pIndexBuffer));

    // Constant buffers, written with UpdateSubresource as the sample does.
    sp::CBUFFER_DESC cbd(sizeof(CB_FRAME), sp::BIND_CONSTANT_BUFFER);
    V_RETURN(pd3dDevice->CreateBuffer(&cbd, nullptr, &m_pcbFrame));
    cbd.ByteWidth = sizeof(CB_SHADOW_PASS);
    V_RETURN(pd3dDevice->CreateBuffer(&cbd, nullptr, &m_pcbShadowPass));

    // The atlas: one typeless texture, a D32_FLOAT depth view for rendering and an R32_FLOAT
    // view for sampling.
    sp::TEXTURE2D_DESC dtd = {uint32_t(m_iBufferSize * m_nCascades), uint32_t(m_iBufferSize), 1, 1, sp::FORMAT_R32_TYPELESS, 1, 0,
                              sp::USAGE_DEFAULT, sp::BIND_DEPTH_STENCIL | sp::BIND_SHADER_RESOURCE, 0, 0};
    V_RETURN(pd3dDevice->CreateTexture2D(&dtd, nullptr, &m_pCascadedShadowMapTexture));
    sp::DEPTH_STENCIL_VIEW_DESC dsvd = {sp::FORMAT_D32_FLOAT, sp::DSV_DIMENSION_TEXTURE2D, 0};
    V_RETURN(pd3dDevice->CreateDepthStencilView(m_pCascadedShadowMapTexture, &dsvd, &m_pCascadedShadowMapDSV));
    sp::SHADER_RESOURCE_VIEW_DESC dsrvd = {sp::FORMAT_R32_FLOAT, sp::SRV_DIMENSION_TEXTURE2D, 0, 1};
    V_RETURN(pd3dDevice->CreateShaderResourceView(m_pCascadedShadowMapTexture, &dsrvd, &m_pCascadedShadowMapSRV));

    // States: depth bias against acne for the shadow pass; no culling (closed boxes).
    sp::CRASTERIZER_DESC drd(sp::DEFAULT);
    drd.CullMode = sp::CULL_NONE;
    V_RETURN(pd3dDevice->CreateRasterizerState(&drd, &m_prsScene));
    drd.DepthBias = 1000;
    drd.SlopeScaledDepthBias = 2.0f;
    V_RETURN(pd3dDevice->CreateRasterizerState(&drd, &m_prsShadow));
    sp::SAMPLER_DESC SamDesc;
    SamDesc.Filter = sp::FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    SamDesc.AddressU = sp::TEXTURE_ADDRESS_BORDER;
    SamDesc.AddressV = sp::TEXTURE_ADDRESS_BORDER;
    SamDesc.AddressW = sp::TEXTURE_ADDRESS_BORDER;
    SamDesc.MipLODBias = 0.0f;
    SamDesc.MaxAnisotropy = 0;
    SamDesc.ComparisonFunc = sp::COMPARISON_LESS_EQUAL;
    SamDesc.BorderColor[0] = SamDesc.BorderColor[1] = SamDesc.BorderColor[2] = SamDesc.BorderColor[3] = 1.0f;
    SamDesc.MinLOD = 0;
    SamDesc.MaxLOD = sp::FLOAT32_MAX;
    V_RETURN(pd3dDevice->CreateSamplerState(&SamDesc, &m_pSamShadowPCF));
    return sp::S_OK;
  }

  void DestroyAndDeallocateShadowResources() {
    SAFE_RELEASE(m_pvsShadow);
    SAFE_RELEASE(m_pvsScene);
    SAFE_RELEASE(m_ppsScene);
    SAFE_RELEASE(m_pVertexLayout);
    SAFE_RELEASE(m_pVertexBuffer);
    SAFE_RELEASE(m_pIndexBuffer);
    SAFE_RELEASE(m_pcbFrame);
    SAFE_RELEASE(m_pcbShadowPass);
    SAFE_RELEASE(m_pCascadedShadowMapTexture);
    SAFE_RELEASE(m_pCascadedShadowMapDSV);
    SAFE_RELEASE(m_pCascadedShadowMapSRV);
    SAFE_RELEASE(m_prsScene);
    SAFE_RELEASE(m_prsShadow);
    SAFE_RELEASE(m_pSamShadowPCF);
  }

  // Practical split scheme: a blend of logarithmic and uniform split distances.
  void ComputeCascades(const glm::mat4& mView, float fAspect) {
    const float lambda = 0.8f;
    float fSplits[MAX_CASCADES + 1];
    for (int i = 0; i <= m_nCascades; ++i) {
      float t = float(i) / float(m_nCascades);
      fSplits[i] = lambda * kNear * std::pow(kFar / kNear, t) + (1.0f - lambda) * (kNear + (kFar - kNear) * t);
    }
    // The light's view: only its direction matters; the fit chooses the rest.
    glm::mat4 mLightView = glm::lookAtRH(kToLight, glm::vec3(0), std::abs(kToLight.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0));
    // Near and far from the scene's corners, so casters outside the slice still cast.
    glm::vec3 vSceneMin(1e30f), vSceneMax(-1e30f);
    for (const Box& b : m_scene) {
      for (int c = 0; c < 8; ++c) {
        glm::vec3 p((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
        glm::vec3 l = glm::vec3(mLightView * glm::vec4(p, 1));
        vSceneMin = glm::min(vSceneMin, l);
        vSceneMax = glm::max(vSceneMax, l);
      }
    }
    glm::mat4 mInvView = glm::inverse(mView);
    float fTanY = std::tan(kFovY * 0.5f), fTanX = fTanY * fAspect;
    for (int i = 0; i < m_nCascades; ++i) {
      // The slice's corners in light view space; the ortho box around them, in whole texels so
      // the map does not crawl when the camera moves (the SDK's "move light texel size").
      glm::vec3 vMin(1e30f), vMax(-1e30f);
      for (int c = 0; c < 8; ++c) {
        float z = fSplits[i + (c >> 2)];
        glm::vec4 pView((c & 1 ? 1 : -1) * fTanX * z, (c & 2 ? 1 : -1) * fTanY * z, -z, 1);
        glm::vec3 l = glm::vec3(mLightView * (mInvView * pView));
        vMin = glm::min(vMin, l);
        vMax = glm::max(vMax, l);
      }
      float fTexel = std::max(vMax.x - vMin.x, vMax.y - vMin.y) / float(m_iBufferSize);
      vMin = glm::floor(vMin / fTexel) * fTexel;
      vMax = glm::ceil(vMax / fTexel) * fTexel;
      m_mLightViewProj[i] = glm::orthoRH_ZO(vMin.x, vMax.x, vMin.y, vMax.y, -vSceneMax.z, -vSceneMin.z) * mLightView;
      m_fCascadeEnd[i] = fSplits[i + 1];
    }
  }

  void RenderShadowsForAllCascades(sp::DeviceContext* pd3dDeviceContext) {
    pd3dDeviceContext->ClearDepthStencilView(m_pCascadedShadowMapDSV, sp::CLEAR_DEPTH, 1.0f, 0);
    pd3dDeviceContext->OMSetRenderTargets(0, nullptr, m_pCascadedShadowMapDSV);
    pd3dDeviceContext->RSSetState(m_prsShadow);
    pd3dDeviceContext->VSSetShader(m_pvsShadow, nullptr, 0);
    pd3dDeviceContext->PSSetShader(nullptr, nullptr, 0);
    pd3dDeviceContext->VSSetConstantBuffers(1, 1, &m_pcbShadowPass);
    SetGeometry(pd3dDeviceContext);
    for (int i = 0; i < m_nCascades; ++i) {
      // Each cascade renders into its own tile of the atlas.
      sp::CVIEWPORT vp(float(i * m_iBufferSize), 0.0f, float(m_iBufferSize), float(m_iBufferSize));
      pd3dDeviceContext->RSSetViewports(1, &vp);
      CB_SHADOW_PASS cb = {m_mLightViewProj[i]};
      pd3dDeviceContext->UpdateSubresource(m_pcbShadowPass, 0, nullptr, &cb, 0, 0);
      pd3dDeviceContext->DrawIndexed(uint32_t(m_indices.size()), 0, 0);
    }
  }

  void RenderScene(sp::DeviceContext* pd3dDeviceContext, sp::RenderTargetView* prtvBackBuffer, sp::DepthStencilView* pdsvBackBuffer,
                   const glm::mat4& mView, const glm::mat4& mProj, bool bVisualize, uint32_t uSize) {
    CB_FRAME cb;
    cb.m_mViewProj = mProj * mView;
    cb.m_mView = mView;
    for (int i = 0; i < MAX_CASCADES; ++i) cb.m_mLightViewProj[i] = m_mLightViewProj[std::min(i, m_nCascades - 1)];
    cb.m_vCascadeEnd = glm::vec4(m_fCascadeEnd[0], m_fCascadeEnd[1], m_fCascadeEnd[2], m_fCascadeEnd[3]);
    cb.m_vToLight = glm::vec4(kToLight, kAmbient);
    cb.m_nCascades = m_nCascades;
    cb.m_fTexelSize = 1.0f / float(m_iBufferSize);
    cb.m_bVisualizeCascades = bVisualize ? 1 : 0;
    cb.m_fPad = 0;
    pd3dDeviceContext->UpdateSubresource(m_pcbFrame, 0, nullptr, &cb, 0, 0);

    pd3dDeviceContext->OMSetRenderTargets(1, &prtvBackBuffer, pdsvBackBuffer);
    sp::CVIEWPORT vp(0.0f, 0.0f, float(uSize), float(uSize));
    pd3dDeviceContext->RSSetViewports(1, &vp);
    pd3dDeviceContext->RSSetState(m_prsScene);
    pd3dDeviceContext->VSSetShader(m_pvsScene, nullptr, 0);
    pd3dDeviceContext->PSSetShader(m_ppsScene, nullptr, 0);
    pd3dDeviceContext->VSSetConstantBuffers(0, 1, &m_pcbFrame);
    pd3dDeviceContext->PSSetConstantBuffers(0, 1, &m_pcbFrame);
    pd3dDeviceContext->PSSetShaderResources(0, 1, &m_pCascadedShadowMapSRV);
    pd3dDeviceContext->PSSetSamplers(0, 1, &m_pSamShadowPCF);
    SetGeometry(pd3dDeviceContext);
    pd3dDeviceContext->DrawIndexed(uint32_t(m_indices.size()), 0, 0);
    // The atlas is written again next frame: unbind it from the input stage first.
    sp::ShaderResourceView* nv[] = {nullptr};
    pd3dDeviceContext->PSSetShaderResources(0, 1, nv);
  }

 private:
  sp::HRESULT CompileShaderFromFile(const char* szEntryPoint, const char* szShaderModel, uint32_t flags, sp::hlsl::Blob** ppBlobOut) {
    sp::hlsl::Blob* pErrorBlob = nullptr;
    sp::HRESULT hr = sp::hlsl::CompileFromFile(SAMPLE_DIR "/cascades.hlsl", nullptr, sp::hlsl::COMPILE_STANDARD_FILE_INCLUDE,
                                               szEntryPoint, szShaderModel, flags, 0, ppBlobOut, &pErrorBlob);
    if (sp::FAILED(hr) && pErrorBlob) std::fprintf(stderr, "%s\n", static_cast<const char*>(pErrorBlob->GetBufferPointer()));
    SAFE_RELEASE(pErrorBlob);
    return hr;
  }

  void SetGeometry(sp::DeviceContext* pd3dDeviceContext) {
    uint32_t stride = sizeof(Vertex), offset = 0;
    pd3dDeviceContext->IASetInputLayout(m_pVertexLayout);
    pd3dDeviceContext->IASetVertexBuffers(0, 1, &m_pVertexBuffer, &stride, &offset);
    pd3dDeviceContext->IASetIndexBuffer(m_pIndexBuffer, sp::FORMAT_R16_UINT, 0);
    pd3dDeviceContext->IASetPrimitiveTopology(sp::PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  }

  int m_nCascades = 0, m_iBufferSize = 0;
  std::vector<Box> m_scene;
  std::vector<uint16_t> m_indices;
  glm::mat4 m_mLightViewProj[MAX_CASCADES];
  float m_fCascadeEnd[MAX_CASCADES] = {};
  sp::VertexShader* m_pvsShadow = nullptr;
  sp::VertexShader* m_pvsScene = nullptr;
  sp::PixelShader* m_ppsScene = nullptr;
  sp::InputLayout* m_pVertexLayout = nullptr;
  sp::Buffer* m_pVertexBuffer = nullptr;
  sp::Buffer* m_pIndexBuffer = nullptr;
  sp::Buffer* m_pcbFrame = nullptr;
  sp::Buffer* m_pcbShadowPass = nullptr;
  sp::Texture2D* m_pCascadedShadowMapTexture = nullptr;
  sp::DepthStencilView* m_pCascadedShadowMapDSV = nullptr;
  sp::ShaderResourceView* m_pCascadedShadowMapSRV = nullptr;
  sp::RasterizerState* m_prsScene = nullptr;
  sp::RasterizerState* m_prsShadow = nullptr;
  sp::SamplerState* m_pSamShadowPCF = nullptr;
};

// The application around the manager: device, back buffer, one frame, PNG.
sp::HRESULT Run(sp::Device* pd3dDevice, uint32_t uSize, int nCascades, bool bVisualize, const std::string& out) {
  sp::DeviceContext* pd3dImmediateContext = pd3dDevice->GetImmediateContext();
  sp::Texture2D* pBackBuffer = nullptr;
  sp::Texture2D* pDepth = nullptr;
  sp::Texture2D* pReadback = nullptr;
  sp::RenderTargetView* pRTV = nullptr;
  sp::DepthStencilView* pDSV = nullptr;
  sp::CTEXTURE2D_DESC td(sp::FORMAT_R8G8B8A8_UNORM, uSize, uSize, 1, 1, sp::BIND_RENDER_TARGET);
  V_RETURN(pd3dDevice->CreateTexture2D(&td, nullptr, &pBackBuffer));
  V_RETURN(pd3dDevice->CreateRenderTargetView(pBackBuffer, nullptr, &pRTV));
  sp::CTEXTURE2D_DESC dd(sp::FORMAT_D32_FLOAT, uSize, uSize, 1, 1, sp::BIND_DEPTH_STENCIL);
  V_RETURN(pd3dDevice->CreateTexture2D(&dd, nullptr, &pDepth));
  V_RETURN(pd3dDevice->CreateDepthStencilView(pDepth, nullptr, &pDSV));
  sp::CTEXTURE2D_DESC rd(sp::FORMAT_R8G8B8A8_UNORM, uSize, uSize, 1, 1, 0, sp::USAGE_STAGING, sp::CPU_ACCESS_READ);
  V_RETURN(pd3dDevice->CreateTexture2D(&rd, nullptr, &pReadback));

  CascadedShadowsManager manager;
  V_RETURN(manager.Init(pd3dDevice, nCascades, 1024, MakeScene()));
  glm::mat4 mView = glm::lookAtRH(kEye, kLookAt, glm::vec3(0, 1, 0));
  glm::mat4 mProj = glm::perspectiveRH_ZO(kFovY, 1.0f, kNear, kFar);
  manager.ComputeCascades(mView, 1.0f);
  const float sky[4] = {0.55f, 0.7f, 0.9f, 1.0f};
  pd3dImmediateContext->ClearRenderTargetView(pRTV, sky);
  pd3dImmediateContext->ClearDepthStencilView(pDSV, sp::CLEAR_DEPTH, 1.0f, 0);
  manager.RenderShadowsForAllCascades(pd3dImmediateContext);
  manager.RenderScene(pd3dImmediateContext, pRTV, pDSV, mView, mProj, bVisualize, uSize);

  pd3dImmediateContext->CopyResource(pReadback, pBackBuffer);
  sp::MAPPED_SUBRESOURCE mapped;
  V_RETURN(pd3dImmediateContext->Map(pReadback, 0, sp::MAP_READ, 0, &mapped));
  int written = stbi_write_png(out.c_str(), int(uSize), int(uSize), 4, mapped.pData, int(mapped.RowPitch));
  pd3dImmediateContext->Unmap(pReadback, 0);
  SAFE_RELEASE(pRTV);
  SAFE_RELEASE(pDSV);
  SAFE_RELEASE(pBackBuffer);
  SAFE_RELEASE(pDepth);
  SAFE_RELEASE(pReadback);
  return written ? sp::S_OK : sp::E_FAIL;
}

}  // namespace

int main(int argc, char** argv) {
  sp::DeviceDesc desc;
  uint32_t uSize = 256;
  int nCascades = 4;
  bool bVisualize = false;
  std::string out = "cascades.png";
  for (int i = 1; i < argc; i += 2) {
    std::string k = argv[i], v = i + 1 < argc ? argv[i + 1] : "";
    if (k == "--backend" && sp::ParseBackend(v, &desc.backend)) continue;
    if (k == "--size" && std::atoi(v.c_str()) > 0) { uSize = uint32_t(std::atoi(v.c_str())); continue; }
    if (k == "--cascades" && std::atoi(v.c_str()) >= 1 && std::atoi(v.c_str()) <= MAX_CASCADES) { nCascades = std::atoi(v.c_str()); continue; }
    if (k == "--visualize" && (v == "0" || v == "1")) { bVisualize = v == "1"; continue; }
    if (k == "--out" && !v.empty()) { out = v; continue; }
    std::fprintf(stderr, "usage: cascades [--backend vulkan|gl] [--size N] [--cascades 1..4] [--visualize 0|1] [--out file.png]\n");
    return 2;
  }
  try {
    sp::Ref<sp::Device> device = sp::CreateDevice(desc);  // D3D11CreateDevice, debug layer on
    sp::HRESULT hr = Run(device.get(), uSize, nCascades, bVisualize, out);
    if (sp::FAILED(hr)) return 1;
    std::printf("cascades: %s, %d cascades, %ux%u, wrote %s\n", device->Info().deviceName.c_str(), nCascades, uSize, uSize, out.c_str());
    if (device->ValidationErrorCount() > 0) {
      std::fprintf(stderr, "cascades: %llu validation errors, last: %s\n", (unsigned long long)device->ValidationErrorCount(),
                   device->LastValidationError().c_str());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascades: %s\n", e.what());
    return 1;
  }
}
