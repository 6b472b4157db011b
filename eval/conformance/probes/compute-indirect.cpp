// GPU-driven work and D3D11's implicit ordering of UAV writes: a compute pass culls instances
// against a rectangle and writes the indirect arguments (through a raw view, a typed view, or
// CopyStructureCount of an append buffer); the indirect draw must render exactly the surviving
// instances. Also DispatchIndirect, and UAV writes read by the very next draw without any barrier
// call: as shader resources, as vertex and index buffers (buffers created with
// BIND_VERTEX_BUFFER / BIND_INDEX_BUFFER | BIND_UNORDERED_ACCESS), and pixel-shader UAV writes
// read by the following draw.
#include <algorithm>
#include <set>

#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Compute";

Ref<Buffer> ArgsBuffer(Device& dev, uint32_t bytes, const void* init, uint32_t misc = RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS) {
  return gpu::MakeBuffer(dev, BIND_UNORDERED_ACCESS, init, bytes, RESOURCE_MISC_DRAWINDIRECT_ARGS | misc);
}

// 64 instances on an 8 x 8 grid of 8-pixel cells of a 64 x 64 target, each a 6 x 6 quad inside
// its cell; instance k sits in cell Cell(k) (a permutation, so list order and screen order differ).
constexpr uint32_t kSize = 64, kInstances = 64;
uint32_t Cell(uint32_t k) { return (k * 29 + 7) % kInstances; }
struct Rect {
  float x0, y0, x1, y1;
};
Rect InstanceRect(uint32_t k) {
  float cx = float(Cell(k) % 8) * 8, cy = float(Cell(k) / 8) * 8;
  return {cx + 1, cy + 1, cx + 7, cy + 7};
}
// The culling rectangle: an instance survives when its centre lies inside.
const float kCull[4] = {12.0f, 5.0f, 50.0f, 41.0f};
bool Survives(uint32_t k) {
  Rect r = InstanceRect(k);
  float x = (r.x0 + r.x1) / 2, y = (r.y0 + r.y1) / 2;
  return x >= kCull[0] && x < kCull[2] && y >= kCull[1] && y < kCull[3];
}

const char* kCulling = R"(
StructuredBuffer<float4> rects : register(t0);
cbuffer Cull : register(b0) { float4 cullRect; };
bool Survives(uint k) {
  float2 c = (rects[k].xy + rects[k].zw) * 0.5;
  return all(c >= cullRect.xy) && all(c < cullRect.zw);
}

// Arguments through a raw view: DrawIndexedInstancedIndirect at byte 0, StartIndexLocation 3.
RWByteAddressBuffer rawArgs : register(u0);
RWStructuredBuffer<uint> visibleOut : register(u1);
[numthreads(1, 1, 1)] void ResetIndexed() { rawArgs.Store4(0, uint4(6, 0, 3, 0)); rawArgs.Store(16, 0); }
[numthreads(32, 1, 1)] void CullIndexed(uint k : SV_DispatchThreadID) {
  if (!Survives(k)) return;
  uint slot;
  rawArgs.InterlockedAdd(4, 1u, slot);
  visibleOut[slot] = k;
}

// Arguments through a typed R32_UINT view: DrawInstancedIndirect at element 4 (byte 16), with
// StartVertexLocation 6 (SV_VertexID counts from there in a non-indexed draw).
RWBuffer<uint> typedArgs : register(u0);
[numthreads(1, 1, 1)] void ResetTyped() { typedArgs[4] = 6; typedArgs[5] = 0; typedArgs[6] = 6; typedArgs[7] = 0; }
[numthreads(32, 1, 1)] void CullTyped(uint k : SV_DispatchThreadID) {
  if (!Survives(k)) return;
  uint slot;
  InterlockedAdd(typedArgs[5], 1, slot);
  visibleOut[slot] = k;
}

// Survivors appended; the count reaches the arguments through CopyStructureCount.
AppendStructuredBuffer<uint> visibleAppend : register(u0);
[numthreads(32, 1, 1)] void CullAppend(uint k : SV_DispatchThreadID) { if (Survives(k)) visibleAppend.Append(k); }

StructuredBuffer<uint> visible : register(t1);
struct V { float4 pos : SV_Position; nointerpolation uint id : INSTANCE; };
V VSMain(uint vid : SV_VertexID, uint inst : SV_InstanceID) {
  uint k = visible[inst];
  float4 r = rects[k];
  uint c = vid % 6;
  float2 corner = float2((c == 1 || c == 2 || c == 4) ? 1 : 0, (c == 2 || c == 4 || c == 5) ? 1 : 0);
  float2 p = lerp(r.xy, r.zw, corner);
  V o;
  o.pos = float4(p.x / 64 * 2 - 1, 1 - p.y / 64 * 2, 0.5, 1);
  o.id = k + 1;
  return o;
}
uint PSMain(V v) : SV_Target { return v.id; }
)";

