// Texture2DArray and TextureCube depth textures with comparison sampling, and seamless bilinear
// filtering of cube maps across face edges.
// - Arrays: the array coordinate selects slice clamp(round(z), 0, size - 1); a view's
//   FirstArraySlice offsets it.
// - Cubes: faces are array slices +X, -X, +Y, -Y, +Z, -Z; a direction picks the face of its
//   largest component and (u, v) = ((sc / |ma| + 1) / 2, (tc / |ma| + 1) / 2) with D3D's table
//   (+X: sc = -z, tc = -y; -X: z, -y; +Y: x, z; -Y: x, -z; +Z: x, -y; -Z: -x, -y), v = 0 at the
//   face's first row.
// - SampleCmp compares `reference <= texel` (LESS_EQUAL) per texel, then filters the 0/1 results.
// - Cube filtering is seamless: a bilinear footprint crossing an edge takes texels of the
//   neighbouring face.
// Coordinates are texel centres or 1/4 texel from them and directions have a major component of
// exactly 1, so D3D11's 8-bit filter-weight fractions are exact and every expectation is exact up
// to float32 rounding of the weighted sum (tolerance 2^-20 abs, values in [0, 1] or small
// integers); point comparisons are 0 or 1 exactly (tolerance 0).
#include <algorithm>
#include <cmath>

#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Resources";

// A query: coordinate (u, v, layer) or direction (x, y, z), and the reference.
using Query = std::array<float, 4>;

const char* kArrayShaders = R"(
Texture2DArray<float> tex : register(t0);
StructuredBuffer<float4> queries : register(t1);
SamplerComparisonState cmpPoint : register(s0);
SamplerComparisonState cmpLinear : register(s1);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  float4 q = queries[i.x];
  output[i.x] = float4(tex.SampleCmpLevelZero(cmpPoint, q.xyz, q.w), tex.SampleCmpLevelZero(cmpLinear, q.xyz, q.w), 0, 0);
}
float4 VSFull(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}
float4 PSCmp(float4 p : SV_Position) : SV_Target {
  float4 q = queries[uint(p.y) * 64 + uint(p.x)];
  return float4(tex.SampleCmp(cmpPoint, q.xyz, q.w), tex.SampleCmp(cmpLinear, q.xyz, q.w), 0, 0);
}
)";

// Runs the queries through SampleCmpLevelZero in a compute shader and SampleCmp in a pixel shader
// (`source` with TEX declared as the texture type); returns (point, linear) per query and path.
struct CmpResults {
  std::vector<std::array<float, 4>> compute, pixel;
};
CmpResults RunQueries(Device& device, const std::string& source, const std::string& name, ShaderResourceView* srv, std::vector<Query> queries) {
  DeviceContext& ctx = *device.GetImmediateContext();
  uint32_t n = uint32_t((queries.size() + 63) / 64 * 64);
  queries.resize(n, Query{0.5f, 0.5f, 0.5f, 0});
  Ref<Buffer> qb = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, queries.data(), n * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<ShaderResourceView> qsrv = device.CreateShaderResourceView(qb.get());
  Ref<SamplerState> pt = MakeSampler(device, FILTER_COMPARISON_MIN_MAG_MIP_POINT, TEXTURE_ADDRESS_CLAMP, COMPARISON_LESS_EQUAL);
  Ref<SamplerState> lin = MakeSampler(device, FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT, TEXTURE_ADDRESS_CLAMP, COMPARISON_LESS_EQUAL);
  CmpResults r;
  r.compute = RunCompute(device, source, name, n, {srv, qsrv.get()}, {pt.get(), lin.get()}, n / 64);

  Ref<Texture2D> target = gpu::MakeTexture2D(device, 64, n / 64, FORMAT_R32G32B32A32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  Ref<VertexShader> vs = device.CreateVertexShader(gpu::CompileInline(source, name, "vs_5_0", "VSFull"));
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(source, name, "ps_5_0", "PSCmp"));
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, 64, float(n / 64), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.IASetInputLayout(nullptr);
  ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
  ctx.VSSetShader(vs.get());
  ctx.PSSetShader(ps.get());
  ctx.PSSetShaderResources(0, {srv, qsrv.get()});
  ctx.PSSetSamplers(0, {pt.get(), lin.get()});
  ctx.Draw(3, 0);
  std::vector<float> px = gpu::ReadAs<float>(gpu::ReadTexture(device, ctx, target.get()));
  for (uint32_t i = 0; i < n; ++i) r.pixel.push_back({px[i * 4], px[i * 4 + 1], 0, 0});
  return r;
}

