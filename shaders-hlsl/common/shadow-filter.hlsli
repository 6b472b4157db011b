// Shadow-map filtering (PCF) and depth-bias helpers shared by the shadow techniques.
//
// Compile-time selection (defines set by the technique):
//   SHADOW_FILTER  0 hw2x2     one SampleCmpLevelZero (the hardware's 2x2 bilinear PCF)
//                  1 box       NxN SampleCmpLevelZero taps one texel apart, equal weights
//                  2 gauss     the same taps with separable binomial weights
//                  3 gathercmp the box kernel built from GatherCmp: (N+1)^2/4 fetches instead of N^2
//                  4 poisson   16 Poisson-disk taps of radius N/2 texels, rotated per pixel
//                  5 pcss      percentage-closer soft shadows: ShadowFilterPcss, not ShadowFilter
//                              (it needs the light's size and depth range: ShadowPcssInput)
//   SHADOW_KERNEL  N, odd, 3..15, gathercmp 3..31 (ignored by hw2x2 and pcss); kernels wider than
//                  SHADOW_UNROLL_MAX are [loop]s, which compile in a fraction of the time (docs/techniques.md)
// The sampler must be a comparison sampler with LESS_EQUAL (reference <= stored depth is lit),
// MIN_MAG_LINEAR filtering; its address mode never matters because no tap leaves uvClamp.
//
// The kernels, in texel space (s = uv * mapSize - 0.5: texel centres are integers, a bilinear
// tap at p reads texels floor(p) and floor(p) + 1 with weights 1 - frac(p), frac(p)):
//   box:   taps at s + (x, y), x, y in -N/2..N/2, weight 1/N^2 each. Per axis this is the
//          (N+1)-texel footprint from floor(s) - N/2 with weights (1-f, 1, ..., 1, f) / N,
//          f = frac(s): what gathercmp builds texel by texel.
//   gauss: the same taps weighted C(N-1, x+N/2) C(N-1, y+N/2) / 4^(N-1): binomial, the discrete
//          Gaussian with sigma = sqrt(N-1)/2 = 0.71, 1, 1.22, 1.41 .. 1.87 texels for N = 3..15 (the taps'
//          bilinear interpolation adds a variance of f(1-f) <= 1/4 texel^2 per axis).
//   poisson: 16 taps at kShadowPoissonDisk * N/2 texels, rotated by a per-pixel angle, 1/16 each.
// Receiver-plane bias: a tap at texel-space offset o compares
//   depth + dot(o * texelSize, depthGradient) - min(dot(abs(depthGradient), texelSize), RECEIVER_PLANE_MAX_FOOTPRINT)
// (the last term is explained in ShadowFilterSetup; it is 0 when the gradient is).
// Every tap position is clamped, in texel space, into the centres of the texels inside uvClamp,
// which is CLAMP addressing confined to the rectangle: a tap pushed onto the edge centre reads
// the edge texel with weight 1 (its neighbour outside gets weight 0). The rectangle's edges must
// lie on texel boundaries (atlas regions do), and gathercmp needs it at least 2 texels wide.
#ifndef SHADOW_FILTER_HLSLI
#define SHADOW_FILTER_HLSLI

#ifndef SHADOW_FILTER
#define SHADOW_FILTER 0
#endif
#ifndef SHADOW_KERNEL
#define SHADOW_KERNEL 3
#endif
#if SHADOW_FILTER < 0 || SHADOW_FILTER > 5
#error SHADOW_FILTER must be 0 (hw2x2), 1 (box), 2 (gauss), 3 (gathercmp), 4 (poisson) or 5 (pcss)
#endif
#if SHADOW_FILTER != 0 && SHADOW_FILTER != 5 && (SHADOW_KERNEL < 3 || SHADOW_KERNEL % 2 == 0)
#error SHADOW_KERNEL must be odd and at least 3
#endif
#if SHADOW_FILTER == 3 && SHADOW_KERNEL > 31
#error SHADOW_KERNEL must be at most 31 for gathercmp
#endif
#if SHADOW_FILTER != 0 && SHADOW_FILTER != 3 && SHADOW_FILTER != 5 && SHADOW_KERNEL > 15
#error SHADOW_KERNEL must be at most 15 for box, gauss and poisson
#endif

// Unrolled, a 15x15 kernel is 225 taps of straight-line code that glslang, SPIRV-Cross and
// llvmpipe's compiler each take seconds over; above this width the kernels run as loops.
#ifndef SHADOW_UNROLL_MAX
#define SHADOW_UNROLL_MAX 9
#endif
#if SHADOW_KERNEL > SHADOW_UNROLL_MAX
#define SHADOW_KERNEL_LOOP [loop]
#else
#define SHADOW_KERNEL_LOOP [unroll]
#endif

