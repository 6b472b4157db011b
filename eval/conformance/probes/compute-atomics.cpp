// Interlocked* on groupshared memory and on UAVs (RWStructuredBuffer, RWByteAddressBuffer,
// RWTexture2D<uint>/<int>), with their original-value outputs. The order in which threads apply
// their operations is not defined, so each check is an invariant that holds for every order and
// fails for any wrong result: the originals of InterlockedAdd chain from the initial value to
// the final one, the originals of bit operations gain (or lose) exactly one bit per operation,
// Exchange and CompareExchange hand every value on exactly once, and Min/Max compare signed for
// int and unsigned for uint.
#include <algorithm>
#include <bit>
#include <map>

#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Compute";

enum Target { kGroupshared, kStructured, kRaw, kTexture };

const char* kSource = R"(
#define THREADS 64
#define GROUPS 4
#if TARGET == 0
groupshared uint gu[8];
groupshared int gi[2];
#define ATOMIC_U(op, i, v, o) Interlocked##op(gu[i], v, o)
#define ATOMIC_I(op, i, v, o) Interlocked##op(gi[i], v, o)
#define CMPXCHG_U(i, c, v, o) InterlockedCompareExchange(gu[i], c, v, o)
#elif TARGET == 1
RWStructuredBuffer<uint> su : register(u0);
RWStructuredBuffer<int> si : register(u1);
#define ATOMIC_U(op, i, v, o) Interlocked##op(su[i], v, o)
#define ATOMIC_I(op, i, v, o) Interlocked##op(si[i], v, o)
#define CMPXCHG_U(i, c, v, o) InterlockedCompareExchange(su[i], c, v, o)
#elif TARGET == 2
RWByteAddressBuffer ru : register(u0);
RWByteAddressBuffer ri : register(u1);
#define ATOMIC_U(op, i, v, o) ru.Interlocked##op((i) * 4, v, o)
#define ATOMIC_I(op, i, v, o) ri.Interlocked##op((i) * 4, v, o)
#define CMPXCHG_U(i, c, v, o) ru.InterlockedCompareExchange((i) * 4, c, v, o)
#else
RWTexture2D<uint> tu : register(u0);
RWTexture2D<int> ti : register(u1);
#define ATOMIC_U(op, i, v, o) Interlocked##op(tu[uint2(i, 0)], v, o)
#define ATOMIC_I(op, i, v, o) Interlocked##op(ti[uint2(i, 0)], v, o)
#define CMPXCHG_U(i, c, v, o) InterlockedCompareExchange(tu[uint2(i, 0)], c, v, o)
#endif
RWStructuredBuffer<uint> originals : register(u2);  // [op * THREADS * GROUPS + thread]
RWStructuredBuffer<uint> finals : register(u3);     // groupshared only: [group * 10 + slot]

[numthreads(THREADS, 1, 1)] void main(uint local : SV_GroupIndex, uint3 group : SV_GroupID) {
  uint slot = group.x * THREADS + local;  // where this thread's originals go
#if TARGET == 0
  uint t = local;
  if (t == 0) {
    gu[0] = 1000; gu[1] = 0xffffffffu; gu[2] = 5; gu[3] = 0; gu[4] = 0xffffffffu; gu[5] = 0xf0f0f0f0u; gu[6] = 0xabcdefu; gu[7] = 0;
    gi[0] = 0; gi[1] = -2000000;
  }
  GroupMemoryBarrierWithGroupSync();
#else
  uint t = slot;
#endif
  const uint n = THREADS * GROUPS;
  uint o;
  ATOMIC_U(Add, 0, (t * 7) % 13 + 1, o); originals[0 * n + slot] = o;
  ATOMIC_U(Min, 1, t * 2654435761u + 12345u, o); originals[1 * n + slot] = o;
  ATOMIC_U(Max, 2, t * 2654435761u + 777u, o); originals[2 * n + slot] = o;
  if (t < 32) {
    ATOMIC_U(Or, 3, 1u << t, o); originals[3 * n + slot] = o;
    ATOMIC_U(And, 4, ~(1u << t), o); originals[4 * n + slot] = o;
    ATOMIC_U(Xor, 5, 1u << t, o); originals[5 * n + slot] = o;
  }
  ATOMIC_U(Exchange, 6, t + 1, o); originals[6 * n + slot] = o;
  CMPXCHG_U(7, 0, t + 1, o); originals[7 * n + slot] = o;
#if SIGNED_OPS
  int value = ((t & 1) ? -1 : 1) * int((t * 37) % 1009 + 1);
  int io;
  ATOMIC_I(Min, 0, value, io); originals[8 * n + slot] = asuint(io);
  ATOMIC_I(Max, 1, value, io); originals[9 * n + slot] = asuint(io);
#endif
#if TARGET == 0
  GroupMemoryBarrierWithGroupSync();
  if (t < 8) finals[group.x * 10 + t] = gu[t];
  if (t < 2) finals[group.x * 10 + 8 + t] = asuint(gi[t]);
#endif
}
)";