enum class Cull { IndexedRaw, TypedArgs, AppendCount };

Result RunCulling(Device& device, Cull mode) {
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<Rect> rects(kInstances);
  for (uint32_t k = 0; k < kInstances; ++k) rects[k] = InstanceRect(k);
  Ref<Buffer> rectBuf = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, rects.data(), kInstances * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<ShaderResourceView> rectSrv = device.CreateShaderResourceView(rectBuf.get());
  Ref<Buffer> cull = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, kCull, 16);
  std::vector<uint32_t> zero(8, 0);
  BufferViews visible = MakeStructured(device, kInstances, 4, nullptr, mode == Cull::AppendCount ? uint32_t(BUFFER_UAV_FLAG_APPEND) : 0u);
  Ref<Buffer> args;
  Ref<UnorderedAccessView> argsUav;
  const char* prefix = mode == Cull::IndexedRaw ? "Indexed" : mode == Cull::TypedArgs ? "Typed" : "Append";
  ctx.CSSetShaderResources(0, {rectSrv.get()});
  ctx.CSSetConstantBuffers(0, {cull.get()});
  Ref<ComputeShader> reset, cullCs = MakeCS(device, kCulling, "gpu-culling", std::string("Cull") + prefix);
  if (mode == Cull::IndexedRaw) {
    args = ArgsBuffer(device, 32, zero.data());
    UNORDERED_ACCESS_VIEW_DESC d;
    d.Format = FORMAT_R32_TYPELESS;
    d.ViewDimension = UAV_DIMENSION_BUFFER;
    d.Buffer = {0, 8, BUFFER_UAV_FLAG_RAW};
    argsUav = device.CreateUnorderedAccessView(args.get(), &d);
  } else if (mode == Cull::TypedArgs) {
    args = ArgsBuffer(device, 32, zero.data(), 0);
    UNORDERED_ACCESS_VIEW_DESC d;
    d.Format = FORMAT_R32_UINT;
    d.ViewDimension = UAV_DIMENSION_BUFFER;
    d.Buffer = {0, 8, 0};
    argsUav = device.CreateUnorderedAccessView(args.get(), &d);
  } else {
    const uint32_t init[4] = {6, 0, 0, 0};  // VertexCountPerInstance 6; the instance count comes from the GPU
    args = gpu::MakeBuffer(device, 0, init, 16, RESOURCE_MISC_DRAWINDIRECT_ARGS);
  }
  if (argsUav) {
    reset = MakeCS(device, kCulling, "gpu-culling", std::string("Reset") + prefix);
    ctx.CSSetShader(reset.get());
    ctx.CSSetUnorderedAccessViews(0, {argsUav.get(), visible.uav.get()});
    ctx.Dispatch(1, 1, 1);
    ctx.CSSetShader(cullCs.get());
    ctx.Dispatch(kInstances / 32, 1, 1);
  } else {
    ctx.CSSetShader(cullCs.get());
    UnorderedAccessView* uavs[] = {visible.uav.get()};
    const uint32_t zeroCount[] = {0};
    ctx.CSSetUnorderedAccessViews(0, 1, uavs, zeroCount);
    ctx.Dispatch(kInstances / 32, 1, 1);
    ctx.CopyStructureCount(args.get(), 4, visible.uav.get());
  }
  ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr});

  DrawTarget target = MakeDrawTarget(device, kSize, kSize, FORMAT_R32_UINT);
  target.Clear(ctx, 0);
  target.Bind(ctx);
  Ref<VertexShader> vs = MakeVS(device, kCulling, "gpu-culling", "VSMain");
  Ref<PixelShader> ps = MakePS(device, kCulling, "gpu-culling", "PSMain");
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  ctx.VSSetShaderResources(0, {rectSrv.get(), visible.srv.get()});
  ctx.IASetInputLayout(nullptr);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  // Bound at byte offset 8: StartIndexLocation 3 then reads 0..5 from index 5 of the buffer.
  const uint32_t indices[] = {99, 99, 99, 99, 99, 0, 1, 2, 3, 4, 5};
  Ref<Buffer> ib = gpu::MakeBuffer(device, BIND_INDEX_BUFFER, indices, sizeof(indices));
  if (mode == Cull::IndexedRaw) {
    ctx.IASetIndexBuffer(ib.get(), FORMAT_R32_UINT, 8);
    ctx.DrawIndexedInstancedIndirect(args.get(), 0);
  } else {
    ctx.DrawInstancedIndirect(args.get(), mode == Cull::TypedArgs ? 16 : 0);
  }

  uint32_t survivors = 0;
  for (uint32_t k = 0; k < kInstances; ++k) survivors += Survives(k);
  Mismatches m("values");
  std::vector<uint32_t> a = ReadBufferAs<uint32_t>(device, args.get());
  m.Check(a[mode == Cull::TypedArgs ? 5 : 1], survivors, "InstanceCount written by the GPU");
  std::vector<uint32_t> px = ReadTextureAs<uint32_t>(device, target.texture.get());
  std::vector<uint32_t> cellOwner(kInstances);
  for (uint32_t k = 0; k < kInstances; ++k) cellOwner[Cell(k)] = k;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      uint32_t k = cellOwner[(y / 8) * 8 + x / 8];
      bool inside = x % 8 >= 1 && x % 8 < 7 && y % 8 >= 1 && y % 8 < 7;
      m.Check(px[y * kSize + x], inside && Survives(k) ? k + 1 : 0u, "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")");
    }
  return m.Finish("pixels");
}

}  // namespace

