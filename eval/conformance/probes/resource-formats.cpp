// The formats shadow code uses, in both directions, against D3D11's data conversion rules
// (functional spec 3.2):
// - upload: known texel bits as initial data, read with Load and a point Sample in a compute
//   shader. FLOAT32 and FLOAT16 -> FLOAT32 are exact; UNORM -> FLOAT is code / (2^n - 1),
//   correctly rounded (3.2.3.2: conversions between integer and float must be exact); SRGB ->
//   FLOAT within 0.5 ULP on the sRGB side, measured by re-encoding the result without rounding
//   (3.2.3.7), 0 and 1 exact; UINT exact. Missing channels read 0, and 1 in alpha.
// - render: a pixel shader writes known floats (uints for R32_UINT) into a render target read
//   through staging. FLOAT32 exact; values exactly representable in float16 exact; FLOAT ->
//   UNORM and FLOAT -> SRGB within 0.6 LSB of the ideal scaled value after clamping to [0, 1]
//   (3.2.3.6, 3.2.3.8); UINT exact.
// Rounding of float32 -> float16 and special values are separate probes (formats-special).
// Mesa 22.3's llvmpipe/lavapipe return UNORM texels 1 ulp away from the correctly rounded
// code / (2^n - 1) for about half the 8-bit codes and a few hundred 16-bit ones (as a multiply by
// the float reciprocal does): a driver deviation from 3.2.3.2, reported as such (1 ulp at most;
// more fails).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "render-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Resources";
constexpr uint32_t W = 8, H = 8, N = W * H;

enum class Kind { Float32, Float16, Unorm, Srgb, Uint };

struct FormatCase {
  FORMAT format;
  Kind kind;
  uint32_t channels;
  uint32_t bits;  // per channel
};

const char* kReadCS = R"(
#ifdef UINT_TEXELS
Texture2D<uint4> tex : register(t0);
#else
Texture2D<float4> tex : register(t0);
SamplerState pt : register(s0);
#endif
RWStructuredBuffer<float4> output : register(u0);
[numthreads(64, 1, 1)] void main(uint3 i : SV_DispatchThreadID) {
  int3 p = int3(i.x % 8, i.x / 8, 0);
#ifdef UINT_TEXELS
  output[i.x * 2] = asfloat(tex.Load(p));
  output[i.x * 2 + 1] = asfloat(tex.Load(p));
#else
  output[i.x * 2] = tex.Load(p);
  output[i.x * 2 + 1] = tex.SampleLevel(pt, (float2(p.xy) + 0.5) / 8, 0);
#endif
}
)";

const char* kWritePS = R"(
#ifdef UINT_TEXELS
StructuredBuffer<uint4> values : register(t0);
uint4 main(float4 p : SV_Position) : SV_Target { return values[uint(p.y) * 8 + uint(p.x)]; }
#else
StructuredBuffer<float4> values : register(t0);
float4 main(float4 p : SV_Position) : SV_Target { return values[uint(p.y) * 8 + uint(p.x)]; }
#endif
)";

// One measured quantity of a probe: error, tolerance and unit, and where the worst error was.
struct Measure {
  std::string what, unit;
  double tol = 0, err = 0;
  double knownBound = 0;  // a documented driver deviation up to this error is reported, not failed
  std::string detail;
  int count = 0, over = 0;
  void Add(double e, const std::string& where) {
    ++count;
    over += e > tol;
    if (e > err || (detail.empty() && e >= err)) {
      err = e;
      detail = where;
    }
  }
};

// Fails with every measure that exceeds its tolerance (so one deviation does not hide the others);
// passes with the measure closest to its tolerance.
Result Conclude(const std::vector<Measure>& ms) {
  const Measure* shown = nullptr;
  const Measure* deviation = nullptr;
  std::string failures;
  for (const Measure& m : ms) {
    if (m.err > m.tol && m.err <= m.knownBound) {
      if (!deviation || m.err > deviation->err) deviation = &m;
      continue;
    }
    if (m.err > m.tol) {
      failures += (failures.empty() ? "" : "; ") + m.what + ": " + std::to_string(m.over) + " of " + std::to_string(m.count) + " values off, worst " +
                  m.detail + ": error " + std::to_string(m.err) + " " + m.unit + " exceeds " + std::to_string(m.tol);
      if (!shown || shown->err <= shown->tol) shown = &m;
      continue;
    }
    if (!shown || (shown->err <= shown->tol && (m.tol > 0 && shown->tol > 0 ? m.err / m.tol > shown->err / shown->tol : m.err > shown->err))) shown = &m;
  }
  if (!failures.empty()) return Fail(failures, shown->err, shown->unit, shown->tol);
  if (deviation)
    return WithinKnownDeviation(deviation->err, deviation->tol, deviation->knownBound, deviation->unit,
                                deviation->what + ", " + std::to_string(deviation->over) + " of " + std::to_string(deviation->count) + " values, worst " + deviation->detail,
                                kUnormReadDeviation);
  if (!shown) return Pass();
  return Pass(shown->err, shown->unit, shown->tol, shown->what);
}