constexpr uint32_t kThreads = 64, kGroups = 4, kTotal = kThreads * kGroups, kOps = 10;
const uint32_t kInitial[kOps] = {1000, 0xffffffffu, 5, 0, 0xffffffffu, 0xf0f0f0f0u, 0xabcdefu, 0, 0, uint32_t(-2000000)};

uint32_t AddValue(uint32_t t) { return (t * 7) % 13 + 1; }
uint32_t MinValue(uint32_t t) { return t * 2654435761u + 12345u; }
uint32_t MaxValue(uint32_t t) { return t * 2654435761u + 777u; }
int32_t SignedValue(uint32_t t) { return ((t & 1) ? -1 : 1) * int32_t((t * 37) % 1009 + 1); }

// Checks one domain (a thread group for groupshared, the whole dispatch for UAVs): `orig[op][t]`
// are the original values returned to thread t, `final[op]` what memory holds afterwards.
void CheckDomain(Mismatches& m, const std::string& domain, uint32_t threads, const std::vector<std::vector<uint32_t>>& orig, const uint32_t* final,
                 bool withSigned) {
  std::string at = domain + ": ";
  // InterlockedAdd: sorted by original value, each original is the previous one plus the
  // previous thread's addend (all addends are positive, so the originals are distinct).
  {
    std::vector<std::pair<uint32_t, uint32_t>> seq;
    for (uint32_t t = 0; t < threads; ++t) seq.push_back({orig[0][t], AddValue(t)});
    std::sort(seq.begin(), seq.end());
    uint32_t expect = kInitial[0];
    for (auto& [o, v] : seq) {
      m.Check(o, expect, at + "InterlockedAdd original values do not chain");
      expect = o + v;
    }
    m.Check(final[0], expect, at + "InterlockedAdd final value");
  }
  // Min / Max, unsigned and signed: the final value is exact; every original is the initial
  // value or another thread's operand, never the thread's own, and never beyond the final.
  auto minmax = [&](uint32_t op, bool isMin, bool isSigned, auto value) {
    const char* name = op == 1   ? "InterlockedMin (uint)"
                       : op == 2 ? "InterlockedMax (uint)"
                       : op == 8 ? "InterlockedMin (int)"
                                 : "InterlockedMax (int)";
    auto less = [&](uint32_t a, uint32_t b) { return isSigned ? int32_t(a) < int32_t(b) : a < b; };
    uint32_t best = kInitial[op];
    std::map<uint32_t, int> operands;
    for (uint32_t t = 0; t < threads; ++t) {
      uint32_t v = uint32_t(value(t));
      operands[v]++;
      if (isMin ? less(v, best) : less(best, v)) best = v;
    }
    m.Check(final[op], best, at + name + " final value");
    uint32_t sawInitial = 0;
    for (uint32_t t = 0; t < threads; ++t) {
      uint32_t o = orig[op][t], own = uint32_t(value(t));
      sawInitial += o == kInitial[op];
      m.Expect(o == kInitial[op] || operands.count(o),
               at + name + ": thread " + std::to_string(t) + " got original " + std::to_string(o) + ", which no thread wrote");
      m.Expect(o != own || operands[own] > 1, at + name + ": thread " + std::to_string(t) + " got its own operand as the original value");
      m.Expect(!(isMin ? less(o, best) : less(best, o)), at + name + ": an original value lies beyond the final one");
    }
    m.Expect(sawInitial >= 1, at + name + ": no thread saw the initial value");
  };
  minmax(1, true, false, MinValue);
  minmax(2, false, false, MaxValue);
  if (withSigned) {
    minmax(8, true, true, SignedValue);
    minmax(9, false, true, SignedValue);
  }
  // Or / And / Xor by the first 32 threads, one distinct bit each: thread t's original lacks
  // (Or, Xor) or has (And) bit t, and the originals' popcounts are 0..31 (32..1) in some order.
  const char* bitNames[3] = {"InterlockedOr", "InterlockedAnd", "InterlockedXor"};
  uint32_t bitFinals[3] = {0xffffffffu, 0, kInitial[5] ^ 0xffffffffu};
  for (uint32_t k = 0; k < 3; ++k) {
    uint32_t op = 3 + k;
    std::vector<int> seen(33, 0);
    for (uint32_t t = 0; t < 32 && t < threads; ++t) {
      uint32_t bits = k == 1 ? ~orig[op][t] : k == 2 ? orig[op][t] ^ kInitial[5] : orig[op][t];
      m.Expect(!(bits & (1u << t)), at + bitNames[k] + ": thread " + std::to_string(t) + "'s original already holds its change");
      seen[std::popcount(bits)]++;
    }
    for (uint32_t c = 0; c < 32; ++c) m.Check(seen[c], 1, at + bitNames[k] + " originals with " + std::to_string(c) + " bits changed");
    m.Check(final[op], bitFinals[k], at + bitNames[k] + " final value");
  }
  // Exchange: the originals plus the final value are the initial value plus every operand.
  {
    std::vector<uint32_t> got, want = {kInitial[6]};
    for (uint32_t t = 0; t < threads; ++t) {
      got.push_back(orig[6][t]);
      want.push_back(t + 1);
      m.Expect(orig[6][t] != t + 1, at + "InterlockedExchange: thread " + std::to_string(t) + " got its own value back");
    }
    got.push_back(final[6]);
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    m.Expect(got == want, at + "InterlockedExchange: originals + final are not the initial value and every operand exactly once");
  }
  // CompareExchange(0 -> t + 1): exactly one thread wins and sees 0, the others see its value.
  {
    uint32_t winners = 0, winner = 0;
    for (uint32_t t = 0; t < threads; ++t)
      if (orig[7][t] == 0) ++winners, winner = t;
    m.Check(winners, 1u, at + "InterlockedCompareExchange threads that saw the compare value");
    for (uint32_t t = 0; t < threads; ++t)
      if (t != winner) m.Check(orig[7][t], winner + 1, at + "InterlockedCompareExchange original of a losing thread");
    m.Check(final[7], winner + 1, at + "InterlockedCompareExchange final value");
  }
}

