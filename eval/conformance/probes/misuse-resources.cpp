// Misuse of resources, views, copies, maps and queries: each call D3D11 fails (E_INVALIDARG) or
// its debug layer reports must throw sp::Error with the documented id, naming the call and the
// object, on every backend. One probe per error id; each tries several triggers of that id.
#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Misuse";

Ref<Buffer> Named(Ref<Buffer> b, const char* name) {
  b->SetDebugName(name);
  return b;
}
Ref<Texture2D> Named(Ref<Texture2D> t, const char* name) {
  t->SetDebugName(name);
  return t;
}

TEXTURE2D_DESC Tex(uint32_t w, uint32_t h, FORMAT f, uint32_t bind) {
  TEXTURE2D_DESC d;
  d.Width = w;
  d.Height = h;
  d.Format = f;
  d.BindFlags = bind;
  return d;
}

}  // namespace

SP_PROBE(kGroup, "SP_INVALID_ARGUMENT: null or out-of-range arguments",
         "null resources, over-limit dispatches, misaligned offsets, views without counters") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Buffer> ib = Named(gpu::MakeBuffer(device, BIND_INDEX_BUFFER, nullptr, 64), "indices");
  BufferViews plain = MakeStructured(device, 4, 4);
  plain.uav->SetDebugName("plain uav");
  Ref<Buffer> dst = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, nullptr, 16, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  TextureViews ui = MakeUavTexture(device, 4, 4, FORMAT_R32_UINT);
  ui.uav->SetDebugName("uint uav");
  const float f[4] = {1, 2, 3, 4};
  std::vector<uint8_t> junk(64, 7);
  return ExpectErrors(
      ErrorId::INVALID_ARGUMENT,
      {{"CreateShaderResourceView", "null", {"pResource is null"}, [&] { device.CreateShaderResourceView(nullptr); }},
       {"ShaderBytecode::Deserialize", "bytecode blob", {"bad magic"}, [&] { device.CreatePixelShader(junk.data(), junk.size()); }},
       {"Dispatch", "thread groups", {"65535"}, [&] { ctx.Dispatch(70000, 1, 1); }},
       {"IASetIndexBuffer", "indices", {"multiple of the index size"}, [&] { ctx.IASetIndexBuffer(ib.get(), FORMAT_R16_UINT, 3); }},
       {"CopyStructureCount", "plain uav", {"hidden counter"}, [&] { ctx.CopyStructureCount(dst.get(), 0, plain.uav.get()); }},
       {"ClearUnorderedAccessViewFloat", "uint uav", {"ClearUnorderedAccessViewUint"}, [&] { ctx.ClearUnorderedAccessViewFloat(ui.uav.get(), f); }}});
}

SP_PROBE(kGroup, "SP_INVALID_DESC: a description field D3D11 does not allow",
         "non-square cube maps, bad anisotropy, bad strides, query MiscFlags, append on raw views") {
  Ref<Buffer> raw = Named(gpu::MakeBuffer(device, BIND_UNORDERED_ACCESS, nullptr, 64, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS), "raw buffer");
  return ExpectErrors(ErrorId::INVALID_DESC,
                      {{"CreateTexture2D",
                        "Texture2D 8x4 R8G8B8A8_UNORM",
                        {"square"},
                        [&] {
                          TEXTURE2D_DESC d = Tex(8, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
                          d.ArraySize = 6;
                          d.MiscFlags = RESOURCE_MISC_TEXTURECUBE;
                          device.CreateTexture2D(d);
                        }},
                       {"CreateSamplerState",
                        "SamplerState",
                        {"MaxAnisotropy"},
                        [&] {
                          SAMPLER_DESC s;
                          s.Filter = FILTER_ANISOTROPIC;
                          s.MaxAnisotropy = 17;
                          device.CreateSamplerState(s);
                        }},
                       {"CreateBuffer",
                        "Buffer, 60 bytes",
                        {"StructureByteStride"},
                        [&] { gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, nullptr, 60, RESOURCE_MISC_BUFFER_STRUCTURED, 6); }},
                       {"CreateQuery",
                        "Query",
                        {"MiscFlags"},
                        [&] {
                          QUERY_DESC q;
                          q.Query = QUERY_OCCLUSION;
                          q.MiscFlags = 1;
                          device.CreateQuery(q);
                        }},
                       {"CreateUnorderedAccessView", "raw buffer", {"BUFFER_UAV_FLAG_APPEND"}, [&] {
                          UNORDERED_ACCESS_VIEW_DESC u;
                          u.Format = FORMAT_R32_TYPELESS;
                          u.ViewDimension = UAV_DIMENSION_BUFFER;
                          u.Buffer = {0, 16, BUFFER_UAV_FLAG_RAW | BUFFER_UAV_FLAG_APPEND};
                          device.CreateUnorderedAccessView(raw.get(), &u);
                        }}});
}

