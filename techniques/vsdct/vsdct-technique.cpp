// The vsdct technique: virtual shadow depth cube textures (King, "Shadow Mapping Algorithms",
// NVIDIA; Newhall). One point light's six cube faces are tiles of one 2D depth atlas (3 x 2 tiles),
// each rendered with a viewport into its tile; a tiny indirection TextureCube maps a direction to
// its tile, so the lit pass reads the shadow with 2D comparison lookups (any PCF kernel of
// common/shadow-filter.hlsli) without selecting the face in ALU code.
//
// Faces: the table, window z and face matrices of techniques/cube/cube-faces.h (as the cube
// technique), so a tile holds exactly what the cube technique's face holds, plus its guard band.
//
// Indirection scheme (exact): the cube has one texel per face, point-sampled, holding that
// face's tile position in the atlas (texels, float) and the face number; the hardware's cube face
// selection is the face choice. The shader then computes the face coordinates from the direction
// itself: sc / ma = dot(S_f, d) / dot(M_f, d) with the face's axes from a 6-entry constant table
// indexed by that number: two dot products and a divide, no branch. Storing atlas coordinates per texel and filtering them
// (King's original) is exact only inside a face, where the atlas coordinate is affine in face uv;
// within half an indirection texel of a face edge the seamless cube filter (always on with
// Vulkan, and on GL as the RHI sets it) blends two faces' tiles, and point-sampling a larger map
// snaps lookups to its texel centres. Per-face constants have neither error at any size.
//
// Guard bands (`guard` texels): tile f is rendered with face f's frustum widened by `guard`
// texels on each side (its clip x, y scaled by R / (R + 2 guard)), so a filter tap that crosses
// the face edge reads real depth of the neighbouring directions from the same tile. They stay
// comparable with the receiver: a tile is one ordinary perspective map, storing for every
// direction it covers the planar z = a + b / dot(M_f, d) of its own face f (M_f its major axis;
// past the edge that is not max(|x|, |y|, |z|), the neighbour's), and the lit pass computes the
// receiver's uv and z with dot(M_f, d) of the face the indirection chose, which is the face of the
// tile it reads. So every tap is a comparison within one perspective map, as in any 2D PCF, and a
// tie the hardware breaks differently from cube-faces.h's FaceOf only moves the lookup into the
// guard band of the other tile, where the answer is the same.
// guard = 0: no band; taps are clamped into the face's R x R texels (shadow-filter's uvClamp),
// which is the seam error the guard bands remove.
#include <algorithm>
#include <stdexcept>

#include "pcf-params.h"
#include <string>

#include "cube/cube-culling.h"
#include "cube/cube-faces.h"
#include "hpsm-maps.h"
#include "local-lights.h"
#include <sp/tech/technique.h>

namespace sp::tech {
namespace {

// Why accel (techniques/hpsm-maps.h) is refused here.
const char* const kVsdctAccelRefusal =
    "secondary maps per atlas tile, with the indirection and guard band in the footprint, are not built yet; the cube technique has accel";

const char* const kFilters[] = {"hw2x2", "box", "gauss", "gathercmp", "poisson"};

class VsdctTechnique final : public Technique {
 public:
  std::string Name() const override { return "vsdct"; }

