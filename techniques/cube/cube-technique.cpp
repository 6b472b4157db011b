// The cube technique: omnidirectional shadows of point lights in TextureCubes of depth (King,
// "Shadow Mapping Algorithms"). Six 90-degree faces, one DSV per face, each storing planar window z
// with the same near and far on every face, so the lit pass computes the reference depth from the
// major axis alone (z = a + b / max(|x|, |y|, |z|)) and compares with SampleCmpLevelZero on the
// TextureCube: seamless 2x2 hardware PCF across face edges, and wider kernels whose taps step
// across the edges onto the neighbouring face (shaders-hlsl/cube/shadow.hlsli). D3D11 rasterizer
// depth bias as in basic. The directional light is unshadowed.
//
// lights=one shadows the point light `light`; lights=all shadows up to `max_lights` of the scene's
// point lights, chosen per frame as King advises spending a budget: a light whose range sphere
// meets no visible receiver gets no map, the others are ranked by their size on screen and, with
// resolution_from=screen, each gets a face resolution from it (a light far away gets a small
// cube). Per face, casters are culled against the face frustum, and a face is skipped when its
// frustum meets neither the camera's nor any visible receiver (cull_faces).
//
// storage=radial: the variant for hardware without depth cube maps, to measure the difference: an
// R32_FLOAT cube of light-to-caster distance (rendered with a D32 depth buffer per face), compared
// in the shader on 2x2 Gathers with bilinear weights and a receiver slope bias (no rasterizer
// bias reaches a colour target).
//
// accel (techniques/hpsm-maps.h): every face of every slot's cube is a layer of the slot's
// secondary maps, built from a 2D-array view of the cube; a face is a perspective map, so a
// receiver plane's planar z is affine in its texels (the plane case as for spot), and the lit pass
// decides footprints that lie inside one face first (shaders-hlsl/cube/hpsm.hlsli).
#include <algorithm>
#include <memory>
#include <stdexcept>

#include "cube/cube-culling.h"
#include "cube/cube-faces.h"
#include "hpsm-maps.h"
#include "local-lights.h"
#include "pcf-params.h"
#include <sp/tech/technique.h>

namespace sp::tech {
namespace {

// Cube maps one frame may hold (t0..t7 of the lighting include).
constexpr uint32_t kMaxCubeSlots = 8;

class CubeTechnique final : public Technique, public HpsmCounterSource {
 public:
  std::string Name() const override { return "cube"; }