// 2D texel lookup with CLAMP addressing on one S x S slice.
struct Slice {
  uint32_t size;
  const float* texels;
  float at(int x, int y) const { return texels[std::clamp(y, 0, int(size) - 1) * size + std::clamp(x, 0, int(size) - 1)]; }
  double Point(double u, double v, float ref) const {
    return ref <= at(int(std::floor(u * size)), int(std::floor(v * size))) ? 1.0 : 0.0;
  }
  double Linear(double u, double v, float ref) const {
    double x = u * size - 0.5, y = v * size - 0.5;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    double fx = x - x0, fy = y - y0;
    auto c = [&](int xi, int yi) { return ref <= at(xi, yi) ? 1.0 : 0.0; };
    return (1 - fy) * ((1 - fx) * c(x0, y0) + fx * c(x0 + 1, y0)) + fy * ((1 - fx) * c(x0, y0 + 1) + fx * c(x0 + 1, y0 + 1));
  }
};

Result Compare(const CmpResults& got, const std::vector<std::array<double, 2>>& expected, const std::vector<Query>& queries) {
  double worstPoint = 0, worstLinear = 0;
  std::string detail;
  for (size_t i = 0; i < expected.size(); ++i)
    for (const auto* path : {&got.compute, &got.pixel}) {
      double ep = std::abs((*path)[i][0] - expected[i][0]), el = std::abs((*path)[i][1] - expected[i][1]);
      if (ep > worstPoint || el > worstLinear) {
        detail = std::string(path == &got.compute ? "SampleCmpLevelZero" : "SampleCmp") + " at (" + std::to_string(queries[i][0]) + ", " +
                 std::to_string(queries[i][1]) + ", " + std::to_string(queries[i][2]) + ") ref " + std::to_string(queries[i][3]) + ": point " +
                 std::to_string((*path)[i][0]) + " linear " + std::to_string((*path)[i][1]) + ", D3D11 " + std::to_string(expected[i][0]) + " / " +
                 std::to_string(expected[i][1]);
      }
      worstPoint = std::max(worstPoint, ep);
      worstLinear = std::max(worstLinear, el);
    }
  if (worstPoint > 0) return Fail("point comparison differs: " + detail, worstPoint, "abs", 0);
  return Within(worstLinear, std::ldexp(1.0, -20), "abs", "filtered comparison: " + detail);
}

// Face `f`, face coordinates (sc, tc) in [-1, 1] -> direction with a major component of +-1.
std::array<double, 3> CubeDirection(int f, double sc, double tc) {
  switch (f) {
    case 0: return {1, -tc, -sc};
    case 1: return {-1, -tc, sc};
    case 2: return {sc, 1, tc};
    case 3: return {sc, -1, -tc};
    case 4: return {sc, -tc, 1};
    default: return {-sc, -tc, -1};
  }
}

// D3D's face selection and face coordinates for a direction (no ties between components here).
void CubeFace(std::array<double, 3> d, int* face, double* u, double* v) {
  double ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
  double sc, tc, ma;
  if (ax >= ay && ax >= az) {
    *face = d[0] > 0 ? 0 : 1;
    ma = ax;
    sc = d[0] > 0 ? -d[2] : d[2];
    tc = -d[1];
  } else if (ay >= az) {
    *face = d[1] > 0 ? 2 : 3;
    ma = ay;
    sc = d[0];
    tc = d[1] > 0 ? d[2] : -d[2];
  } else {
    *face = d[2] > 0 ? 4 : 5;
    ma = az;
    sc = d[2] > 0 ? d[0] : -d[0];
    tc = -d[1];
  }
  *u = (sc / ma + 1) / 2;
  *v = (tc / ma + 1) / 2;
}

