// GenerateMips on a texture created with RESOURCE_MISC_GENERATE_MIPS: every level below the top
// is computed from the level above. D3D11 does not specify the filter beyond that; for power-of-
// two sizes every texel of level l + 1 covers exactly a 2x2 block of level l (2x1 or 1x2 once one
// side is 1), and any linear filter centred on that block, which is what GenerateMips
// implementations use, gives the block's average. So each generated texel is checked against the
// box average of the level above as the device stored it (not of a CPU chain, so rounding does
// not accumulate):
//   UNORM8: |texel - average| <= 1 LSB (the average converted to 8 bits, rounding or truncating);
//   float32: the average rounded to float32, plus a float rounding per addition (3 ulp).
#include <cstring>

#include "sampling-util.h"

namespace sp::conformance::sampling {
namespace {

Result Run(Device& device, uint32_t w, uint32_t h, FORMAT fmt) {
  const FormatInfo& fi = GetFormatInfo(fmt);
  const uint32_t need = FORMAT_SUPPORT_MIP | FORMAT_SUPPORT_RENDER_TARGET | FORMAT_SUPPORT_SHADER_SAMPLE;
  if ((device.CheckFormatSupport(fmt) & need) != need) return Unsupported(std::string(FormatName(fmt)) + " cannot have generated mips here");
  const bool unorm = fi.kind == FormatKind::UNorm;
  const uint32_t channels = fi.components, bytes = fi.bytesPerElement / channels;

  // A pattern with detail at every scale: smooth gradients plus pseudo-random texels.
  std::vector<uint8_t> top(size_t(w) * h * fi.bytesPerElement);
  uint32_t seed = 12345;
  for (uint32_t i = 0; i < w * h * channels; ++i) {
    seed = seed * 1664525u + 1013904223u;
    uint32_t x = (i / channels) % w, y = (i / channels) / w, c = i % channels;
    double value = 0.5 * ((x * (c + 1) * 7 + y * 13) % 64) / 64.0 + 0.5 * double(seed >> 24) / 255.0;
    if (unorm) {
      top[i] = uint8_t(std::lround(value * 255));
    } else {
      float f = float(value);
      std::memcpy(&top[size_t(i) * 4], &f, 4);
    }
  }
  Ref<Texture2D> tex = gpu::MakeTexture2D(device, w, h, fmt, BIND_SHADER_RESOURCE | BIND_RENDER_TARGET, nullptr, 0, 1, 1, RESOURCE_MISC_GENERATE_MIPS);
  DeviceContext& ctx = *device.GetImmediateContext();
  ctx.UpdateSubresource(tex.get(), 0, nullptr, top.data(), w * fi.bytesPerElement, 0);
  Ref<ShaderResourceView> srv = device.CreateShaderResourceView(tex.get());
  ctx.GenerateMips(srv.get());

  const uint32_t levels = tex->GetDesc().MipLevels;
  auto read = [&](const std::vector<uint8_t>& raw, size_t index) {
    if (unorm) return double(raw[index]);
    float f;
    std::memcpy(&f, &raw[index * bytes], 4);
    return double(f);
  };
  Worst worst;
  std::vector<uint8_t> above = gpu::ReadTexture(device, ctx, tex.get(), 0);
  if (above != top) return Fail("GenerateMips changed level 0");
  for (uint32_t l = 1; l < levels; ++l) {
    std::vector<uint8_t> below = gpu::ReadTexture(device, ctx, tex.get(), l);
    const uint32_t aw = std::max(1u, w >> (l - 1)), ah = std::max(1u, h >> (l - 1));
    const uint32_t bw = std::max(1u, w >> l), bh = std::max(1u, h >> l);
    for (uint32_t y = 0; y < bh; ++y)
      for (uint32_t x = 0; x < bw; ++x)
        for (uint32_t c = 0; c < channels; ++c) {
          double sum = 0;
          int n = 0;
          for (uint32_t dy = 0; dy < 2; ++dy)
            for (uint32_t dx = 0; dx < 2; ++dx) {
              uint32_t sx = std::min(2 * x + dx, aw - 1), sy = std::min(2 * y + dy, ah - 1);
              if ((aw == 1 && dx) || (ah == 1 && dy)) continue;
              sum += read(above, (size_t(sy) * aw + sx) * channels + c);
              ++n;
            }
          double avg = sum / n, got = read(below, (size_t(y) * bw + x) * channels + c);
          double err = std::abs(got - avg);
          std::string where = "level " + std::to_string(l) + " texel (" + std::to_string(x) + "," + std::to_string(y) + ") channel " + std::to_string(c) +
                              ": got " + Fmt(got) + ", box average " + Fmt(avg);
          if (unorm)
            worst.AddError(err, 1.0, where);
          else
            worst.AddError(err / FloatUlp(std::max(std::abs(avg), 1e-30)), 3.0, where);
        }
    above = std::move(below);
  }
  return worst.Finish(unorm ? "LSB" : "ulp");
}

}  // namespace

SP_PROBE(kGroup, "GenerateMips R8G8B8A8_UNORM 64x64: each level is the 2x2 box of the level above",
         "every generated texel is within 1 LSB of the average of its 2x2 block in the level above") {
  return Run(device, 64, 64, FORMAT_R8G8B8A8_UNORM);
}
SP_PROBE(kGroup, "GenerateMips R8G8B8A8_UNORM 64x16 (2x1 boxes below height 1)",
         "non-square power of two: once a side is 1 the box is 2x1; within 1 LSB") {
  return Run(device, 64, 16, FORMAT_R8G8B8A8_UNORM);
}
SP_PROBE(kGroup, "GenerateMips R32_FLOAT 32x32", "every generated texel is the float average of its 2x2 block (3 ulp)") {
  return Run(device, 32, 32, FORMAT_R32_FLOAT);
}

}  // namespace sp::conformance::sampling