  std::vector<ParamSpec> Params() const override {
    return {
        {ParamSpec::Int, "light", "the point light shadowed (index into the scene's point lights = local light index)", "0", 0, kMaxLocalLights - 1, {}},
        {ParamSpec::Int, "resolution", "side of each face's tile in texels, guard band not included", "512", 16, 4096, {}},
        {ParamSpec::Float, "near", "near plane of every face, in world units (casters closer to the light are not drawn)", "0.05", 1e-4, 1e3, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias", "2.0", -100, 100, {}},
        {ParamSpec::Choice, "filter", "shadow filter (common/shadow-filter.hlsli)", "hw2x2", 0, 0, {"hw2x2", "box", "gauss", "gathercmp", "poisson", "pcss"}},
        PcfKernelParam("box, gauss, gathercmp, poisson"),
        {ParamSpec::Int, "guard", "guard band around each tile in texels, at least the filter's reach (hw2x2: 1, others: kernel/2 + 1); 0: clamp taps into the face instead",
         "5", 0, 64, {}},
        {ParamSpec::Int, "receiver_plane", "1: each tap compares the receiver's plane at the tap (exact, from the normal) and a texel's slope less, so wide kernels have no acne; 0: the centre's depth for every tap",
         "1", 0, 1, {}},
        {ParamSpec::Int, "cull_faces", "1: skip the faces whose frustum (widened by the guard band) meets neither the camera's nor a visible receiver (their tiles stay cleared: lit)", "1", 0, 1, {}},
        {ParamSpec::Choice, "resolution_from", "fixed: tiles of `resolution`; screen: each frame's tile from the screen size of the light's range sphere, between min_resolution and resolution (King's smaller tile)", "fixed", 0, 0, {"fixed", "screen"}},
        {ParamSpec::Int, "min_resolution", "resolution_from=screen: the smallest tile (face texels, guard band not included)", "64", 16, 4096, {}},
        {ParamSpec::Float, "texels_per_pixel", "resolution_from=screen: face texels per screen pixel across the light's range sphere", "1.0", 0.01, 100, {}},
        UnofferedAccelParam(kVsdctAccelRefusal),
    };
  }

  void Configure(Device& device, const ParamValues& p) override {
    RefuseAccel(p, "vsdct", kVsdctAccelRefusal);
    light_ = uint32_t(p.getInt("light"));
    device_ = &device;
    maxResolution_ = uint32_t(p.getInt("resolution"));
    fromScreen_ = p.getChoice("resolution_from") == "screen";
    minResolution_ = uint32_t(p.getInt("min_resolution"));
    texelsPerPixel_ = p.getFloat("texels_per_pixel");
    if (fromScreen_ && minResolution_ > maxResolution_)
      throw std::invalid_argument("vsdct: min_resolution=" + std::to_string(minResolution_) + " is above resolution=" + std::to_string(maxResolution_));
    near_ = p.getFloat("near");
    guard_ = uint32_t(p.getInt("guard"));
    cullFaces_ = p.getInt("cull_faces") != 0;
    // PCSS reads a footprint chosen per pixel, up to pcss_max_kernel wide, by point loads and a box in
    // one face's texels; vsdct's faces are atlas tiles of different resolutions whose guard bands
    // are sized for a fixed kernel, and its lookup through the indirection has no such path yet.
    if (p.getChoice("filter") == "pcss")
      throw std::invalid_argument("vsdct: filter=pcss is not offered: the faces are atlas tiles of their own resolutions with guard bands sized "
                                  "for a fixed kernel, and the indirect lookup has no PCSS path (use cube)");
    for (int i = 0; i < 5; ++i)
      if (p.getChoice("filter") == kFilters[i]) filter_ = i;
    kernel_ = p.getInt("kernel");
    CheckPcfKernel("vsdct", filter_, kernel_);
    receiverPlane_ = p.getInt("receiver_plane") != 0;
    // Texels a lookup reads beyond its centre's texel: the 2x2 tap one, an N-wide kernel N/2 more
    // (gathercmp's footprint and the Poisson disk's radius with its bilinear taps included).
    int reach = filter_ == 0 ? 1 : kernel_ / 2 + 1;
    if (guard_ != 0 && int(guard_) < reach)
      throw std::invalid_argument("vsdct: guard=" + std::to_string(guard_) + " is too small for filter=" + kFilters[filter_] +
                                  (filter_ == 0 ? "" : " kernel=" + std::to_string(kernel_)) + ", which reads " + std::to_string(reach) +
                                  " texel(s) past the face edge (use guard >= " + std::to_string(reach) + ", or guard=0 to clamp)");
    EnsureAtlas(maxResolution_);

    RASTERIZER_DESC rd;
    // As cube: the faces' bases are mirror images of a camera's, so both sides are drawn.
    rd.CullMode = CULL_NONE;
    rd.FrontCounterClockwise = true;
    rd.DepthBias = p.getInt("depth_bias");
    rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    // Clipping already keeps a face inside its viewport; the scissor makes sure no rasterizer
    // rounding at the tile's edge writes into the neighbouring tile.
    rd.ScissorEnable = true;
    rasterizer_ = device.CreateRasterizerState(rd);

    cmpSampler_ = MakeShadowComparisonSampler(device);
    SAMPLER_DESC ps;
    ps.Filter = FILTER_MIN_MAG_MIP_POINT;
    ps.AddressU = ps.AddressV = ps.AddressW = TEXTURE_ADDRESS_CLAMP;
    pointSampler_ = device.CreateSamplerState(ps);
    constants_ = MakeConstantBuffer(device, sizeof(Constants), "VsdctShadow constants");
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    const LocalLight& l = ShadowedPointLight("vsdct", light_, near_, frame);
    EnsureAtlas(fromScreen_ ? cube::ScreenSizedResolution(cube::ScreenRadius(l.position, l.range, frame.camera.position, frame.cameraProj, frame.height),
                                                          texelsPerPixel_, minResolution_, maxResolution_)
                            : maxResolution_);
    Constants c{};
    c.lightPosition = l.position;
    c.depthA = cube::DepthA(near_, l.range);
    c.depthB = cube::DepthB(near_, l.range);
    c.faceSize = float(resolution_);
    c.lightIndex = light_;
    c.guard = float(guard_);
    c.atlasSize = glm::vec2(3.0f * tile_, 2.0f * tile_);
    c.receiverPlane = receiverPlane_ ? 1 : 0;
    for (int f = 0; f < 6; ++f) {
      cube::FaceAxes ax = cube::Face(f);
      c.faceS[f] = glm::vec4(ax.s, 0.0f);
      c.faceT[f] = glm::vec4(ax.t, 0.0f);
      c.faceMajor[f] = glm::vec4(ax.major, 0.0f);
    }
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);

    ShaderResourceView* none = nullptr;
    ctx.PSSetShaderResources(0, 1, &none);
    ctx.OMSetRenderTargets(0, nullptr, dsv_.get());
    ctx.ClearDepthStencilView(dsv_.get(), CLEAR_DEPTH, 1.0f, 0);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    trianglesSubmitted_ = 0;
    facesRendered_ = 0;
    const std::vector<scene::Instance>& instances = frame.scene->instances;
    const glm::mat4 camera = frame.cameraProj * frame.cameraView;
    const std::vector<uint32_t> visible = cube::VisibleInstances(*frame.scene, camera);
    // A lookup reads its tile up to the guard band (or one texel, clamped) past the face's edge.
    const float widen = 1.0f + 2.0f * float(std::max(guard_, 1u) + 1) / float(resolution_);
    for (int f = 0; f < 6; ++f) {
      if (cullFaces_ && !cube::FaceNeeded(f, l.position, near_, l.range, widen, camera, *frame.scene, visible)) continue;
      ++facesRendered_;
      glm::uvec2 o = TileOrigin(f);
      VIEWPORT vp{float(o.x), float(o.y), float(tile_), float(tile_), 0, 1};
      RECT sc{int32_t(o.x), int32_t(o.y), int32_t(o.x + tile_), int32_t(o.y + tile_)};
      ctx.RSSetViewports(1, &vp);
      ctx.RSSetScissorRects(1, &sc);
      glm::mat4 viewProj = TileViewProj(f, l);
      trianglesSubmitted_ += drawer.DrawDepth(ctx, viewProj, [&](uint32_t i) { return cube::BoxMayMeetFrustum(viewProj, instances[i].worldBounds); });
    }
  }