Result RunAtomics(Device& device, Target target, bool withSigned = true) {
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<uint32_t> initU(kInitial, kInitial + 8);
  std::vector<int32_t> initI = {int32_t(kInitial[8]), int32_t(kInitial[9])};
  BufferViews originals = MakeStructured(device, kOps * kTotal, 4), finals = MakeStructured(device, kGroups * 10, 4);
  BufferViews bu, bi;
  TextureViews tu, ti;
  UnorderedAccessView *uu = nullptr, *ui = nullptr;
  if (target == kStructured) {
    bu = MakeStructured(device, 8, 4, initU.data());
    bi = MakeStructured(device, 2, 4, initI.data());
  } else if (target == kRaw) {
    bu = MakeRaw(device, 32, initU.data());
    bi = MakeRaw(device, 8, initI.data());
  } else if (target == kTexture) {
    tu = MakeUavTexture(device, 8, 1, FORMAT_R32_UINT, 1, initU.data());
    ti = MakeUavTexture(device, 2, 1, FORMAT_R32_SINT, 1, initI.data());
  }
  if (bu.uav) uu = bu.uav.get(), ui = bi.uav.get();
  if (tu.uav) uu = tu.uav.get(), ui = ti.uav.get();
  const char* names[] = {"atomics-groupshared", "atomics-structured", "atomics-raw", "atomics-texture"};
  Ref<ComputeShader> shader =
      MakeCS(device, kSource, names[target], "main", {{"TARGET", std::to_string(int(target))}, {"SIGNED_OPS", withSigned ? "1" : "0"}});
  ctx.CSSetShader(shader.get());
  ctx.CSSetUnorderedAccessViews(0, {uu, ui, originals.uav.get(), finals.uav.get()});
  ctx.Dispatch(kGroups, 1, 1);

  std::vector<uint32_t> o = ReadBufferAs<uint32_t>(device, originals.buffer.get());
  std::vector<uint32_t> f;
  if (target == kGroupshared) {
    f = ReadBufferAs<uint32_t>(device, finals.buffer.get());
  } else {
    std::vector<uint32_t> a = bu.buffer ? ReadBufferAs<uint32_t>(device, bu.buffer.get()) : ReadTextureAs<uint32_t>(device, tu.texture.get());
    std::vector<uint32_t> b = bi.buffer ? ReadBufferAs<uint32_t>(device, bi.buffer.get()) : ReadTextureAs<uint32_t>(device, ti.texture.get());
    f = a;
    f.insert(f.end(), b.begin(), b.end());
  }
  Mismatches m("invariants");
  uint32_t domains = target == kGroupshared ? kGroups : 1, threads = target == kGroupshared ? kThreads : kTotal;
  for (uint32_t d = 0; d < domains; ++d) {
    std::vector<std::vector<uint32_t>> orig(kOps, std::vector<uint32_t>(threads));
    for (uint32_t op = 0; op < kOps; ++op)
      for (uint32_t t = 0; t < threads; ++t) orig[op][t] = o[op * kTotal + d * threads + t];
    CheckDomain(m, target == kGroupshared ? "group " + std::to_string(d) : std::string("dispatch"), threads, orig, f.data() + d * 10, withSigned);
  }
  return m.Finish("invariants");
}

}  // namespace