// The texel of an S x S cube containing the point of face `f` at (sc, tc), where one coordinate may
// lie up to one texel beyond the face: that point is folded over the edge onto the neighbouring face.
float CubeTexel(const std::vector<float>& faces, uint32_t S, int f, double sc, double tc) {
  std::array<double, 3> d = CubeDirection(f, sc, tc);
  for (int a = 0; a < 3; ++a) {
    double over = std::abs(d[a]) - 1;
    if (over <= 0) continue;
    for (int m = 0; m < 3; ++m)
      if (m != a && std::abs(d[m]) == 1) d[m] = (d[m] > 0 ? 1 : -1) * (1 - over);
    d[a] = d[a] > 0 ? 1 : -1;
  }
  int face;
  double u, v;
  CubeFace(d, &face, &u, &v);
  int x = std::clamp(int(std::floor(u * S)), 0, int(S) - 1), y = std::clamp(int(std::floor(v * S)), 0, int(S) - 1);
  return faces[(face * S + y) * S + x];
}

Ref<Texture2D> MakeDepthArray(Device& device, uint32_t S, uint32_t slices, bool cube, const std::vector<float>& texels) {
  Ref<Texture2D> tex = gpu::MakeTexture2D(device, S, S, FORMAT_R32_TYPELESS, BIND_DEPTH_STENCIL | BIND_SHADER_RESOURCE, nullptr, 1, slices, 1,
                                          cube ? uint32_t(RESOURCE_MISC_TEXTURECUBE) : 0u);
  for (uint32_t s = 0; s < slices; ++s) UploadThroughStaging(device, tex.get(), s, texels.data() + size_t(s) * S * S);
  return tex;
}

}  // namespace

SP_PROBE(kGroup, "Texture2DArray: SampleCmp and SampleCmpLevelZero per slice",
         "a D32 depth array read through an R32_FLOAT Texture2DArray view compares reference <= texel in slice clamp(round(z))") {
  const uint32_t S = 8, N = 4;
  std::vector<float> texels(S * S * N);
  for (uint32_t i = 0; i < texels.size(); ++i) texels[i] = float((i * 37 % 61) + 1) / 64.0f;
  Ref<Texture2D> tex = MakeDepthArray(device, S, N, false, texels);
  Ref<ShaderResourceView> all = MakeSrv(device, tex.get(), FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2DARRAY, 0, N);
  Ref<ShaderResourceView> upper = MakeSrv(device, tex.get(), FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURE2DARRAY, 2, 2);
  for (auto [srv, first, count] : {std::tuple{all.get(), 0u, N}, std::tuple{upper.get(), 2u, 2u}}) {
    std::vector<Query> queries;
    std::vector<std::array<double, 2>> expected;
    for (uint32_t s = 0; s < count; ++s)
      for (double dz : {0.0, 0.3, -0.3})
        for (uint32_t y = 0; y < S; y += 3)
          for (uint32_t x = 0; x < S; ++x)
            for (double du : {0.0, 0.25, -0.25}) {
              double u = (x + 0.5 + du) / S, v = (y + 0.5 - du) / S;
              float layer = float(s + dz);
              uint32_t slice = first + uint32_t(std::clamp(std::lround(layer), 0L, long(count) - 1));
              Slice sl{S, texels.data() + size_t(slice) * S * S};
              float texel = sl.at(int(std::floor(u * S)), int(std::floor(v * S)));
              float ref = texel + ((x + y + s) % 2 ? 1.0f : -1.0f) / 512;
              queries.push_back({float(u), float(v), layer, ref});
              expected.push_back({sl.Point(u, v, ref), sl.Linear(u, v, ref)});
            }
    // Layers beyond the view clamp to its first and last slice.
    for (float layer : {-1.7f, float(count) + 0.8f}) {
      uint32_t slice = first + (layer < 0 ? 0 : count - 1);
      Slice sl{S, texels.data() + size_t(slice) * S * S};
      float ref = sl.at(3, 4) - 1.0f / 512;
      queries.push_back({3.5f / S, 4.5f / S, layer, ref});
      expected.push_back({sl.Point(3.5 / S, 4.5 / S, ref), sl.Linear(3.5 / S, 4.5 / S, ref)});
    }
    std::string src = kArrayShaders;
    Result r = Compare(RunQueries(device, src, "conformance/array-cmp.hlsl", srv, queries), expected, queries);
    if (r.status != Status::Pass) {
      r.detail = "view of slices " + std::to_string(first) + ".." + std::to_string(first + count - 1) + ": " + r.detail;
      return r;
    }
  }
  return Pass(0, "abs", std::ldexp(1.0, -20));
}