  std::string LightingInclude() const override { return "vsdct/shadow.hlsli"; }
  // hw2x2 ignores the kernel: one variant for it, not four.
  std::vector<hlsl::Define> LightingDefines() const override {
    return {{"SHADOW_FILTER", std::to_string(filter_)}, {"SHADOW_KERNEL", std::to_string(filter_ == 0 ? 3 : kernel_)}};
  }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ctx.PSSetShaderResources(0, {srv_.get(), indirectionSrv_.get()});
    ctx.PSSetSamplers(0, {cmpSampler_.get(), pointSampler_.get()});
  }

  // The atlas (guard bands included) and the 6 x 16-byte indirection cube.
  ShadowStats Stats() const override { return {uint64_t(3 * tile_) * (2 * tile_) * 4 + 6 * 16, trianglesSubmitted_, facesRendered_}; }
  // The lab's layers are the faces, texels within the face's R x R (the guard band is not a
  // face's own area: its texels duplicate the neighbours'), as cube reports them.
  std::vector<ShadowLayer> Layers() const override { return std::vector<ShadowLayer>(6, {resolution_, resolution_}); }
  Texture2D* ShadowMapTexture() const override { return atlas_.get(); }  // the six faces' tiles in one slice
  int LabLocalLight(const scene::Scene&) const override { return int(light_); }  // point lights come first