SP_PROBE(kGroup, "SP_SIZE_OUT_OF_RANGE: zero or over-limit sizes",
         "textures over 16384, zero-byte buffers, constant buffers not a multiple of 16, too many mips") {
  return ExpectErrors(ErrorId::SIZE_OUT_OF_RANGE,
                      {{"CreateTexture2D",
                        "Texture2D 20000x4",
                        {"16384"},
                        [&] { gpu::MakeTexture2D(device, 20000, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE); }},
                       {"CreateBuffer", "Buffer, 0 bytes", {"ByteWidth"}, [&] { gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, nullptr, 0); }},
                       {"CreateBuffer", "Buffer, 20 bytes", {"multiple of 16"}, [&] { gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, nullptr, 20); }},
                       {"CreateBuffer", "Buffer, 65552 bytes", {"65536"}, [&] { gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, nullptr, 65552); }},
                       {"CreateTexture2D", "Texture2D 4x4", {"MipLevels"}, [&] {
                          gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, nullptr, 5);
                        }}});
}

SP_PROBE(kGroup, "SP_FORMAT_UNSUPPORTED: a format that cannot be used this way",
         "R32G32B32 textures, view-only formats as textures, 8-bit index buffers") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Buffer> ib = Named(gpu::MakeBuffer(device, BIND_INDEX_BUFFER, nullptr, 64), "byte indices");
  return ExpectErrors(ErrorId::FORMAT_UNSUPPORTED,
                      {{"CreateTexture2D",
                        "R32G32B32_FLOAT",
                        {"only supported for buffers"},
                        [&] { gpu::MakeTexture2D(device, 4, 4, FORMAT_R32G32B32_FLOAT, BIND_SHADER_RESOURCE); }},
                       {"CreateTexture2D",
                        "R24_UNORM_X8_TYPELESS",
                        {"view format", "R24G8_TYPELESS"},
                        [&] { gpu::MakeTexture2D(device, 4, 4, FORMAT_R24_UNORM_X8_TYPELESS, BIND_SHADER_RESOURCE); }},
                       {"IASetIndexBuffer", "byte indices", {"R16_UINT or R32_UINT"}, [&] { ctx.IASetIndexBuffer(ib.get(), FORMAT_R8_UINT, 0); }}});
}

SP_PROBE(kGroup, "SP_BIND_FLAGS_INVALID: a resource lacks (or may not have) a bind flag",
         "views and bindings need the matching bind flag; constant buffers and depth textures restrict the others") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> albedo = Named(gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE), "albedo");
  Ref<Buffer> verts = Named(gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, nullptr, 64), "verts");
  Ref<Buffer> plain = Named(gpu::MakeBuffer(device, BIND_UNORDERED_ACCESS, nullptr, 64, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS), "not args");
  Ref<Buffer> indices = Named(gpu::MakeBuffer(device, BIND_INDEX_BUFFER, nullptr, 64), "index only");
  Buffer* vbs[] = {indices.get()};
  uint32_t stride = 16, offset = 0;
  return ExpectErrors(
      ErrorId::BIND_FLAGS_INVALID,
      {{"CreateRenderTargetView", "albedo", {"BIND_RENDER_TARGET"}, [&] { device.CreateRenderTargetView(albedo.get()); }},
       {"CreateUnorderedAccessView", "albedo", {"BIND_UNORDERED_ACCESS"}, [&] { device.CreateUnorderedAccessView(albedo.get()); }},
       {"PSSetConstantBuffers", "verts", {"BIND_CONSTANT_BUFFER"}, [&] { ctx.PSSetConstantBuffers(0, {verts.get()}); }},
       {"IASetVertexBuffers", "index only", {"BIND_VERTEX_BUFFER"}, [&] { ctx.IASetVertexBuffers(0, 1, vbs, &stride, &offset); }},
       {"CreateBuffer",
        "BIND_CONSTANT_BUFFER",
        {"cannot be combined"},
        [&] { gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER | BIND_SHADER_RESOURCE, nullptr, 64); }},
       {"CreateTexture2D",
        "D32_FLOAT",
        {"TYPELESS"},
        [&] { gpu::MakeTexture2D(device, 4, 4, FORMAT_D32_FLOAT, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE); }},
       {"DrawInstancedIndirect", "not args", {"RESOURCE_MISC_DRAWINDIRECT_ARGS"}, [&] { ctx.DrawInstancedIndirect(plain.get(), 0); }}});
}