uint32_t BytesPerChannel(const FormatCase& f) { return f.bits / 8; }

// The k-th 16-bit code whose quotient code / 65535 a multiplication by the float reciprocal of 65535
// does not round correctly: the cases that tell an exact UNORM -> FLOAT from a cheaper one.
uint32_t HardUnorm16(uint32_t k) {
  static const std::vector<uint32_t> codes = [] {
    std::vector<uint32_t> v;
    volatile float r = 1.0f / 65535.0f;
    for (uint32_t c = 0; c < 65536; c += 7)
      if (float(c) * r != float(c) / 65535.0f) v.push_back(c);
    return v;
  }();
  return codes[k * 3 % codes.size()];
}

// Texel codes for the upload direction: per texel and channel, spread over the format's range.
uint32_t UploadCode(const FormatCase& f, uint32_t texel, uint32_t c) {
  uint32_t i = texel * f.channels + c;  // distinct index per channel value
  switch (f.kind) {
    case Kind::Unorm:
    case Kind::Srgb:
      if (f.bits == 8) return (i * 97 + 3) % 256;  // 256 values of 4 channels: every code once
      return i == 0 ? 0 : i == 1 ? 65535 : i == 2 ? 1 : i == 3 ? 65534 : HardUnorm16(i - 4);
    case Kind::Float16: {
      // Normal, denormal, zero, largest finite, infinity and negative halves.
      static const uint16_t special[] = {0x0000, 0x8000, 0x0001, 0x03ff, 0x0400, 0x7bff, 0xfbff, 0x7c00, 0xfc00, 0x3c00, 0x3555, 0xc248};
      if (i < std::size(special)) return special[i];
      return (i * 2654435761u >> 16) % 0x7c00u | (i % 2 ? 0x8000u : 0u);  // finite values of both signs
    }
    case Kind::Float32: {
      float v = std::ldexp(float((i * 2654435761u) % 1000003u) / 1000003.0f + 0.5f, int(i % 40) - 20) * (i % 3 ? 1.0f : -1.0f);
      uint32_t b;
      std::memcpy(&b, &v, 4);
      return b;
    }
    case Kind::Uint: return i * 2654435761u;
  }
  return 0;
}

// What D3D11 returns in a shader for a code, as a float (uints as their bits).
float Decode(const FormatCase& f, uint32_t code, uint32_t c) {
  switch (f.kind) {
    case Kind::Unorm: return UnormToFloat(code, f.bits);
    case Kind::Srgb: return c == 3 ? UnormToFloat(code, 8) : float(SrgbDecode(code));
    case Kind::Float16: return HalfToFloat(uint16_t(code));
    case Kind::Float32:
    case Kind::Uint: {
      float v;
      std::memcpy(&v, &code, 4);
      return v;
    }
  }
  return 0;
}