  std::vector<ParamSpec> Params() const override {
    std::vector<ParamSpec> specs = {
        {ParamSpec::Int, "light", "the point light shadowed (lights=one) or judged by the lab (lights=all): index into the scene's point lights = local light index", "0", 0, kMaxLocalLights - 1, {}},
        {ParamSpec::Int, "resolution", "width and height of each cube face in texels (resolution_from=screen: the largest)", "512", 16, 8192, {}},
        {ParamSpec::Float, "near", "near plane of every face, in world units (casters closer to the light are not drawn)", "0.05", 1e-4, 1e3, {}},
        {ParamSpec::Int, "depth_bias", "D3D11 DepthBias (units of the depth format)", "200", -1e7, 1e7, {}},
        {ParamSpec::Float, "slope_bias", "D3D11 SlopeScaledDepthBias (storage=depth)", "2.0", -100, 100, {}},
        {ParamSpec::Choice, "storage", "depth: planar window z in a depth cube, hardware comparison; radial: distance in an R32_FLOAT cube, compared in the shader", "depth", 0, 0, {"depth", "radial"}},
        {ParamSpec::Float, "radial_bias", "storage=radial: constant bias in world units", "0.01", 0, 1e3, {}},
        {ParamSpec::Int, "cull_faces", "1: skip the faces whose frustum (widened by the filter's reach) meets neither the camera's nor a visible receiver", "1", 0, 1, {}},
        {ParamSpec::Float, "radial_slope_bias", "storage=radial: bias in texel footprints times tan(angle to the light), at most 10", "1.5", 0, 100, {}},
        {ParamSpec::Choice, "filter", "comparison filter: the hardware's seamless 2x2, box/gauss kernels whose taps cross face edges, or pcss "
                                      "(the light as a sphere of radius light_size; storage=depth)", "hw2x2", 0, 0, {"hw2x2", "box", "gauss", "pcss"}},
        PcfKernelParam("box, gauss"),
        {ParamSpec::Choice, "lights", "one: the point light `light`; all: up to max_lights point lights, those lighting visible receivers, largest on screen first", "one", 0, 0, {"one", "all"}},
        {ParamSpec::Int, "max_lights", "lights=all: most point lights shadowed per frame (the rest stay unshadowed)", "8", 1, kMaxCubeSlots, {}},
        {ParamSpec::Choice, "resolution_from", "fixed: every cube at `resolution`; screen: each light's from the screen size of its range sphere, between min_resolution and resolution", "fixed", 0, 0, {"fixed", "screen"}},
        {ParamSpec::Int, "min_resolution", "resolution_from=screen: the smallest face resolution", "64", 16, 8192, {}},
        {ParamSpec::Float, "texels_per_pixel", "resolution_from=screen: face texels per screen pixel across the light's range sphere", "1.0", 0.01, 100, {}},
        {ParamSpec::Choice, "faces_pass", "per_face: one pass per face; single: one instanced pass into all six faces, the vertex shader choosing the face (storage=depth, needs the device capability vsRenderTargetArrayIndex)", "per_face", 0, 0, {"per_face", "single"}},
    };
    for (const ParamSpec& p : PcssParamSpecs(PcssLight::Local)) specs.push_back(p);
    for (ParamSpec& h : HpsmParams()) specs.push_back(h);
    return specs;
  }

  void Configure(Device& device, const ParamValues& p) override {
    device_ = &device;
    light_ = uint32_t(p.getInt("light"));
    resolution_ = uint32_t(p.getInt("resolution"));
    near_ = p.getFloat("near");
    radial_ = p.getChoice("storage") == "radial";
    radialBias_ = p.getFloat("radial_bias");
    radialSlope_ = p.getFloat("radial_slope_bias");
    cullFaces_ = p.getInt("cull_faces") != 0;
    const std::string& filter = p.getChoice("filter");
    filter_ = PcfFilterIndex(filter);
    kernel_ = std::stoi(p.getChoice("kernel"));
    CheckPcfKernel("cube", filter_, kernel_);
    pcss_ = PcssSettingsFrom(p);
    // The search reads the stored depths, which storage=radial keeps as distances compared in the
    // shader on Gathers: its own box would be needed; not offered.
    if (filter_ == kPcssFilter && radial_) throw std::invalid_argument("cube: filter=pcss needs storage=depth (storage=radial has no PCSS path)");
    allLights_ = p.getChoice("lights") == "all";
    slotCount_ = allLights_ ? uint32_t(p.getInt("max_lights")) : 1;
    fromScreen_ = p.getChoice("resolution_from") == "screen";
    minResolution_ = uint32_t(p.getInt("min_resolution"));
    texelsPerPixel_ = p.getFloat("texels_per_pixel");
    if (fromScreen_ && minResolution_ > resolution_)
      throw std::invalid_argument("cube: min_resolution=" + std::to_string(minResolution_) + " is above resolution=" + std::to_string(resolution_));
    slots_.assign(slotCount_, {});
    ConfigureAccel(p);

    if (radial_) {
      radialVs_ = device.CreateVertexShader(CompileTechniqueShader("cube/radial.hlsl", "vs_5_0", "VSMain"));
      radialPs_ = device.CreatePixelShader(CompileTechniqueShader("cube/radial.hlsl", "ps_5_0", "PSMain"));
    }
    RASTERIZER_DESC rd;
    // The faces' (s, t, major) bases are mirror images of a camera's, so winding flips between
    // faces' conventions; draw both sides (open meshes cast from either side anyway).
    rd.CullMode = CULL_NONE;
    rd.FrontCounterClockwise = true;
    if (!radial_) {
      rd.DepthBias = p.getInt("depth_bias");
      rd.SlopeScaledDepthBias = p.getFloat("slope_bias");
    }
    rasterizer_ = device.CreateRasterizerState(rd);

    SAMPLER_DESC smp;
    smp.Filter = radial_ ? FILTER_MIN_MAG_MIP_POINT : FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    smp.AddressU = smp.AddressV = smp.AddressW = TEXTURE_ADDRESS_CLAMP;
    smp.ComparisonFunc = radial_ ? COMPARISON_NEVER : COMPARISON_LESS_EQUAL;
    sampler_ = device.CreateSamplerState(smp);
    pointSampler_ = nullptr;
    if (filter_ == kPcssFilter) {
      SAMPLER_DESC ps;
      ps.Filter = FILTER_MIN_MAG_MIP_POINT;
      ps.AddressU = ps.AddressV = ps.AddressW = TEXTURE_ADDRESS_CLAMP;
      pointSampler_ = device.CreateSamplerState(ps);
    }
    constants_ = MakeConstantBuffer(device, sizeof(Constants), "CubeShadow constants");
    ConfigureFacesPass(device, p);
  }