SP_PROBE(kGroup, "TextureCube: SampleCmp and SampleCmpLevelZero per face",
         "a D32 cube read through an R32_FLOAT TextureCube view finds each face (+X, -X, +Y, -Y, +Z, -Z) and texel by D3D's face table") {
  const uint32_t S = 4;
  std::vector<float> texels(S * S * 6);
  for (uint32_t i = 0; i < texels.size(); ++i) texels[i] = float((i * 29 % 97) + 1) / 128.0f;
  Ref<Texture2D> tex = MakeDepthArray(device, S, 6, true, texels);
  Ref<ShaderResourceView> srv = MakeSrv(device, tex.get(), FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURECUBE);
  std::vector<Query> queries;
  std::vector<std::array<double, 2>> expected;
  for (int f = 0; f < 6; ++f) {
    Slice sl{S, texels.data() + size_t(f) * S * S};
    for (uint32_t y = 0; y < S; ++y)
      for (uint32_t x = 0; x < S; ++x)
        for (float sign : {1.0f, -1.0f}) {
          // Texel centres for the point comparison; inner texels also 1/4 texel off for the
          // bilinear comparison (its footprint stays on the face).
          bool inner = x > 0 && x < S - 1 && y > 0 && y < S - 1;
          double du = inner && sign < 0 ? 0.25 : 0.0, dv = inner && sign < 0 ? -0.25 : 0.0;
          double u = (x + 0.5 + du) / S, v = (y + 0.5 + dv) / S;
          std::array<double, 3> d = CubeDirection(f, u * 2 - 1, v * 2 - 1);
          float ref = sl.at(int(x), int(y)) + sign / 512;
          queries.push_back({float(d[0]), float(d[1]), float(d[2]), ref});
          expected.push_back({sl.Point(u, v, ref), inner ? sl.Linear(u, v, ref) : -1.0});
        }
  }
  std::string src = kArrayShaders;
  src.replace(src.find("Texture2DArray<float>"), std::string("Texture2DArray<float>").size(), "TextureCube<float>");
  CmpResults got = RunQueries(device, src, "conformance/cube-cmp.hlsl", srv.get(), queries);
  // Edge texels' bilinear footprints cross faces; only the point result is checked there.
  for (size_t i = 0; i < expected.size(); ++i)
    if (expected[i][1] < 0) expected[i][1] = got.compute[i][1] = got.pixel[i][1] = 0;
  return Compare(got, expected, queries);
}