Result CheckFormat(Device& device, const FormatCase& f) {
  DeviceContext& ctx = *device.GetImmediateContext();
  uint32_t support = device.CheckFormatSupport(f.format);
  if (!(support & FORMAT_SUPPORT_RENDER_TARGET) || !(support & FORMAT_SUPPORT_SHADER_LOAD))
    return Unsupported(std::string(FormatName(f.format)) + " is not a render target / loadable format here");
  const bool isUint = f.kind == Kind::Uint;
  std::string prefix = isUint ? "#define UINT_TEXELS 1\n" : "";
  const uint32_t texelBytes = f.channels * BytesPerChannel(f);

  // Upload -> Load / Sample.
  std::vector<uint8_t> texels(N * texelBytes);
  for (uint32_t t = 0; t < N; ++t)
    for (uint32_t c = 0; c < f.channels; ++c) {
      uint32_t code = UploadCode(f, t, c);
      std::memcpy(&texels[t * texelBytes + c * BytesPerChannel(f)], &code, BytesPerChannel(f));
    }
  Ref<Texture2D> src = gpu::MakeTexture2D(device, W, H, f.format, BIND_SHADER_RESOURCE, texels.data());
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(src.get());
  Ref<SamplerState> pt = MakeSampler(device, FILTER_MIN_MAG_MIP_POINT);
  std::vector<std::array<float, 4>> r = RunCompute(device, prefix + kReadCS, "conformance/format-read.hlsl", N * 2, {srv.get()},
                                                   isUint ? std::vector<SamplerState*>{} : std::vector<SamplerState*>{pt.get()});
  Measure read{"Load/Sample of uploaded texels", f.kind == Kind::Srgb ? "sRGB ULP" : "ulp", f.kind == Kind::Srgb ? 0.5 : 0.0};
  Measure alpha{"Load/Sample of the linear alpha channel", "ulp", 0.0};
  if (f.kind == Kind::Unorm) read.knownBound = 1.0;
  alpha.knownBound = 1.0;
  Measure defaults{"channels the format lacks (0, 0, 1)", "abs", 0};
  for (uint32_t t = 0; t < N; ++t)
    for (uint32_t path = 0; path < 2; ++path)
      for (uint32_t c = 0; c < 4; ++c) {
        float got = r[t * 2 + path][c];
        std::string where = std::string(path ? "Sample" : "Load") + " texel " + std::to_string(t) + " channel " + std::to_string(c);
        if (c >= f.channels) {
          float one = 1.0f;
          if (isUint) {
            uint32_t u = 1;
            std::memcpy(&one, &u, 4);
          }
          float want = c == 3 ? one : 0.0f;
          defaults.Add(std::memcmp(&got, &want, 4) ? 1.0 : 0.0, where + ": " + std::to_string(got));
          continue;
        }
        uint32_t code = UploadCode(f, t, c);
        float want = Decode(f, code, c);
        double e;
        if (f.kind == Kind::Srgb && c < 3)
          e = (code == 0 || code == 255) ? (got == (code ? 1.0f : 0.0f) ? 0 : 1e9) : std::abs(SrgbEncodeScaled(got) - code);
        else if (f.kind == Kind::Float32 || f.kind == Kind::Uint)
          e = std::memcmp(&got, &want, 4) ? 1e9 : 0;
        else if (std::isinf(want))
          e = got == want ? 0 : 1e9;
        else
          e = std::abs(double(got) - want) / (want == 0 ? std::ldexp(1.0, -149) : FloatUlp(std::abs(want)));
        (f.kind == Kind::Srgb && c == 3 ? alpha : read).Add(e, where + ": code " + std::to_string(code) + " read " + std::to_string(got) + ", D3D11 " +
                                                                   std::to_string(want));
      }

  // Render -> staging.
  std::vector<std::array<float, 4>> values(N);
  for (uint32_t t = 0; t < N; ++t)
    for (uint32_t c = 0; c < 4; ++c) {
      uint32_t i = t * 4 + c;
      float v = 0;
      switch (f.kind) {
        case Kind::Unorm:
        case Kind::Srgb: {
          // In-range values, exact code/(2^n - 1) values, half-way points and values outside [0, 1].
          const float fixed[] = {0.0f, 1.0f, 0.5f, 1.0f / 3, 2.0f / 3, -0.5f, 1.5f, 0.0031308f, 0.04045f, 1e-6f, 0.999999f, 1e-30f};
          v = i < std::size(fixed) ? fixed[i] : float((i * 2654435761u) % 100003u) / 100003.0f;
          break;
        }
        case Kind::Float16: v = HalfToFloat(uint16_t((i * 2654435761u >> 16) % 0x7c00u | (i % 2 ? 0x8000u : 0u))); break;
        case Kind::Float32: {
          uint32_t b = UploadCode(f, t, c);
          std::memcpy(&v, &b, 4);
          break;
        }
        case Kind::Uint: {
          uint32_t b = i * 2246822519u + 7;
          std::memcpy(&v, &b, 4);
          break;
        }
      }
      values[t][c] = v;
    }
  Ref<Buffer> vb = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, values.data(), N * 16, RESOURCE_MISC_BUFFER_STRUCTURED, 16);
  Ref<ShaderResourceView> vsrv = device.CreateShaderResourceView(vb.get());
  Ref<PixelShader> ps = device.CreatePixelShader(gpu::CompileInline(prefix + kWritePS, "conformance/format-write.hlsl", "ps_5_0", "main"));
  Ref<Texture2D> target = gpu::MakeTexture2D(device, W, H, f.format, BIND_RENDER_TARGET);
  Ref<RenderTargetView> rtv = device.CreateRenderTargetView(target.get());
  RenderTargetView* rtvs[] = {rtv.get()};
  ctx.OMSetRenderTargets(1, rtvs, nullptr);
  VIEWPORT vp{0, 0, float(W), float(H), 0, 1};
  ctx.RSSetViewports(1, &vp);
  ctx.PSSetShader(ps.get());
  ctx.PSSetShaderResources(0, {vsrv.get()});
  PixelDrawer(device).Draw(ctx, {{0, 0}, {2.0 * W, 0}, {0, 2.0 * H}}, W, H);
  std::vector<uint8_t> raw = gpu::ReadTexture(device, ctx, target.get());
  Measure write{"render-target write", f.kind == Kind::Unorm || f.kind == Kind::Srgb ? "LSB" : "ulp",
                f.kind == Kind::Unorm || f.kind == Kind::Srgb ? 0.6 : 0.0};
  for (uint32_t t = 0; t < N; ++t)
    for (uint32_t c = 0; c < f.channels; ++c) {
      uint32_t code = 0;
      std::memcpy(&code, &raw[t * texelBytes + c * BytesPerChannel(f)], BytesPerChannel(f));
      float v = values[t][c];
      double e;
      std::string want;
      if (f.kind == Kind::Unorm || (f.kind == Kind::Srgb && c == 3)) {
        double ideal = UnormScaled(v, f.bits);
        e = std::abs(code - ideal);
        want = std::to_string(ideal);
      } else if (f.kind == Kind::Srgb) {
        double ideal = SrgbEncodeScaled(v);
        e = std::abs(code - ideal);
        want = std::to_string(ideal);
      } else if (f.kind == Kind::Float16) {
        uint16_t h = FloatToHalfRtz(v);
        e = code == h ? 0 : 1e9;
        want = std::to_string(h);
      } else {
        uint32_t b;
        std::memcpy(&b, &v, 4);
        e = code == b ? 0 : 1e9;
        want = std::to_string(b);
      }
      write.Add(e, "texel " + std::to_string(t) + " channel " + std::to_string(c) + ": wrote " + std::to_string(v) + ", stored " + std::to_string(code) +
                       ", D3D11 " + want);
    }
  std::vector<Measure> all = {read, defaults, write};
  if (f.kind == Kind::Srgb) all.push_back(alpha);
  return Conclude(all);
}

}  // namespace