  void RenderShadows(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame) override {
    GpuTimer::Scope timed(frame.timer, ctx, "shadow");
    const scene::Scene& s = *frame.scene;
    ShadowedPointLight("cube", light_, near_, frame);
    if (allLights_)
      for (uint32_t i = 0; i < s.pointLights.size(); ++i) ShadowedPointLight("cube", i, near_, frame);

    const glm::mat4 camera = frame.cameraProj * frame.cameraView;
    visible_ = cube::VisibleInstances(s, camera);

    std::vector<uint32_t> chosen = ChooseLights(frame, camera);
    Constants c{};
    c.radialBias = radialBias_;
    c.radialSlope = radialSlope_;
    c.labSlot = kMaxCubeSlots;  // none, unless the judged light has a map this frame
    c.pcss = glm::vec4(pcss_.lightSize, float(pcss_.searchTaps), float(pcss_.maxKernel), 0.0f);
    for (auto& slot : c.slots) slot.light = ~0u;

    ShaderResourceView* none = nullptr;
    ctx.PSSetShaderResources(0, 1, &none);
    ctx.RSSetState(rasterizer_.get());
    ctx.OMSetDepthStencilState(nullptr, 0);
    trianglesSubmitted_ = 0;
    facesRendered_ = 0;
    for (uint32_t k = 0; k < slotCount_; ++k) {
      Slot& slot = slots_[k];
      if (k >= chosen.size()) {
        slot.light = ~0u;
        continue;
      }
      const LocalLight& l = frame.localLights[chosen[k]];
      EnsureSlotMaps(slot, ResolutionFor(l, frame));
      slot.light = chosen[k];
      c.slots[k] = {l.position, cube::DepthA(near_, l.range), cube::DepthB(near_, l.range), float(slot.resolution), chosen[k], l.range};
      if (chosen[k] == light_) c.labSlot = k;
      c.passLightPosition = l.position;
      ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
      RenderSlot(ctx, drawer, frame, slot, l, camera);
    }
    ctx.UpdateSubresource(constants_.get(), 0, nullptr, &c, 0, 0);
    labSlot_ = c.labSlot;
    if (hpsm_.accel != ShadowAccel::None) {
      ctx.OMSetRenderTargets(0, nullptr, nullptr);
      GpuTimer::Scope built(frame.timer, ctx, "hpsm");
      for (uint32_t k = 0; k < slotCount_ && k < chosen.size(); ++k) slots_[k].hpsm->Build(ctx, slots_[k].faceArray.get());
    }
  }