SP_PROBE(kGroup, "SP_USAGE_INVALID: a usage / CPU access combination D3D11 forbids",
         "dynamic without CPU write, default with CPU access, staging with bind flags, UpdateSubresource on dynamic") {
  DeviceContext& ctx = *device.GetImmediateContext();
  BUFFER_DESC dyn;
  dyn.ByteWidth = 64;
  dyn.Usage = USAGE_DYNAMIC;
  dyn.BindFlags = BIND_CONSTANT_BUFFER;
  dyn.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> dynamic = Named(device.CreateBuffer(dyn), "per-frame constants");
  std::vector<uint8_t> data(64);
  return ExpectErrors(
      ErrorId::USAGE_INVALID,
      {{"CreateBuffer",
        "BIND_CONSTANT_BUFFER",
        {"CPU_ACCESS_WRITE"},
        [&] {
          BUFFER_DESC d = dyn;
          d.CPUAccessFlags = 0;
          device.CreateBuffer(d);
        }},
       {"CreateTexture2D",
        "Texture2D 4x4",
        {"USAGE_DEFAULT"},
        [&] {
          TEXTURE2D_DESC d = Tex(4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
          d.CPUAccessFlags = CPU_ACCESS_READ;
          device.CreateTexture2D(d);
        }},
       {"CreateTexture2D",
        "Texture2D 4x4",
        {"USAGE_STAGING"},
        [&] {
          TEXTURE2D_DESC d = Tex(4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
          d.Usage = USAGE_STAGING;
          d.CPUAccessFlags = CPU_ACCESS_READ;
          device.CreateTexture2D(d);
        }},
       {"CreateBuffer",
        "BIND_UNORDERED_ACCESS",
        {"output"},
        [&] {
          BUFFER_DESC d = dyn;
          d.BindFlags = BIND_UNORDERED_ACCESS;
          device.CreateBuffer(d);
        }},
       {"UpdateSubresource", "per-frame constants", {"Map"}, [&] { ctx.UpdateSubresource(dynamic.get(), 0, nullptr, data.data(), 0, 0); }}});
}

SP_PROBE(kGroup, "SP_INITIAL_DATA_INVALID: missing or ill-sized initial data",
         "immutable resources without data, a row pitch shorter than a row, null pSysMem") {
  std::vector<uint8_t> data(256);
  return ExpectErrors(ErrorId::INITIAL_DATA_INVALID, {{"CreateBuffer",
                                                       "Buffer, 64 bytes",
                                                       {"USAGE_IMMUTABLE"},
                                                       [&] {
                                                         BUFFER_DESC d;
                                                         d.ByteWidth = 64;
                                                         d.Usage = USAGE_IMMUTABLE;
                                                         d.BindFlags = BIND_VERTEX_BUFFER;
                                                         device.CreateBuffer(d);
                                                       }},
                                                      {"CreateTexture2D",
                                                       "Texture2D 8x8",
                                                       {"SysMemPitch 16"},
                                                       [&] {
                                                         TEXTURE2D_DESC d = Tex(8, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
                                                         SUBRESOURCE_DATA init{data.data(), 16, 0};
                                                         device.CreateTexture2D(d, &init);
                                                       }},
                                                      {"CreateBuffer", "Buffer, 64 bytes", {"pSysMem is null"}, [&] {
                                                         BUFFER_DESC d;
                                                         d.ByteWidth = 64;
                                                         d.BindFlags = BIND_VERTEX_BUFFER;
                                                         SUBRESOURCE_DATA init{nullptr, 0, 0};
                                                         device.CreateBuffer(d, &init);
                                                       }}});
}

SP_PROBE(kGroup, "SP_VIEW_FORMAT_INCOMPATIBLE: a view format outside the resource's family",
         "views of other families, ambiguous TYPELESS views, wrong DSV formats, raw views of buffers without ALLOW_RAW_VIEWS") {
  Ref<Texture2D> depth = Named(gpu::MakeTexture2D(device, 4, 4, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE), "shadow map");
  Ref<Buffer> structured = Named(gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, nullptr, 64), "typed only");
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R16G16_FLOAT;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2D;
  sd.Texture2D = {0, 1};
  DEPTH_STENCIL_VIEW_DESC dd;
  dd.Format = FORMAT_D16_UNORM;
  dd.ViewDimension = DSV_DIMENSION_TEXTURE2D;
  SHADER_RESOURCE_VIEW_DESC raw;
  raw.Format = FORMAT_R32_TYPELESS;
  raw.ViewDimension = SRV_DIMENSION_BUFFEREX;
  raw.BufferEx = {0, 16, BUFFEREX_SRV_FLAG_RAW};
  Result r = ExpectErrors(
      ErrorId::VIEW_FORMAT_INCOMPATIBLE,
      {{"CreateShaderResourceView", "shadow map", {"R16G16_FLOAT"}, [&] { device.CreateShaderResourceView(depth.get(), &sd); }},
       {"CreateDepthStencilView", "shadow map", {"D32_FLOAT"}, [&] { device.CreateDepthStencilView(depth.get(), &dd); }},
       {"CreateShaderResourceView", "shadow map", {"TYPELESS"}, [&] { device.CreateShaderResourceView(depth.get()); }},
       {"CreateShaderResourceView", "typed only", {"ALLOW_RAW_VIEWS"}, [&] { device.CreateShaderResourceView(structured.get(), &raw); }}});
  // The family's valid pair (R32_FLOAT SRV, D32_FLOAT DSV) is accepted; a throw fails the probe.
  sd.Format = FORMAT_R32_FLOAT;
  dd.Format = FORMAT_D32_FLOAT;
  device.CreateShaderResourceView(depth.get(), &sd);
  device.CreateDepthStencilView(depth.get(), &dd);
  return r;
}

SP_PROBE(kGroup, "SP_VIEW_DIMENSION_INVALID: a view dimension that does not fit the resource",
         "3D or cube views of 2D textures, texture dimensions for buffers, MS views of single-sampled textures") {
  Ref<Texture2D> tex =
      Named(gpu::MakeTexture2D(device, 4, 4, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET, nullptr, 1, 6), "flat array");
  BufferViews buf = MakeStructured(device, 4, 4);
  buf.buffer->SetDebugName("items");
  SHADER_RESOURCE_VIEW_DESC s3;
  s3.Format = FORMAT_R8G8B8A8_UNORM;
  s3.ViewDimension = SRV_DIMENSION_TEXTURE3D;
  s3.Texture3D = {0, 1};
  SHADER_RESOURCE_VIEW_DESC cube;
  cube.Format = FORMAT_R8G8B8A8_UNORM;
  cube.ViewDimension = SRV_DIMENSION_TEXTURECUBE;
  cube.TextureCube = {0, 1};
  UNORDERED_ACCESS_VIEW_DESC u;
  u.Format = FORMAT_UNKNOWN;
  u.ViewDimension = UAV_DIMENSION_TEXTURE2D;
  RENDER_TARGET_VIEW_DESC ms;
  ms.Format = FORMAT_R8G8B8A8_UNORM;
  ms.ViewDimension = RTV_DIMENSION_TEXTURE2DMS;
  return ExpectErrors(
      ErrorId::VIEW_DIMENSION_INVALID,
      {{"CreateShaderResourceView", "flat array", {"Texture3D"}, [&] { device.CreateShaderResourceView(tex.get(), &s3); }},
       {"CreateShaderResourceView", "flat array", {"RESOURCE_MISC_TEXTURECUBE"}, [&] { device.CreateShaderResourceView(tex.get(), &cube); }},
       {"CreateUnorderedAccessView", "items", {"UAV_DIMENSION_BUFFER"}, [&] { device.CreateUnorderedAccessView(buf.buffer.get(), &u); }},
       {"CreateRenderTargetView", "flat array", {"multisampled"}, [&] { device.CreateRenderTargetView(tex.get(), &ms); }}});
}

SP_PROBE(kGroup, "SP_SUBRESOURCE_OUT_OF_RANGE: a mip, slice, element or box outside the resource",
         "view ranges, subresource indices, copy boxes, counter and argument offsets") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> tex = Named(gpu::MakeTexture2D(device, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE, nullptr, 2, 3), "array");
  Ref<Texture2D> dst = gpu::MakeTexture2D(device, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE);
  Ref<Buffer> args = Named(
      gpu::MakeBuffer(device, BIND_UNORDERED_ACCESS, nullptr, 16, RESOURCE_MISC_DRAWINDIRECT_ARGS | RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS), "args");
  BufferViews counted = MakeStructured(device, 4, 4, nullptr, BUFFER_UAV_FLAG_APPEND);
  SHADER_RESOURCE_VIEW_DESC sd;
  sd.Format = FORMAT_R8G8B8A8_UNORM;
  sd.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  sd.Texture2DArray = {0, 1, 2, 2};
  SHADER_RESOURCE_VIEW_DESC mip;
  mip.Format = FORMAT_R8G8B8A8_UNORM;
  mip.ViewDimension = SRV_DIMENSION_TEXTURE2DARRAY;
  mip.Texture2DArray = {2, 1, 0, 1};
  std::vector<uint8_t> data(64 * 4);
  BOX box{0, 0, 0, 9, 8, 1};
  return ExpectErrors(ErrorId::SUBRESOURCE_OUT_OF_RANGE,
                      {{"CreateShaderResourceView", "array", {"array slices"}, [&] { device.CreateShaderResourceView(tex.get(), &sd); }},
                       {"CreateShaderResourceView", "array", {"mip 2"}, [&] { device.CreateShaderResourceView(tex.get(), &mip); }},
                       {"UpdateSubresource", "array", {"subresource 6"}, [&] { ctx.UpdateSubresource(tex.get(), 6, nullptr, data.data(), 32, 0); }},
                       {"CopySubresourceRegion", "array", {"pSrcBox"}, [&] { ctx.CopySubresourceRegion(dst.get(), 0, 0, 0, 0, tex.get(), 0, &box); }},
                       {"CopyStructureCount", "args", {"DstAlignedByteOffset"}, [&] { ctx.CopyStructureCount(args.get(), 16, counted.uav.get()); }},
                       {"DrawInstancedIndirect", "args", {"exceed the buffer"}, [&] { ctx.DrawInstancedIndirect(args.get(), 4); }}});
}

SP_PROBE(kGroup, "SP_COPY_INVALID: a copy between incompatible resources",
         "different sizes or format families, immutable destinations, overlapping regions of one subresource") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Buffer> a = Named(gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, nullptr, 64), "64-byte buffer");
  Ref<Buffer> b = gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, nullptr, 128);
  std::vector<uint8_t> data(64);
  BUFFER_DESC id;
  id.ByteWidth = 64;
  id.Usage = USAGE_IMMUTABLE;
  id.BindFlags = BIND_VERTEX_BUFFER;
  SUBRESOURCE_DATA init{data.data(), 0, 0};
  Ref<Buffer> immutable = Named(device.CreateBuffer(id, &init), "immutable");
  Ref<Texture2D> rgba = Named(gpu::MakeTexture2D(device, 8, 8, FORMAT_R8G8B8A8_UNORM, BIND_SHADER_RESOURCE), "rgba");
  Ref<Texture2D> rf = gpu::MakeTexture2D(device, 8, 8, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE);
  BOX box{0, 0, 0, 4, 4, 1};
  return ExpectErrors(
      ErrorId::COPY_INVALID,
      {{"CopyResource", "64-byte buffer", {"differ in size"}, [&] { ctx.CopyResource(a.get(), b.get()); }},
       {"CopyResource", "immutable", {"USAGE_IMMUTABLE"}, [&] { ctx.CopyResource(immutable.get(), a.get()); }},
       {"CopyResource", "rgba", {"format family"}, [&] { ctx.CopyResource(rgba.get(), rf.get()); }},
       {"CopyResource", "rgba", {"same resource"}, [&] { ctx.CopyResource(rgba.get(), rgba.get()); }},
       {"CopySubresourceRegion", "rgba", {"overlap"}, [&] { ctx.CopySubresourceRegion(rgba.get(), 0, 2, 2, 0, rgba.get(), 0, &box); }}});
}