SP_PROBE(kGroup, "TextureCube: seamless bilinear filtering across face edges",
         "Sample and SampleLevel 1/4 texel from a face edge blend 3/4 of the edge texel with 1/4 of the texel across the edge on the neighbouring face") {
  const uint32_t S = 4;
  std::vector<float> texels(S * S * 6);
  for (uint32_t i = 0; i < texels.size(); ++i) texels[i] = float(i);
  Ref<Texture2D> tex = gpu::MakeTexture2D(device, S, S, FORMAT_R32_FLOAT, BIND_SHADER_RESOURCE, nullptr, 1, 6, 1, RESOURCE_MISC_TEXTURECUBE);
  for (uint32_t f = 0; f < 6; ++f) device.GetImmediateContext()->UpdateSubresource(tex.get(), f, nullptr, texels.data() + f * S * S, S * 4, 0);
  Ref<ShaderResourceView> srv = MakeSrv(device, tex.get(), FORMAT_R32_FLOAT, SRV_DIMENSION_TEXTURECUBE);
  Ref<SamplerState> linear = MakeSampler(device, FILTER_MIN_MAG_MIP_LINEAR);
  std::vector<Query> queries;
  std::vector<double> expected;
  const double q = 0.5 / S;  // a quarter texel in face coordinates (a texel spans 2 / S)
  for (int f = 0; f < 6; ++f)
    for (int edge = 0; edge < 4; ++edge)
      for (uint32_t k : {1u, 2u}) {
        double along = (k + 0.5) / S * 2 - 1;  // a texel centre along the edge (no corner texels)
        double across = edge % 2 ? 1 - q : -1 + q;
        double sc = edge < 2 ? across : along, tc = edge < 2 ? along : across;
        double step = 2.0 / S * (across > 0 ? 1 : -1);
        double scIn = edge < 2 ? sc - step / 4 : sc, tcIn = edge < 2 ? tc : tc - step / 4;      // edge texel centre
        double scOut = edge < 2 ? sc + 3 * step / 4 : sc, tcOut = edge < 2 ? tc : tc + 3 * step / 4;  // across the edge
        std::array<double, 3> d = CubeDirection(f, sc, tc);
        queries.push_back({float(d[0]), float(d[1]), float(d[2]), 0});
        expected.push_back(0.75 * CubeTexel(texels, S, f, scIn, tcIn) + 0.25 * CubeTexel(texels, S, f, scOut, tcOut));
      }
  uint32_t n = uint32_t(queries.size());
  Ref<Buffer> qb = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, queries.data(), n * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<ShaderResourceView> qsrv = device.CreateShaderResourceView(qb.get());
  const char* cs = R"(
TextureCube<float> cube : register(t0);
StructuredBuffer<float4> queries : register(t1);
SamplerState smp : register(s0);
RWStructuredBuffer<float4> output : register(u0);
[numthreads(48, 1, 1)] void main(uint3 i : SV_DispatchThreadID) { output[i.x] = float4(cube.SampleLevel(smp, queries[i.x].xyz, 0), 0, 0, 0); }
)";
  std::vector<std::array<float, 4>> got = RunCompute(device, cs, "conformance/cube-seamless.hlsl", n, {srv.get(), qsrv.get()}, {linear.get()});
  // The same queries through Sample in a pixel shader, one pixel each (one mip: the derivatives
  // only pick the minification filter, which is the same linear filter).
  const char* ps = R"(
TextureCube<float> cube : register(t0);
StructuredBuffer<float4> queries : register(t1);
SamplerState smp : register(s0);
float4 main(float4 p : SV_Position) : SV_Target { return float4(cube.Sample(smp, queries[uint(p.x)].xyz), 0, 0, 0); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  Ref<Texture2D> target = gpu::MakeTexture2D(device, n, 1, FORMAT_R32_FLOAT, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  Ref<PixelShader> sampler = device.CreatePixelShader(gpu::CompileInline(ps, "conformance/cube-seamless-ps.hlsl", "ps_5_0", "main"));
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, float(n), 1, 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(sampler.get());
  ctx.PSSetShaderResources(0, {srv.get(), qsrv.get()});
  ctx.PSSetSamplers(0, {linear.get()});
  PixelDrawer(device).Draw(ctx, {{0, 0}, {2.0 * n, 0}, {0, 2.0}}, n, 1);
  std::vector<float> sampled = gpu::ReadAs<float>(gpu::ReadTexture(device, ctx, target.get()));
  double worst = 0;
  std::string detail;
  for (uint32_t i = 0; i < n; ++i)
    for (int path = 0; path < 2; ++path) {
      float v = path ? sampled[i] : got[i][0];
      double e = std::abs(v - expected[i]);
      if (e > worst) {
        worst = e;
        detail = std::string(path ? "Sample" : "SampleLevel") + " face " + std::to_string(i / 8) + " edge " + std::to_string(i / 2 % 4) +
                 ": got " + std::to_string(v) + ", D3D11 " + std::to_string(expected[i]) + " (texel values are their index, face-major)";
      }
    }
  // Values up to 95 with weights 3/4 and 1/4: exact in float32 but for the last bits of the sum.
  return Within(worst, 95 * std::ldexp(1.0, -20), "abs", detail);
}

}  // namespace sp::conformance