  std::string LightingInclude() const override { return "cube/shadow.hlsli"; }
  std::vector<hlsl::Define> LightingDefines() const override {
    std::vector<hlsl::Define> d = {{"SP_CUBE_RADIAL", radial_ ? "1" : "0"},
            {"SP_CUBE_SLOTS", std::to_string(slotCount_)},
            {"SHADOW_FILTER", std::to_string(filter_)},
            {"SHADOW_KERNEL", std::to_string(filter_ == kPcssFilter ? 3 : kernel_)}};
    for (hlsl::Define& h : HpsmDefines(hpsm_)) d.push_back(h);
    return d;
  }

  void BindLighting(DeviceContext& ctx) override {
    ctx.PSSetConstantBuffers(2, {constants_.get()});
    ShaderResourceView* srvs[kMaxCubeSlots] = {};
    for (uint32_t k = 0; k < slotCount_; ++k) srvs[k] = slots_[k].light == ~0u ? nullptr : slots_[k].srv.get();
    ctx.PSSetShaderResources(0, slotCount_, srvs);
    ctx.PSSetSamplers(0, {sampler_.get(), pointSampler_.get()});
    if (hpsm_.accel != ShadowAccel::None) {
      // t8 + k: CubeHpsm<k>; every slot counts into slot 0's counters (slot 0 is filled first).
      for (uint32_t k = 0; k < slotCount_; ++k) srvs[k] = slots_[k].light == ~0u ? nullptr : slots_[k].hpsm->srv();
      ctx.PSSetShaderResources(kMaxCubeSlots, slotCount_, srvs);
      if (slots_[0].hpsm) slots_[0].hpsm->BindCounters(ctx);
    }
  }
  HpsmCounts HpsmDecisions() const override {
    return slots_.empty() || !slots_[0].hpsm ? HpsmCounts{} : slots_[0].hpsm->ReadCounters(*device_->GetImmediateContext());
  }

  // Every cube held, and with storage=radial the depth buffers of their passes.
  ShadowStats Stats() const override {
    uint64_t bytes = 0;
    for (const Slot& slot : slots_) bytes += uint64_t(slot.resolution) * slot.resolution * 4 * (radial_ ? 7 : 6) + (slot.hpsm ? slot.hpsm->memoryBytes() : 0);
    return {bytes, trianglesSubmitted_, facesRendered_};
  }
  // The judged light's six faces.
  std::vector<ShadowLayer> Layers() const override {
    uint32_t r = labSlot_ < slotCount_ ? slots_[labSlot_].resolution : resolution_;
    return std::vector<ShadowLayer>(6, {r, r});
  }
  // The judged light's cube (its six faces as slices), what Layers() describes.
  Texture2D* ShadowMapTexture() const override { return labSlot_ < slotCount_ ? slots_[labSlot_].cube.get() : nullptr; }
  int LabLocalLight(const scene::Scene&) const override { return int(light_); }  // point lights come first

 private:
  struct Slot {
    uint32_t light = ~0u;  // local light index this frame, ~0u when unused
    uint32_t resolution = 0;
    Ref<Texture2D> cube, radialDepth;
    std::vector<Ref<DepthStencilView>> faces;  // depth: one per face; radial: the passes' depth buffer
    std::vector<Ref<RenderTargetView>> faceRtvs;
    Ref<ShaderResourceView> srv;
    Ref<DepthStencilView> allFaces;  // faces_pass=single
    Ref<ShaderResourceView> faceArray;  // accel: the six faces as a Texture2DArray, the build's input
    std::shared_ptr<HpsmMaps> hpsm;     // accel: one layer per face
  };

