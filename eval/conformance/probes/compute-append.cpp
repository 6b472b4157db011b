// Append/consume buffers and UAV counters: the hidden counter of a structured UAV created with
// BUFFER_UAV_FLAG_APPEND or _COUNTER, set through pUAVInitialCounts (-1 keeps it), read with
// CopyStructureCount; Append writes at the counter and increments it, Consume decrements it and
// reads the element there, IncrementCounter/DecrementCounter return the value before/after.
#include <algorithm>

#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Compute";
constexpr uint32_t kKeep = 0xffffffffu;

// The structure count of `uav` as CopyStructureCount writes it (into a buffer at offset 4).
uint32_t StructureCount(Device& device, UnorderedAccessView* uav) {
  std::vector<uint32_t> zero(4, 0);
  Ref<Buffer> dst = gpu::MakeBuffer(device, BIND_SHADER_RESOURCE, zero.data(), 16, RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS);
  device.GetImmediateContext()->CopyStructureCount(dst.get(), 4, uav);
  return ReadBufferAs<uint32_t>(device, dst.get())[1];
}

const char* kAppend = R"(
struct Item { uint id; float value; };
AppendStructuredBuffer<Item> items : register(u0);
cbuffer Pass : register(b0) { uint base; uint modulus; uint2 pad; };
[numthreads(64, 1, 1)] void main(uint i : SV_DispatchThreadID) {
  if ((i * 7) % modulus == 0) {
    Item it;
    it.id = base + i;
    it.value = i * 0.5;
    items.Append(it);
  }
}
)";

struct Item {
  uint32_t id;
  float value;
  bool operator<(const Item& o) const { return id < o.id; }
  bool operator==(const Item& o) const { return id == o.id && value == o.value; }
};

// Items appended by a dispatch of `groups` x 64 threads with the constants (base, modulus).
std::vector<Item> Appended(uint32_t groups, uint32_t base, uint32_t modulus) {
  std::vector<Item> v;
  for (uint32_t i = 0; i < groups * 64; ++i)
    if ((i * 7) % modulus == 0) v.push_back({base + i, float(i) * 0.5f});
  return v;
}

}  // namespace

SP_PROBE(kGroup, "AppendStructuredBuffer: count and multiset of appended items",
         "Append from many threads writes each item once at [0, count); CopyStructureCount gives the count") {
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t Capacity = 512, Groups = 6;
  std::vector<Item> sentinel(Capacity, Item{0xffffffffu, -1.0f});
  BufferViews buf = MakeStructured(device, Capacity, sizeof(Item), sentinel.data(), BUFFER_UAV_FLAG_APPEND);
  uint32_t consts[4] = {100000, 3, 0, 0};
  Ref<Buffer> cb = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, consts, 16);
  Ref<ComputeShader> shader = MakeCS(device, kAppend, "append");
  ctx.CSSetShader(shader.get());
  ctx.CSSetConstantBuffers(0, {cb.get()});
  UnorderedAccessView* uavs[] = {buf.uav.get()};
  const uint32_t zero[] = {0};
  ctx.CSSetUnorderedAccessViews(0, 1, uavs, zero);
  ctx.Dispatch(Groups, 1, 1);
  std::vector<Item> expect = Appended(Groups, 100000, 3);
  uint32_t count = StructureCount(device, buf.uav.get());
  std::vector<Item> got = ReadBufferAs<Item>(device, buf.buffer.get());
  Mismatches m("items");
  m.Check(count, uint32_t(expect.size()), "structure count");
  std::vector<Item> appended(got.begin(), got.begin() + std::min<size_t>(expect.size(), got.size()));
  std::sort(appended.begin(), appended.end());
  for (size_t i = 0; i < expect.size(); ++i)
    m.Expect(appended[i] == expect[i], "appended items are not the expected multiset (sorted position " + std::to_string(i) + ": id " +
                                           std::to_string(appended[i].id) + ", expected " + std::to_string(expect[i].id) + ")");
  for (size_t i = expect.size(); i < Capacity; ++i) m.Check(got[i].id, 0xffffffffu, "element " + std::to_string(i) + " beyond the count");
  return m.Finish();
}