SP_PROBE(kGroup, "GPU culling: DrawIndexedInstancedIndirect with compute-written args (raw view)",
         "a compute pass culls instances and writes the arguments through RWByteAddressBuffer; the draw renders exactly the survivors") {
  return RunCulling(device, Cull::IndexedRaw);
}
SP_PROBE(kGroup, "GPU culling: DrawInstancedIndirect with compute-written args (typed view)",
         "the same through a typed R32_UINT view of the argument buffer, at a non-zero AlignedByteOffsetForArgs") {
  return RunCulling(device, Cull::TypedArgs);
}
SP_PROBE(kGroup, "GPU culling: CopyStructureCount of an append buffer into DrawInstancedIndirect args",
         "survivors appended by a compute pass; CopyStructureCount writes the InstanceCount the indirect draw uses") {
  return RunCulling(device, Cull::AppendCount);
}

SP_PROBE(kGroup, "DispatchIndirect with compute-written args",
         "thread-group counts written by a compute pass drive the next DispatchIndirect; 0 groups run nothing") {
  const char* cs = R"(
RWByteAddressBuffer args : register(u0);
[numthreads(1, 1, 1)] void Write() { args.Store3(12, uint3(3, 2, 1)); args.Store3(28, uint3(0, 5, 1)); }
RWStructuredBuffer<uint> hits : register(u0);
[numthreads(4, 1, 1)] void Count(uint3 g : SV_GroupID, uint i : SV_GroupIndex) { InterlockedAdd(hits[(g.z * 6 + g.y * 3 + g.x) * 4 + i], 1); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> zero(16, 0);
  Ref<Buffer> args = ArgsBuffer(device, 64, zero.data());
  UNORDERED_ACCESS_VIEW_DESC d;
  d.Format = FORMAT_R32_TYPELESS;
  d.ViewDimension = UAV_DIMENSION_BUFFER;
  d.Buffer = {0, 16, BUFFER_UAV_FLAG_RAW};
  Ref<UnorderedAccessView> argsUav = device.CreateUnorderedAccessView(args.get(), &d);
  std::vector<uint32_t> zeros(32, 0);
  BufferViews hits = MakeStructured(device, 32, 4, zeros.data());
  Ref<ComputeShader> write = MakeCS(device, cs, "dispatch-indirect", "Write"), count = MakeCS(device, cs, "dispatch-indirect", "Count");
  ctx.CSSetShader(write.get());
  ctx.CSSetUnorderedAccessViews(0, {argsUav.get()});
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetShader(count.get());
  ctx.CSSetUnorderedAccessViews(0, {hits.uav.get()});
  ctx.DispatchIndirect(args.get(), 12);
  ctx.DispatchIndirect(args.get(), 28);
  std::vector<uint32_t> h = ReadBufferAs<uint32_t>(device, hits.buffer.get());
  Mismatches m("counters");
  for (uint32_t i = 0; i < 32; ++i) m.Check(h[i], i < 24 ? 1u : 0u, "thread slot " + std::to_string(i));
  return m.Finish();
}

SP_PROBE(kGroup, "compute writes are visible to the next draw's shader resources",
         "a dispatch writes a texture array and a structured buffer; the next draw reads both as SRVs with no barrier call") {
  const char* src = R"(
RWTexture2DArray<float> texOut : register(u0);
RWStructuredBuffer<float> valuesOut : register(u1);
[numthreads(8, 8, 1)] void Write(uint3 id : SV_DispatchThreadID) {
  texOut[id] = id.x + id.y * 8 + id.z * 100;
  if (id.z == 0) valuesOut[id.x + id.y * 8] = -0.5 * (id.x * 8 + id.y);
}
Texture2DArray<float> tex : register(t0);
StructuredBuffer<float> values : register(t1);
float2 Read(float4 p : SV_Position) : SV_Target { return float2(tex.Load(int4(p.xy, 1, 0)), values[uint(p.x) + uint(p.y) * 8]); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t W = 8;
  TextureViews tex = MakeUavTexture(device, W, W, FORMAT_R32_FLOAT, 2, nullptr, true);
  BufferViews values = MakeStructured(device, W * W, 4);
  Ref<ComputeShader> write = MakeCS(device, src, "uav-then-srv", "Write");
  Ref<PixelShader> read = MakePS(device, src, "uav-then-srv", "Read");
  ctx.CSSetShader(write.get());
  ctx.CSSetUnorderedAccessViews(0, {tex.uav.get(), values.uav.get()});
  ctx.Dispatch(1, 1, 2);
  ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr});
  DrawTarget target = MakeDrawTarget(device, W, W, FORMAT_R32G32_FLOAT);
  target.Bind(ctx);
  RectDrawer rect(device);
  ctx.PSSetShader(read.get());
  ctx.PSSetShaderResources(0, {tex.srv.get(), values.srv.get()});
  rect.Draw(ctx, 0, 0, W, W, W, W);
  std::vector<float> px = ReadTextureAs<float>(device, target.texture.get());
  Mismatches m("pixels");
  for (uint32_t y = 0; y < W; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      std::string at = "(" + std::to_string(x) + "," + std::to_string(y) + ")";
      m.Check(px[(y * W + x) * 2], float(x + y * 8 + 100), "texture slice 1 read at " + at);
      m.Check(px[(y * W + x) * 2 + 1], -0.5f * float(x * 8 + y), "structured buffer read at " + at);
    }
  return m.Finish();
}