  // accel: storage=depth only (radial distance is not affine in a face's texels), and a block no
  // wider than the smallest face the slots may get.
  void ConfigureAccel(const ParamValues& p) {
    uint32_t smallest = fromScreen_ ? minResolution_ : resolution_;
    // cube's PCSS searches and filters in direction space across face edges (shadow-pcss-cube):
    // its reach in a face's texels is not the 2D bound hpsm.hlsli derives.
    if (filter_ == kPcssFilter && p.getChoice("accel") != "none")
      throw std::invalid_argument("cube: accel=" + p.getChoice("accel") + " is not offered with filter=pcss (its search and box run in direction space across face edges, not in one face's texels)");
    hpsm_ = ReadHpsmSettings(p, filter_, kernel_, smallest);
    if (hpsm_.accel == ShadowAccel::None) return;
    if (radial_)
      throw std::invalid_argument("cube: accel=" + p.getChoice("accel") + " needs storage=depth (storage=radial stores distances, which are not affine in a face's texels)");
    // The lookup decides only footprints whose rectangle, widened by a texel, lies inside a face.
    uint32_t footprint = uint32_t(2 * hpsm_.reach + 6);
    if (footprint > smallest)
      throw std::invalid_argument("cube: accel needs faces of at least " + std::to_string(footprint) + " texels for filter's footprint; " +
                                  (fromScreen_ ? "min_resolution" : "resolution") + " is " + std::to_string(smallest));
  }

  // faces_pass=single: one DSV over a cube's six faces, drawn into with the face chosen per instance.
  void ConfigureFacesPass(Device& device, const ParamValues& p) {
    onePass_ = p.getChoice("faces_pass") == "single";
    if (!onePass_) return;
    if (radial_) throw std::invalid_argument("cube: faces_pass=single needs storage=depth (storage=radial renders each face with its own colour target)");
    if (!device.Info().vsRenderTargetArrayIndex)
      throw std::invalid_argument(std::string("cube: faces_pass=single needs the device capability vsRenderTargetArrayIndex (a vertex shader writing "
                                              "SV_RenderTargetArrayIndex), which this ") + BackendName(device.GetBackend()) + " device lacks; use faces_pass=per_face");
  }

  static Ref<DepthStencilView> AllFacesView(Device& device, Texture2D* cube) {
    DEPTH_STENCIL_VIEW_DESC dv;
    dv.Format = FORMAT_D32_FLOAT;
    dv.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
    dv.Texture2DArray = {0, 0, 6};
    return device.CreateDepthStencilView(cube, &dv);
  }

  // RenderSlot's six passes as one: the same face culling (a skipped face gets no instances, but is
  // cleared with the rest), the same matrices and rasterizer state, so the same depth bits.
  void RenderSlotInOnePass(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame, Slot& slot, const LocalLight& l, const glm::mat4& camera,
                           float widen) {
    const std::vector<scene::Instance>& instances = frame.scene->instances;
    glm::mat4 viewProj[6];
    bool skip[6];
    for (int f = 0; f < 6; ++f) {
      viewProj[f] = cube::FaceViewProj(f, l.position, near_, l.range);
      skip[f] = cullFaces_ && !cube::FaceNeeded(f, l.position, near_, l.range, widen, camera, *frame.scene, visible_);
      if (!skip[f]) ++facesRendered_;
    }
    ctx.OMSetRenderTargets(0, nullptr, slot.allFaces.get());
    ctx.ClearDepthStencilView(slot.allFaces.get(), CLEAR_DEPTH, 1.0f, 0);
    trianglesSubmitted_ += drawer.DrawDepthLayered(ctx, viewProj, 6, [&](uint32_t i, uint32_t f) {
      return !skip[f] && cube::BoxMayMeetFrustum(viewProj[f], instances[i].worldBounds);
    });
  }

  // The lights shadowed this frame: lights=one, the chosen light; lights=all, the point lights
  // whose range sphere meets a visible receiver's box and the camera frustum, largest on screen
  // first, at most max_lights.
  std::vector<uint32_t> ChooseLights(const FrameInputs& frame, const glm::mat4& camera) const {
    if (!allLights_) return {light_};
    const scene::Scene& s = *frame.scene;
    std::vector<std::pair<float, uint32_t>> ranked;
    for (uint32_t i = 0; i < s.pointLights.size(); ++i) {
      const LocalLight& l = frame.localLights[i];
      scene::Bounds sphere;
      sphere.extend(l.position - glm::vec3(l.range));
      sphere.extend(l.position + glm::vec3(l.range));
      if (!cube::BoxMayMeetFrustum(camera, sphere)) continue;
      bool lights = false;
      for (uint32_t v : visible_) {
        const scene::Bounds& b = s.instances[v].worldBounds;
        glm::vec3 nearest = glm::clamp(l.position, b.min, b.max);
        if (glm::dot(nearest - l.position, nearest - l.position) <= l.range * l.range) {
          lights = true;
          break;
        }
      }
      if (lights) ranked.push_back({ScreenRadius(l, frame), i});
    }
    std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<uint32_t> chosen;
    for (size_t k = 0; k < ranked.size() && k < slotCount_; ++k) chosen.push_back(ranked[k].second);
    return chosen;
  }