SP_PROBE(kGroup, "SP_MAP_INVALID: a map type the resource's usage does not allow",
         "WRITE_DISCARD on default resources, READ without CPU_ACCESS_READ, double maps, Unmap without Map") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Buffer> def = Named(gpu::MakeBuffer(device, BIND_VERTEX_BUFFER, nullptr, 64), "default vb");
  BUFFER_DESC sd;
  sd.ByteWidth = 64;
  sd.Usage = USAGE_STAGING;
  sd.CPUAccessFlags = CPU_ACCESS_WRITE;
  Ref<Buffer> upload = Named(device.CreateBuffer(sd), "upload");
  MAPPED_SUBRESOURCE m;
  return ExpectErrors(ErrorId::MAP_INVALID, {{"Map", "default vb", {"USAGE_DYNAMIC"}, [&] { ctx.Map(def.get(), 0, MAP_WRITE_DISCARD, 0, &m); }},
                                             {"Map", "upload", {"CPU_ACCESS_READ"}, [&] { ctx.Map(upload.get(), 0, MAP_READ, 0, &m); }},
                                             {"Map",
                                              "upload",
                                              {"already mapped"},
                                              [&] {
                                                ctx.Map(upload.get(), 0, MAP_WRITE, 0, &m);
                                                struct Unmap {
                                                  DeviceContext& c;
                                                  Buffer* b;
                                                  ~Unmap() { c.Unmap(b, 0); }
                                                } unmap{ctx, upload.get()};
                                                ctx.Map(upload.get(), 0, MAP_WRITE, 0, &m);
                                              }},
                                             {"Unmap", "default vb", {"not mapped"}, [&] { ctx.Unmap(def.get(), 0); }}});
}