SP_PROBE(kGroup, "compute-written vertex and index buffers feed the next draw",
         "buffers created with BIND_VERTEX_BUFFER / BIND_INDEX_BUFFER | BIND_UNORDERED_ACCESS, written through raw UAVs, are read by the input "
         "assembler") {
  const char* src = R"(
RWByteAddressBuffer vertices : register(u0);  // { float2 pos; uint id; } per vertex
RWByteAddressBuffer indices : register(u1);   // 6 uint indices per quad
[numthreads(4, 1, 1)] void Write(uint q : SV_DispatchThreadID) {
  float x0 = q * 8 + 1, x1 = x0 + 5, y0 = 2 + q, y1 = 9 + q;
  float2 corners[4] = { float2(x0, y0), float2(x1, y0), float2(x1, y1), float2(x0, y1) };
  for (uint c = 0; c < 4; ++c) {
    float2 ndc = float2(corners[c].x / 32 * 2 - 1, 1 - corners[c].y / 16 * 2);
    vertices.Store3((q * 4 + c) * 12, uint3(asuint(ndc.x), asuint(ndc.y), q + 1));
  }
  uint b = q * 4;
  indices.Store3(q * 24, uint3(b, b + 1, b + 2));
  indices.Store3(q * 24 + 12, uint3(b, b + 2, b + 3));
}
struct V { float4 pos : SV_Position; nointerpolation uint id : ID; };
V VSMain(float2 pos : POSITION, uint id : ID) { V o; o.pos = float4(pos, 0.5, 1); o.id = id; return o; }
uint PSMain(V v) : SV_Target { return v.id; }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t W = 32, H = 16, Quads = 4;
  BufferViews vb = MakeRaw(device, Quads * 4 * 12, nullptr, BIND_VERTEX_BUFFER), ib = MakeRaw(device, Quads * 24, nullptr, BIND_INDEX_BUFFER);
  Ref<ComputeShader> write = MakeCS(device, src, "uav-vertex-buffer", "Write");
  ctx.CSSetShader(write.get());
  ctx.CSSetUnorderedAccessViews(0, {vb.uav.get(), ib.uav.get()});
  ctx.Dispatch(1, 1, 1);
  ctx.CSSetUnorderedAccessViews(0, {nullptr, nullptr});
  ShaderBytecode vsb = gpu::CompileInline(src, "conformance/uav-vertex-buffer.hlsl", "vs_5_0", "VSMain");
  Ref<VertexShader> vs = device.CreateVertexShader(vsb);
  Ref<PixelShader> ps = MakePS(device, src, "uav-vertex-buffer", "PSMain");
  INPUT_ELEMENT_DESC el[] = {{"POSITION", 0, FORMAT_R32G32_FLOAT, 0, 0, INPUT_PER_VERTEX_DATA, 0},
                             {"ID", 0, FORMAT_R32_UINT, 0, 8, INPUT_PER_VERTEX_DATA, 0}};
  Ref<InputLayout> layout = device.CreateInputLayout(el, 2, vsb);
  DrawTarget target = MakeDrawTarget(device, W, H, FORMAT_R32_UINT);
  target.Clear(ctx, 0);
  target.Bind(ctx);
  Buffer* vbs[] = {vb.buffer.get()};
  uint32_t stride = 12, offset = 0;
  ctx.IASetVertexBuffers(0, 1, vbs, &stride, &offset);
  ctx.IASetIndexBuffer(ib.buffer.get(), FORMAT_R32_UINT, 0);
  ctx.IASetInputLayout(layout.get());
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  ctx.DrawIndexed(Quads * 6, 0, 0);
  std::vector<uint32_t> px = ReadTextureAs<uint32_t>(device, target.texture.get());
  Mismatches m("pixels");
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t q = x / 8, expect = 0;
      if (x % 8 >= 1 && x % 8 < 6 && y >= 2 + q && y < 9 + q) expect = q + 1;
      m.Check(px[y * W + x], expect, "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")");
    }
  return m.Finish();
}