  static float ScreenRadius(const LocalLight& l, const FrameInputs& frame) {
    return cube::ScreenRadius(l.position, l.range, frame.camera.position, frame.cameraProj, frame.height);
  }

  uint32_t ResolutionFor(const LocalLight& l, const FrameInputs& frame) const {
    return fromScreen_ ? cube::ScreenSizedResolution(ScreenRadius(l, frame), texelsPerPixel_, minResolution_, resolution_) : resolution_;
  }

  void EnsureSlotMaps(Slot& slot, uint32_t resolution) {
    if (slot.cube && slot.resolution == resolution) return;
    Device& device = *device_;
    slot = {};
    slot.resolution = resolution;
    TEXTURE2D_DESC td;
    td.Width = td.Height = resolution;
    td.ArraySize = 6;
    td.Format = radial_ ? FORMAT_R32_FLOAT : FORMAT_R32_TYPELESS;
    td.BindFlags = (radial_ ? BIND_RENDER_TARGET : BIND_DEPTH_STENCIL) | BIND_SHADER_RESOURCE;
    td.MiscFlags = RESOURCE_MISC_TEXTURECUBE;
    slot.cube = device.CreateTexture2D(td);
    slot.cube->SetDebugName(radial_ ? "cube shadow map (radial distance)" : "cube shadow map");
    if (radial_) {
      for (uint32_t f = 0; f < 6; ++f) {
        RENDER_TARGET_VIEW_DESC rv;
        rv.Format = FORMAT_R32_FLOAT;
        rv.ViewDimension = RTV_DIMENSION_TEXTURE2DARRAY;
        rv.Texture2DArray = {0, f, 1};
        slot.faceRtvs.push_back(device.CreateRenderTargetView(slot.cube.get(), &rv));
      }
      TEXTURE2D_DESC dd;
      dd.Width = dd.Height = resolution;
      dd.Format = FORMAT_D32_FLOAT;
      dd.BindFlags = BIND_DEPTH_STENCIL;
      slot.radialDepth = device.CreateTexture2D(dd);
      slot.radialDepth->SetDebugName("cube radial pass depth");
      slot.faces.push_back(device.CreateDepthStencilView(slot.radialDepth.get()));
    } else {
      slot.faces = MakeSliceDepthViews(device, slot.cube.get());
      if (onePass_) slot.allFaces = AllFacesView(device, slot.cube.get());
    }
    SHADER_RESOURCE_VIEW_DESC sd;
    sd.Format = FORMAT_R32_FLOAT;
    sd.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
    sd.TextureCube = {0, 1};
    slot.srv = device.CreateShaderResourceView(slot.cube.get(), &sd);
    if (hpsm_.accel != ShadowAccel::None) {
      slot.faceArray = MakeSliceArraySrv(device, slot.cube.get());
      slot.hpsm = std::make_shared<HpsmMaps>(device, hpsm_, resolution, resolution, 6);
    }
  }