SP_PROBE(kGroup, "Interlocked* on groupshared memory, with original values",
         "Add/Min/Max/And/Or/Xor/Exchange/CompareExchange on groupshared uint and int are atomic within a group; int Min/Max compare signed") {
  return RunAtomics(device, kGroupshared);
}
SP_PROBE(kGroup, "Interlocked* on RWStructuredBuffer, with original values",
         "the same operations on structured UAV elements are atomic across thread groups") {
  return RunAtomics(device, kStructured);
}
SP_PROBE(kGroup, "Interlocked* on RWByteAddressBuffer, with original values",
         "RWByteAddressBuffer.Interlocked* at byte offsets are atomic across thread groups (int literal operands included)") {
  return RunAtomics(device, kRaw, false);
}
// GLSL's atomicMin/atomicMax take their signedness from the memory (the buffer's uint words), so
// the GL backend cannot run D3D11's int overloads on a RWByteAddressBuffer: the toolchain makes
// the GL driver reject such a shader with a message instead of comparing unsigned. The probe
// checks that the rejection happens (never a silently unsigned compare) and reports it as
// unsupported on GL; use RWStructuredBuffer<int> there.
SP_PROBE(kGroup, "RWByteAddressBuffer InterlockedMin/Max with int values compare signed",
         "the int overloads of RWByteAddressBuffer.InterlockedMin/InterlockedMax compare as signed integers") {
  if (device.GetBackend() != Backend::OpenGL) return RunAtomics(device, kRaw, true);
  try {
    RunAtomics(device, kRaw, true);
  } catch (const Error& e) {
    if (std::string(e.what()).find("InterlockedMin/InterlockedMax with an int value on a RWByteAddressBuffer") != std::string::npos)
      return Unsupported("GLSL atomicMin/atomicMax on a byte-address buffer's uint words compare unsigned; the toolchain rejects the shader with "
                         "SP_SHADER_COMPILE_FAILED (use RWStructuredBuffer<int>)");
    throw;
  }
  return Fail("the GL backend accepted a signed InterlockedMin/Max on a RWByteAddressBuffer, which GLSL compares unsigned");
}
SP_PROBE(kGroup, "Interlocked* on RWTexture2D<uint>/<int>, with original values",
         "atomics on R32_UINT / R32_SINT texture UAVs are atomic across thread groups") {
  return RunAtomics(device, kTexture);
}

}  // namespace sp::conformance