SP_PROBE(kGroup, "pixel-shader UAV writes are visible to the next draw",
         "UAVs bound with OMSetRenderTargetsAndUnorderedAccessViews are written by one draw and read by the next (as SRV) with no barrier call") {
  const char* src = R"(
RWStructuredBuffer<uint> counts : register(u1);
RWTexture2D<uint> ids : register(u2);
float4 Write(float4 p : SV_Position) : SV_Target {
  InterlockedAdd(counts[0], 1);
  ids[uint2(p.xy)] = uint(p.x) + uint(p.y) * 100 + 1;
  return 1;
}
Texture2D<uint> written : register(t0);
uint Read(float4 p : SV_Position) : SV_Target { return written.Load(int3(p.xy, 0)); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t W = 8, H = 4;
  DrawTarget color = MakeDrawTarget(device, W, H, FORMAT_R8G8B8A8_UNORM), copy = MakeDrawTarget(device, W, H, FORMAT_R32_UINT);
  std::vector<uint32_t> zeros(W * H, 0);
  BufferViews counts = MakeStructured(device, 4, 4, zeros.data());
  TextureViews ids = MakeUavTexture(device, W, H, FORMAT_R32_UINT, 1, zeros.data(), true);
  Ref<PixelShader> write = MakePS(device, src, "ps-uav-then-draw", "Write"), read = MakePS(device, src, "ps-uav-then-draw", "Read");
  RectDrawer rect(device);
  RenderTargetView* rtvs[] = {color.rtv.get()};
  UnorderedAccessView* uavs[] = {counts.uav.get(), ids.uav.get()};
  ctx.OMSetRenderTargetsAndUnorderedAccessViews(1, rtvs, nullptr, 1, 2, uavs, nullptr);
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(write.get());
  rect.Draw(ctx, 0, 0, 6, H, W, H);
  rect.Draw(ctx, 4, 1, 8, 3, W, H);
  // Rebinding the output merger without UAVs frees the texture for reading.
  RenderTargetView* copyRtvs[] = {copy.rtv.get()};
  ctx.OMSetRenderTargetsAndUnorderedAccessViews(1, copyRtvs, nullptr, 1, 0, nullptr, nullptr);
  ctx.PSSetShader(read.get());
  ctx.PSSetShaderResources(0, {ids.srv.get()});
  rect.Draw(ctx, 0, 0, W, H, W, H);
  Mismatches m("values");
  m.Check(ReadBufferAs<uint32_t>(device, counts.buffer.get())[0], 6 * H + 4 * 2, "pixel-shader invocations counted by InterlockedAdd");
  std::vector<uint32_t> px = ReadTextureAs<uint32_t>(device, copy.texture.get());
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      bool covered = x < 6 || (y >= 1 && y < 3);
      m.Check(px[y * W + x], covered ? x + y * 100 + 1 : 0u, "value read by the next draw at (" + std::to_string(x) + "," + std::to_string(y) + ")");
    }
  return m.Finish();
}

}  // namespace sp::conformance