#define SHADOW_KERNEL_HALF (SHADOW_KERNEL / 2)
#define SHADOW_POISSON_TAPS 16

// The most the receiver-plane footprint term (ShadowFilterSetup) may move the reference, in the
// map's depth units; a technique may define it lower before including this file. The term is a
// full texel of the receiver's slope, which grows without bound as the receiver turns edge-on to
// the light; under a small flat occluder (a column's capital over its shaft) it then moves the
// reference past the occluder: light leaks. The default leaves it unbounded, as the techniques
// whose receiver-plane mode has no other bias need (csm: clamping it brings their acne back).
#ifndef RECEIVER_PLANE_MAX_FOOTPRINT
#define RECEIVER_PLANE_MAX_FOOTPRINT 3.0e38
#endif

struct ShadowFilterInput {
  float2 uv;             // map coordinates in [0,1] of the layer (D3D: v = 0 is the top row)
  float layer;           // Texture2DArray slice
  float depth;           // receiver depth in the map's [0,1] space, already biased
  float2 texelSize;      // 1 / map size in texels
  float4 uvClamp;        // (minU, minV, maxU, maxV); (0,0,1,1) for a whole layer
  float2 depthGradient;  // receiver-plane bias d(depth)/d(uv); (0,0) disables it
  float2 pixel;          // SV_Position.xy, seeds the Poisson rotation
};

// Best-candidate points relaxed to a minimum spacing of 0.53, all within radius 0.98 and
// centred (mean within 0.006 of the origin) so the kernel adds no directional bias.
static const float2 kShadowPoissonDisk[SHADOW_POISSON_TAPS] = {
    float2(-0.4597, -0.0193), float2(0.9028, -0.3812), float2(0.2740, 0.9409),  float2(0.0066, -0.9800),
    float2(0.3682, -0.2773),  float2(-0.7239, 0.6605), float2(-0.5415, -0.8168), float2(0.7279, 0.6562),
    float2(-0.1500, 0.4225),  float2(0.5417, -0.8167), float2(0.3753, 0.2581),  float2(-0.1367, -0.4424),
    float2(-0.9651, 0.1702),  float2(-0.2618, 0.9444), float2(0.9661, 0.1647),  float2(-0.8997, -0.3885)};

#if SHADOW_KERNEL == 3
static const float kShadowBinomial[3] = {1, 2, 1};
#elif SHADOW_KERNEL == 5
static const float kShadowBinomial[5] = {1, 4, 6, 4, 1};
#elif SHADOW_KERNEL == 7
static const float kShadowBinomial[7] = {1, 6, 15, 20, 15, 6, 1};
#elif SHADOW_KERNEL == 9
static const float kShadowBinomial[9] = {1, 8, 28, 56, 70, 56, 28, 8, 1};
#elif SHADOW_KERNEL == 11
static const float kShadowBinomial[11] = {1, 10, 45, 120, 210, 252, 210, 120, 45, 10, 1};
#elif SHADOW_KERNEL == 13
static const float kShadowBinomial[13] = {1, 12, 66, 220, 495, 792, 924, 792, 495, 220, 66, 12, 1};
#else
// 15 (gathercmp 17..31 do not read it; gauss stops at 15). The largest product, 3432^2 < 2^24,
// and the sum 4^14 = 2^28 (a power of two) are exact in float.
static const float kShadowBinomial[15] = {1, 14, 91, 364, 1001, 2002, 3003, 3432, 3003, 2002, 1001, 364, 91, 14, 1};
#endif

// What every tap needs, computed once per lookup.
struct ShadowFilterFrame {
  float2 s;        // receiver in texel space
  float2 lo, hi;   // texel-space centres of the first and last texel inside uvClamp
  float reference; // depth minus the receiver-plane footprint term
};

ShadowFilterFrame ShadowFilterSetup(ShadowFilterInput i) {
  ShadowFilterFrame f;
  float2 mapSize = 1.0 / i.texelSize;
  f.s = i.uv * mapSize - 0.5;
  // round(): uvClamp is on texel boundaries, but uv * size need not come out as an exact integer.
  f.lo = round(i.uvClamp.xy * mapSize);
  f.hi = round(i.uvClamp.zw * mapSize) - 1.0;
  // Receiver-plane bias makes each tap's reference exact at the tap, but a bilinear tap compares
  // it with texel centres up to one texel away in each axis (gathercmp: half a texel), where the
  // receiver plane lies lower by up to this much; without it a tilted plane still has acne.
  f.reference = i.depth - min(dot(abs(i.depthGradient), i.texelSize), RECEIVER_PLANE_MAX_FOOTPRINT);
  return f;
}