 private:
  // The atlas and the indirection cube (whose tile origins depend on the tile size) for faces of
  // `resolution` texels; kept while the resolution stays.
  void EnsureAtlas(uint32_t resolution) {
    if (atlas_ && resolution == resolution_) return;
    resolution_ = resolution;
    tile_ = resolution_ + 2 * guard_;

    TEXTURE2D_DESC td;
    td.Width = 3 * tile_;
    td.Height = 2 * tile_;
    td.ArraySize = 1;  // read as a one-slice Texture2DArray, what shadow-filter.hlsli takes
    td.Format = FORMAT_R32_TYPELESS;
    td.BindFlags = BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE;
    atlas_ = device_->CreateTexture2D(td);
    atlas_->SetDebugName("vsdct depth atlas");
    dsv_ = MakeSliceDepthViews(*device_, atlas_.get())[0];
    srv_ = MakeSliceArraySrv(*device_, atlas_.get());

    // The indirection cube: per face (tile origin of the face's inner R x R texels, face, 0).
    float texels[6][4];
    SUBRESOURCE_DATA init[6];
    for (int f = 0; f < 6; ++f) {
      glm::uvec2 o = TileOrigin(f);
      texels[f][0] = float(o.x + guard_);
      texels[f][1] = float(o.y + guard_);
      texels[f][2] = float(f);
      texels[f][3] = 0.0f;
      init[f].pSysMem = texels[f];
      init[f].SysMemPitch = sizeof(texels[f]);
    }
    TEXTURE2D_DESC cd;
    cd.Width = cd.Height = 1;
    cd.ArraySize = 6;
    cd.Format = FORMAT_R32G32B32A32_FLOAT;
    cd.Usage = USAGE_IMMUTABLE;
    cd.BindFlags = BIND_SHADER_RESOURCE;
    cd.MiscFlags = RESOURCE_MISC_TEXTURECUBE;
    indirection_ = device_->CreateTexture2D(cd, init);
    indirection_->SetDebugName("vsdct indirection cube");
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.Format = FORMAT_R32G32B32A32_FLOAT;
    sd.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
    sd.TextureCube = {0, 1};
    indirectionSrv_ = device_->CreateShaderResourceView(indirection_.get(), &sd);
  }

  glm::uvec2 TileOrigin(int f) const { return glm::uvec2(uint32_t(f % 3) * tile_, uint32_t(f / 3) * tile_); }

  // Face f's clip transform with x and y scaled so the face's [-1, 1] covers the inner R texels
  // of the tile's R + 2 guard; z and w (so window z) are the face's own.
  glm::mat4 TileViewProj(int f, const LocalLight& l) const {
    glm::mat4 widen(1.0f);
    widen[0][0] = widen[1][1] = float(resolution_) / float(tile_);
    return widen * cube::FaceViewProj(f, l.position, near_, l.range);
  }

  // cbuffer VsdctShadow in shaders-hlsl/vsdct/shadow.hlsli.
  struct Constants {
    glm::vec3 lightPosition;
    float depthA;
    float depthB;
    float faceSize;
    uint32_t lightIndex;
    float guard;
    glm::vec2 atlasSize;
    uint32_t receiverPlane;
    float pad;
    glm::vec4 faceS[6], faceT[6], faceMajor[6];
  };
  static_assert(sizeof(Constants) == 48 + 3 * 6 * 16);

  Device* device_ = nullptr;
  uint32_t light_ = 0, resolution_ = 0, maxResolution_ = 0, minResolution_ = 64, guard_ = 0, tile_ = 0;
  bool fromScreen_ = false;
  float texelsPerPixel_ = 1.0f;
  float near_ = 0.05f;
  int filter_ = 0, kernel_ = 3;
  bool receiverPlane_ = true;
  Ref<Texture2D> atlas_, indirection_;
  Ref<DepthStencilView> dsv_;
  Ref<ShaderResourceView> srv_, indirectionSrv_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> cmpSampler_, pointSampler_;
  Ref<Buffer> constants_;
  uint64_t trianglesSubmitted_ = 0;
  uint32_t facesRendered_ = 0;
  bool cullFaces_ = true;
};

}  // namespace

std::unique_ptr<Technique> MakeVsdctTechnique() { return std::make_unique<VsdctTechnique>(); }

}  // namespace sp::tech