SP_PROBE(kGroup, "pUAVInitialCounts sets the append counter, -1 keeps it",
         "CSSetUnorderedAccessViews with an initial count appends after it; (UINT)-1 keeps the current count across bindings") {
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t Capacity = 256;
  std::vector<Item> sentinel(Capacity, Item{0xffffffffu, -1.0f});
  BufferViews buf = MakeStructured(device, Capacity, sizeof(Item), sentinel.data(), BUFFER_UAV_FLAG_APPEND);
  BufferViews other = MakeStructured(device, 4, 4);
  uint32_t c0[4] = {1000, 5, 0, 0}, c1[4] = {2000, 4, 0, 0}, c2[4] = {3000, 16, 0, 0};
  Ref<Buffer> cb0 = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, c0, 16), cb1 = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, c1, 16),
              cb2 = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, c2, 16);
  Ref<ComputeShader> shader = MakeCS(device, kAppend, "append");
  ctx.CSSetShader(shader.get());
  UnorderedAccessView* uavs[] = {buf.uav.get()};
  UnorderedAccessView* unrelated[] = {other.uav.get()};
  const uint32_t seven[] = {7}, keep[] = {kKeep}, three[] = {3};
  Mismatches m("values");
  // 1: count 7, append; 2: rebind (after binding something else) with -1 and append again.
  ctx.CSSetConstantBuffers(0, {cb0.get()});
  ctx.CSSetUnorderedAccessViews(0, 1, uavs, seven);
  ctx.Dispatch(1, 1, 1);
  std::vector<Item> first = Appended(1, 1000, 5);
  ctx.CSSetUnorderedAccessViews(0, 1, unrelated, nullptr);
  ctx.CSSetConstantBuffers(0, {cb1.get()});
  ctx.CSSetUnorderedAccessViews(0, 1, uavs, keep);
  ctx.Dispatch(1, 1, 1);
  std::vector<Item> second = Appended(1, 2000, 4);
  uint32_t afterKeep = StructureCount(device, buf.uav.get());
  m.Check(afterKeep, uint32_t(7 + first.size() + second.size()), "count after initial count 7, an append pass, -1 and another pass");
  std::vector<Item> got = ReadBufferAs<Item>(device, buf.buffer.get());
  for (uint32_t i = 0; i < 7; ++i) m.Check(got[i].id, 0xffffffffu, "element " + std::to_string(i) + " below the initial count");
  std::vector<Item> a(got.begin() + 7, got.begin() + 7 + first.size()), b(got.begin() + 7 + first.size(), got.begin() + afterKeep);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  m.Expect(a == first, "the first pass's items are not at [7, 7 + n1)");
  m.Expect(b == second, "the second pass's items do not follow the first pass's");
  // 3: an explicit count resets the counter; the next pass overwrites from there.
  ctx.CSSetConstantBuffers(0, {cb2.get()});
  ctx.CSSetUnorderedAccessViews(0, 1, uavs, three);
  ctx.Dispatch(1, 1, 1);
  std::vector<Item> third = Appended(1, 3000, 16);
  m.Check(StructureCount(device, buf.uav.get()), uint32_t(3 + third.size()), "count after resetting to 3 and a pass");
  got = ReadBufferAs<Item>(device, buf.buffer.get());
  std::vector<Item> c(got.begin() + 3, got.begin() + 3 + third.size());
  std::sort(c.begin(), c.end());
  m.Expect(c == third, "after resetting the count to 3, the items are not at [3, 3 + n3)");
  return m.Finish();
}