SP_PROBE(kGroup, "SP_QUERY_INVALID: Begin/End/GetData used against the query's rules",
         "Begin on a TIMESTAMP, End without Begin, Begin twice, GetData with the wrong size or inside Begin/End") {
  DeviceContext& ctx = *device.GetImmediateContext();
  QUERY_DESC ts, oc;
  ts.Query = QUERY_TIMESTAMP;
  oc.Query = QUERY_OCCLUSION;
  Ref<Query> timestamp = device.CreateQuery(ts), occlusion = device.CreateQuery(oc), open = device.CreateQuery(oc);
  timestamp->SetDebugName("frame start");
  occlusion->SetDebugName("visibility");
  open->SetDebugName("open span");
  uint32_t small = 0;
  uint64_t big = 0;
  ctx.Begin(open.get());
  Result r = ExpectErrors(ErrorId::QUERY_INVALID,
                          {{"Begin", "frame start", {"only use End"}, [&] { ctx.Begin(timestamp.get()); }},
                           {"End", "visibility", {"End without Begin"}, [&] { ctx.End(occlusion.get()); }},
                           {"Begin", "open span", {"twice"}, [&] { ctx.Begin(open.get()); }},
                           {"GetData", "open span", {"between Begin and End"}, [&] { ctx.GetData(open.get(), &big, sizeof(big), 0); }},
                           {"GetData", "frame start", {"DataSize 4"}, [&] { ctx.GetData(timestamp.get(), &small, sizeof(small), 0); }}});
  ctx.End(open.get());
  return r;
}

}  // namespace sp::conformance