// The receiver plane's reference depth at texel-space position p.
float ShadowFilterReference(ShadowFilterInput i, ShadowFilterFrame f, float2 p) {
  return f.reference + dot((p - f.s) * i.texelSize, i.depthGradient);
}

// One SampleCmpLevelZero tap at texel-space offset o from the receiver.
float ShadowFilterTap(Texture2DArray<float> map, SamplerComparisonState cmp, ShadowFilterInput i, ShadowFilterFrame f, float2 o) {
  float2 p = clamp(f.s + o, f.lo, f.hi);
  return map.SampleCmpLevelZero(cmp, float3((p + 0.5) * i.texelSize, i.layer), ShadowFilterReference(i, f, p));
}

// PCG (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020): integer-only, so the
// angle is the same on every backend and driver (only sincos may differ in the last bits).
uint ShadowFilterHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// (cos, sin) of the pixel's rotation angle: 24 hash bits, so the float conversion is exact.
float2 ShadowFilterRotation(float2 pixel) {
  uint2 p = uint2(pixel);
  float angle = float(ShadowFilterHash(p.x + ShadowFilterHash(p.y)) >> 8) * (6.283185307179586 / 16777216.0);
  float2 r;
  sincos(angle, r.y, r.x);
  return r;
}

// One GatherCmp over the footprint texels b and b + 1 per axis, weighted w0 (at b) and w1 (at
// b + 1) per axis. The box's clamped taps read texel clamp(t, lo, hi) for footprint texel t; gather
// the 2x2 block at g, which holds both clamp(b) and clamp(b + 1), and move each weight onto
// whichever of g, g + 1 its texel became. Needs uvClamp at least 2 texels wide.
float ShadowGatherBlock(Texture2DArray<float> map, SamplerComparisonState cmp, ShadowFilterInput i, ShadowFilterFrame f, float2 b, float2 w0, float2 w1) {
  float2 g = clamp(b, f.lo, f.hi - 1.0);
  float2 onG = w0 * float2(clamp(b, f.lo, f.hi) == g) + w1 * float2(clamp(b + 1.0, f.lo, f.hi) == g);
  float2 onG1 = w0 + w1 - onG;
  // Gather's order: (g.x, g.y+1), (g.x+1, g.y+1), (g.x+1, g.y), (g.x, g.y). Sampling at the
  // corner shared by the four centres keeps the choice of g far from any rounding boundary.
  float4 w = float4(onG.x * onG1.y, onG1.x * onG1.y, onG1.x * onG.y, onG.x * onG.y);
  float4 lit = map.GatherCmp(cmp, float3((g + 1.0) * i.texelSize, i.layer), ShadowFilterReference(i, f, g + 0.5));
  return dot(lit, w);
}

#if SHADOW_FILTER == 3
// The box kernel from GatherCmp. A gather compares one reference with its four texels, so each
// texel meets the receiver plane at its 2x2 block's centre (at most half a texel away per axis)
// instead of at each box tap that reads it (less than one texel away). Tolerance against the
// SampleCmp box: with depthGradient = 0 the kernels are identical (equal to float rounding where
// the sampler's bilinear weights are exact, as on Mesa; D3D11 hardware may round them to 8 bits,
// up to 2/256 of difference); with a gradient, results can differ only where a footprint texel's
// depth lies within dot(abs(depthGradient), texelSize) of the reference plane (ShadowFilterReference)
// at that texel.
//
// Per axis, the box kernel's (N+1)-texel footprint weights (times N): 1 - f at the first texel,
// f at the last, 1 between; a is the texel's index in the footprint (a constant once unrolled).
float2 ShadowFootprintWeight(int2 a, float2 f) {
  return float2(a.x == 0 ? 1.0 - f.x : (a.x == SHADOW_KERNEL ? f.x : 1.0), a.y == 0 ? 1.0 - f.y : (a.y == SHADOW_KERNEL ? f.y : 1.0));
}

float ShadowFilterGather(Texture2DArray<float> map, SamplerComparisonState cmp, ShadowFilterInput i, ShadowFilterFrame f) {
  float2 first = floor(f.s);
  float2 frac = f.s - first;
  first -= SHADOW_KERNEL_HALF;
  float sum = 0.0;
  // N + 1 is even, so (N+1)/2 gathers per axis tile the footprint exactly.
  SHADOW_KERNEL_LOOP for (int gy = 0; gy <= SHADOW_KERNEL_HALF; ++gy) {
    SHADOW_KERNEL_LOOP for (int gx = 0; gx <= SHADOW_KERNEL_HALF; ++gx) {
      int2 a = int2(gx, gy) * 2;
      float2 b = first + float2(a);  // this 2x2 part of the footprint: texels b and b + 1
      float2 w0 = ShadowFootprintWeight(a, frac), w1 = ShadowFootprintWeight(a + 1, frac);
      sum += ShadowGatherBlock(map, cmp, i, f, b, w0, w1);
    }
  }
  // Weights sum to 1 only up to rounding; keep the result a visibility.
  return saturate(sum * (1.0 / (SHADOW_KERNEL * SHADOW_KERNEL)));
}
#endif