SP_PROBE(kGroup, "ConsumeStructuredBuffer takes items from the top",
         "Consume decrements the counter and returns the element at the new count: n consumes return elements [count - n, count)") {
  const char* cs = R"(
ConsumeStructuredBuffer<uint> source : register(u0);
RWStructuredBuffer<uint> taken : register(u1);
[numthreads(8, 1, 1)] void main(uint i : SV_DispatchThreadID) { taken[i] = source.Consume(); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t Capacity = 64, Initial = 40, Taken = 16;
  std::vector<uint32_t> values(Capacity);
  for (uint32_t i = 0; i < Capacity; ++i) values[i] = 7000 + i * 3;
  BufferViews source = MakeStructured(device, Capacity, 4, values.data(), BUFFER_UAV_FLAG_APPEND);
  BufferViews taken = MakeStructured(device, Taken, 4);
  Ref<ComputeShader> shader = MakeCS(device, cs, "consume");
  ctx.CSSetShader(shader.get());
  UnorderedAccessView* uavs[] = {source.uav.get(), taken.uav.get()};
  const uint32_t counts[] = {Initial, kKeep};
  ctx.CSSetUnorderedAccessViews(0, 2, uavs, counts);
  ctx.Dispatch(Taken / 8, 1, 1);
  Mismatches m("values");
  m.Check(StructureCount(device, source.uav.get()), Initial - Taken, "count after consuming");
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device, taken.buffer.get());
  std::sort(got.begin(), got.end());
  for (uint32_t i = 0; i < Taken; ++i) m.Check(got[i], values[Initial - Taken + i], "consumed values (sorted) " + std::to_string(i));
  return m.Finish();
}

SP_PROBE(kGroup, "IncrementCounter/DecrementCounter on a COUNTER UAV",
         "IncrementCounter returns the count before, DecrementCounter the count after; each value exactly once") {
  const char* cs = R"(
RWStructuredBuffer<uint> slots : register(u0);
RWStructuredBuffer<uint> results : register(u1);
[numthreads(32, 1, 1)] void Increment(uint i : SV_DispatchThreadID) {
  uint n = slots.IncrementCounter();
  slots[n] = i + 500;
  results[i] = n;
}
[numthreads(32, 1, 1)] void Decrement(uint i : SV_DispatchThreadID) { results[i] = slots.DecrementCounter(); }
)";
  DeviceContext& ctx = *device.GetImmediateContext();
  constexpr uint32_t Threads = 64, Initial = 10;
  std::vector<uint32_t> zero(Threads + Initial + 8, 0);
  BufferViews slots = MakeStructured(device, uint32_t(zero.size()), 4, zero.data(), BUFFER_UAV_FLAG_COUNTER);
  BufferViews inc = MakeStructured(device, Threads, 4), dec = MakeStructured(device, Threads / 2, 4);
  Ref<ComputeShader> up = MakeCS(device, cs, "uav-counter", "Increment"), down = MakeCS(device, cs, "uav-counter", "Decrement");
  UnorderedAccessView* a[] = {slots.uav.get(), inc.uav.get()};
  UnorderedAccessView* b[] = {slots.uav.get(), dec.uav.get()};
  const uint32_t initial[] = {Initial, kKeep}, keep[] = {kKeep, kKeep};
  ctx.CSSetShader(up.get());
  ctx.CSSetUnorderedAccessViews(0, 2, a, initial);
  ctx.Dispatch(Threads / 32, 1, 1);
  Mismatches m("values");
  m.Check(StructureCount(device, slots.uav.get()), Initial + Threads, "count after IncrementCounter");
  ctx.CSSetShader(down.get());
  ctx.CSSetUnorderedAccessViews(0, 2, b, keep);
  ctx.Dispatch(Threads / 64, 1, 1);
  m.Check(StructureCount(device, slots.uav.get()), Initial + Threads - Threads / 2, "count after DecrementCounter");
  std::vector<uint32_t> gi = ReadBufferAs<uint32_t>(device, inc.buffer.get()), gd = ReadBufferAs<uint32_t>(device, dec.buffer.get());
  std::vector<uint32_t> gs = ReadBufferAs<uint32_t>(device, slots.buffer.get());
  std::vector<uint32_t> si = gi, sd = gd;
  std::sort(si.begin(), si.end());
  std::sort(sd.begin(), sd.end());
  for (uint32_t i = 0; i < Threads; ++i) {
    m.Check(si[i], Initial + i, "IncrementCounter results (sorted) " + std::to_string(i));
    m.Check(gs[gi[i] % gs.size()], i + 500, "slot written at thread " + std::to_string(i) + "'s counter value");
  }
  for (uint32_t i = 0; i < Threads / 2; ++i) m.Check(sd[i], Initial + Threads / 2 + i, "DecrementCounter results (sorted) " + std::to_string(i));
  return m.Finish();
}

}  // namespace sp::conformance