SP_PROBE(kGroup, "format R32_FLOAT: upload/Load/Sample and render/staging", "float32 texels read and write bit-exactly; missing channels read (0, 0, 1)") {
  return CheckFormat(device, {FORMAT_R32_FLOAT, Kind::Float32, 1, 32});
}
SP_PROBE(kGroup, "format R32G32_FLOAT: upload/Load/Sample and render/staging", "float32 texels read and write bit-exactly; missing channels read (0, 1)") {
  return CheckFormat(device, {FORMAT_R32G32_FLOAT, Kind::Float32, 2, 32});
}
SP_PROBE(kGroup, "format R32G32B32A32_FLOAT: upload/Load/Sample and render/staging", "float32 texels read and write bit-exactly") {
  return CheckFormat(device, {FORMAT_R32G32B32A32_FLOAT, Kind::Float32, 4, 32});
}
SP_PROBE(kGroup, "format R16G16_FLOAT: upload/Load/Sample and render/staging",
         "float16 texels (denormals, infinities included) read exactly as float32; representable values write exactly") {
  return CheckFormat(device, {FORMAT_R16G16_FLOAT, Kind::Float16, 2, 16});
}
SP_PROBE(kGroup, "format R16G16B16A16_FLOAT: upload/Load/Sample and render/staging",
         "float16 texels (denormals, infinities included) read exactly as float32; representable values write exactly") {
  return CheckFormat(device, {FORMAT_R16G16B16A16_FLOAT, Kind::Float16, 4, 16});
}
SP_PROBE(kGroup, "format R16_UNORM: upload/Load/Sample and render/staging",
         "reads give code / 65535 correctly rounded; writes clamp to [0, 1] and round within 0.6 LSB") {
  return CheckFormat(device, {FORMAT_R16_UNORM, Kind::Unorm, 1, 16});
}
SP_PROBE(kGroup, "format R8G8B8A8_UNORM: upload/Load/Sample and render/staging",
         "reads give code / 255 correctly rounded (all 256 codes); writes clamp to [0, 1] and round within 0.6 LSB") {
  return CheckFormat(device, {FORMAT_R8G8B8A8_UNORM, Kind::Unorm, 4, 8});
}
SP_PROBE(kGroup, "format R8G8B8A8_UNORM_SRGB: upload/Load/Sample and render/staging",
         "reads decode sRGB within 0.5 sRGB ULP (0 and 1 exact); writes encode within 0.6 LSB; alpha stays linear") {
  return CheckFormat(device, {FORMAT_R8G8B8A8_UNORM_SRGB, Kind::Srgb, 4, 8});
}
SP_PROBE(kGroup, "format R32_UINT: upload/Load and render/staging", "uint texels read and write exactly; missing channels read (0, 0, 1)") {
  return CheckFormat(device, {FORMAT_R32_UINT, Kind::Uint, 1, 32});
}

}  // namespace sp::conformance