#if SHADOW_FILTER != 5
// pcss has no ShadowFilter (calling it is a compile error): it needs ShadowFilterPcss's inputs.
float ShadowFilter(Texture2DArray<float> map, SamplerComparisonState cmp, ShadowFilterInput i) {
  ShadowFilterFrame f = ShadowFilterSetup(i);
#if SHADOW_FILTER == 0
  return ShadowFilterTap(map, cmp, i, f, float2(0, 0));
#elif SHADOW_FILTER == 1 || SHADOW_FILTER == 2
  float sum = 0.0;
  SHADOW_KERNEL_LOOP for (int y = -SHADOW_KERNEL_HALF; y <= SHADOW_KERNEL_HALF; ++y) {
    SHADOW_KERNEL_LOOP for (int x = -SHADOW_KERNEL_HALF; x <= SHADOW_KERNEL_HALF; ++x) {
#if SHADOW_FILTER == 1
      sum += ShadowFilterTap(map, cmp, i, f, float2(x, y));
#else
      sum += kShadowBinomial[x + SHADOW_KERNEL_HALF] * kShadowBinomial[y + SHADOW_KERNEL_HALF] * ShadowFilterTap(map, cmp, i, f, float2(x, y));
#endif
    }
  }
#if SHADOW_FILTER == 1
  return saturate(sum * (1.0 / (SHADOW_KERNEL * SHADOW_KERNEL)));
#else
  // The binomial row sums to 2^(N-1); the product of two rows to 4^(N-1) (exact in float).
  return sum * (1.0 / float(1u << (2 * (SHADOW_KERNEL - 1))));
#endif
#elif SHADOW_FILTER == 3
  return ShadowFilterGather(map, cmp, i, f);
#else
  // A rotation per pixel turns the 16 taps' banding into noise that a few pixels average out.
  float2 r = ShadowFilterRotation(i.pixel);
  float radius = SHADOW_KERNEL * 0.5;
  float sum = 0.0;
  [unroll] for (int k = 0; k < SHADOW_POISSON_TAPS; ++k) {
    float2 d = kShadowPoissonDisk[k] * radius;
    sum += ShadowFilterTap(map, cmp, i, f, float2(d.x * r.x - d.y * r.y, d.x * r.y + d.y * r.x));
  }
  return sum * (1.0 / SHADOW_POISSON_TAPS);
#endif
}
#endif

// Receiver-plane depth bias (Isidoro, "Shadow mapping: GPU-based tips and techniques", GDC 2006).
// Across the screen, (dz/dx, dz/dy) = J (dz/du, dz/dv) with J = [du/dx dv/dx; du/dy dv/dy];
// inverting J gives the receiver's depth slope in map space. Pass ddx/ddy of (u, v, depth).
float2 ReceiverPlaneDepthGradient(float3 coordDdx, float3 coordDdy) {
  float det = coordDdx.x * coordDdy.y - coordDdx.y * coordDdy.x;
  // Relative test: when the two products cancel to within 1e-3 the pixel's footprint in the map is
  // a sliver (a receiver seen edge-on), float error in ddx/ddy dominates the inverse and the
  // "gradient" would be a huge random bias. (0,0) leaves the caller's constant bias in charge.
  // Written as !(a > b) so a NaN derivative is also rejected.
  if (!(abs(det) > 1e-3 * (abs(coordDdx.x * coordDdy.y) + abs(coordDdx.y * coordDdy.x)))) return float2(0, 0);
  return float2(coordDdy.y * coordDdx.z - coordDdx.y * coordDdy.z, coordDdx.x * coordDdy.z - coordDdy.x * coordDdx.z) / det;
}

// Normal-offset bias: move the receiver along its normal before projecting it into the map.
// Acne comes from the map's depth varying across one texel's footprint on the receiver, which
// is zero facing the light and grows towards grazing; (1 - N.L) follows that while staying
// bounded (the exact tan(angle) is not), and one world-space texel is the footprint's size.
// Back faces (N.L < 0) get the full offset. Both vectors are normalized here so interpolated
// normals can be passed as they are.
float3 NormalOffset(float3 worldNormal, float3 toLight, float worldTexelSize, float scale) {
  float3 n = normalize(worldNormal);
  return n * (scale * worldTexelSize * (1.0 - saturate(dot(n, normalize(toLight)))));
}

#endif  // SHADOW_FILTER_HLSLI