  void RenderSlot(DeviceContext& ctx, SceneDrawer& drawer, const FrameInputs& frame, Slot& slot, const LocalLight& l, const glm::mat4& camera) {
    const std::vector<scene::Instance>& instances = frame.scene->instances;
    VIEWPORT vp{0, 0, float(slot.resolution), float(slot.resolution), 0, 1};
    ctx.RSSetViewports(1, &vp);
    // The lookup reads past a face's edge: the 2x2 filter one texel, a kernel its half width more.
    // pcss: search and box stay within pcss_max_kernel / 2 texels.
    const int reach = filter_ == kPcssFilter ? pcss_.maxKernel / 2 + 1 : filter_ ? kernel_ / 2 : 0;
    const float widen = 1.0f + 2.0f * float(2 + reach) / float(slot.resolution);
    if (slot.allFaces) return RenderSlotInOnePass(ctx, drawer, frame, slot, l, camera, widen);
    for (int f = 0; f < 6; ++f) {
      glm::mat4 viewProj = cube::FaceViewProj(f, l.position, near_, l.range);
      // A skipped face is still cleared (to lit), so no earlier frame's depths remain in it.
      bool skip = cullFaces_ && !cube::FaceNeeded(f, l.position, near_, l.range, widen, camera, *frame.scene, visible_);
      if (!skip) ++facesRendered_;
      auto keep = [&](uint32_t i) { return !skip && cube::BoxMayMeetFrustum(viewProj, instances[i].worldBounds); };
      if (radial_) {
        RenderTargetView* rtv = slot.faceRtvs[f].get();
        ctx.OMSetRenderTargets(1, &rtv, slot.faces[0].get());
        const float far[4] = {3.0e38f, 0, 0, 0};  // nothing: lit at any distance
        ctx.ClearRenderTargetView(rtv, far);
        ctx.ClearDepthStencilView(slot.faces[0].get(), CLEAR_DEPTH, 1.0f, 0);
        ctx.PSSetConstantBuffers(2, {constants_.get()});
        trianglesSubmitted_ += drawer.DrawDepth(ctx, viewProj, keep, {radialVs_.get(), radialPs_.get()});
      } else {
        ctx.OMSetRenderTargets(0, nullptr, slot.faces[f].get());
        ctx.ClearDepthStencilView(slot.faces[f].get(), CLEAR_DEPTH, 1.0f, 0);
        trianglesSubmitted_ += drawer.DrawDepth(ctx, viewProj, keep);
      }
    }
  }

  // cbuffer CubeShadow in shaders-hlsl/cube/constants.hlsli.
  struct SlotConstants {
    glm::vec3 lightPosition;
    float depthA;
    float depthB;
    float faceSize;
    uint32_t light;  // local light index, ~0u for an unused slot
    float range;
  };
  struct Constants {
    glm::vec3 passLightPosition;  // the light whose faces are being rendered (storage=radial)
    float radialBias;
    float radialSlope;
    uint32_t labSlot;
    float pad[2];
    SlotConstants slots[kMaxCubeSlots];
    glm::vec4 pcss;  // filter=pcss: radius, search taps, max kernel, unused
  };
  static_assert(sizeof(SlotConstants) == 32 && sizeof(Constants) == 48 + 32 * kMaxCubeSlots);

  Device* device_ = nullptr;
  uint32_t light_ = 0, resolution_ = 0, minResolution_ = 64;
  float near_ = 0.05f, texelsPerPixel_ = 1.0f;
  bool radial_ = false, allLights_ = false, fromScreen_ = false, cullFaces_ = true, onePass_ = false;
  int filter_ = 0, kernel_ = 3;
  HpsmSettings hpsm_;
  float radialBias_ = 0, radialSlope_ = 0;
  PcssSettings pcss_;
  uint32_t slotCount_ = 1, labSlot_ = kMaxCubeSlots;
  std::vector<Slot> slots_;
  std::vector<uint32_t> visible_;
  Ref<VertexShader> radialVs_;
  Ref<PixelShader> radialPs_;
  Ref<RasterizerState> rasterizer_;
  Ref<SamplerState> sampler_, pointSampler_;  // pointSampler_: filter=pcss's blocker search (s1)
  Ref<Buffer> constants_;
  uint64_t trianglesSubmitted_ = 0;
  uint32_t facesRendered_ = 0;
};

}  // namespace

std::unique_ptr<Technique> MakeCubeTechnique() { return std::make_unique<CubeTechnique>(); }

}  // namespace sp::tech
