// HLSL constant-buffer packing (fxc's rules for SM4/5 cbuffers), computed here independently of
// the toolchain: members are 4-byte aligned and never straddle a 16-byte register; arrays,
// structs and multi-register matrices start a register; every array element starts a register;
// a column_major floatRxC takes C registers of R components, a row_major one R registers of C;
// and the member after an array, struct or matrix may pack into its last register. Each probe
// declares a cbuffer, fills a buffer on the CPU with distinct values at these offsets (poison in
// the padding), and a shader writes every scalar it reads to a UAV (or render target); the bits
// must match. The reflection's member offsets are compared with the same computation.
#include <map>
#include <sstream>

#include "compute-helpers.h"

namespace sp::conformance {
namespace {

const char* kGroup = "Constant buffers";

struct StructDef;
struct Type {
  enum Kind { Scalar, Vector, Matrix, Struct } kind = Scalar;
  std::string base = "float";   // float, int, uint, bool
  uint32_t rows = 1, cols = 1;  // vectors: cols components; matrices: floatRxC
  bool rowMajor = false;
  uint32_t count = 0;  // array elements, 0 when not an array
  const StructDef* def = nullptr;
};
struct Member {
  std::string name;
  Type type;
};
struct StructDef {
  std::string name;
  std::vector<Member> members;
};

Type Sc(const std::string& base) { return Type{Type::Scalar, base}; }
Type Vec(const std::string& base, uint32_t n) { return Type{Type::Vector, base, 1, n}; }
Type Mat(uint32_t r, uint32_t c, bool rowMajor) { return Type{Type::Matrix, "float", r, c, rowMajor}; }
Type St(const StructDef& d) { return Type{Type::Struct, "", 1, 1, false, 0, &d}; }
Type Arr(Type t, uint32_t n) {
  t.count = n;
  return t;
}

uint32_t Round16(uint32_t v) { return (v + 15) / 16 * 16; }
std::vector<uint32_t> Offsets(const std::vector<Member>& members);
uint32_t Size(const Type& t);
uint32_t StructSize(const StructDef& d) {
  std::vector<uint32_t> o = Offsets(d.members);
  return o.empty() ? 0 : o.back() + Size(d.members.back().type);
}
uint32_t ElementSize(const Type& t) {
  switch (t.kind) {
    case Type::Scalar:
      return 4;
    case Type::Vector:
      return 4 * t.cols;
    case Type::Matrix:
      return t.rowMajor ? (t.rows - 1) * 16 + t.cols * 4 : (t.cols - 1) * 16 + t.rows * 4;
    case Type::Struct:
      return StructSize(*t.def);
  }
  return 0;
}
uint32_t Size(const Type& t) { return t.count ? (t.count - 1) * Round16(ElementSize(t)) + ElementSize(t) : ElementSize(t); }
std::vector<uint32_t> Offsets(const std::vector<Member>& members) {
  std::vector<uint32_t> out;
  uint32_t cursor = 0;
  for (const Member& m : members) {
    uint32_t size = Size(m.type);
    bool startsRegister = m.type.count || m.type.kind == Type::Struct;
    if (startsRegister || cursor % 16 + size > 16) cursor = Round16(cursor);
    out.push_back(cursor);
    cursor += size;
  }
  return out;
}

// One scalar the shader reads: its HLSL expression and byte offset.
struct Leaf {
  std::string expr;
  uint32_t offset;
  std::string base;
};
void LeavesOfElement(const Type& t, const std::string& expr, uint32_t offset, std::vector<Leaf>& out);
void LeavesOf(const Type& t, const std::string& expr, uint32_t offset, std::vector<Leaf>& out) {
  if (!t.count) return LeavesOfElement(t, expr, offset, out);
  for (uint32_t i = 0; i < t.count; ++i) LeavesOfElement(t, expr + "[" + std::to_string(i) + "]", offset + i * Round16(ElementSize(t)), out);
}
void LeavesOfElement(const Type& t, const std::string& expr, uint32_t offset, std::vector<Leaf>& out) {
  switch (t.kind) {
    case Type::Scalar:
      out.push_back({expr, offset, t.base});
      break;
    case Type::Vector:
      for (uint32_t i = 0; i < t.cols; ++i) out.push_back({expr + "." + "xyzw"[i], offset + 4 * i, t.base});
      break;
    case Type::Matrix:
      for (uint32_t r = 0; r < t.rows; ++r)
        for (uint32_t c = 0; c < t.cols; ++c)
          out.push_back(
              {expr + "[" + std::to_string(r) + "][" + std::to_string(c) + "]", offset + (t.rowMajor ? r * 16 + c * 4 : c * 16 + r * 4), "float"});
      break;
    case Type::Struct: {
      std::vector<uint32_t> o = Offsets(t.def->members);
      for (size_t i = 0; i < o.size(); ++i) LeavesOf(t.def->members[i].type, expr + "." + t.def->members[i].name, offset + o[i], out);
      break;
    }
  }
}

std::string TypeName(const Type& t) {
  switch (t.kind) {
    case Type::Scalar:
      return t.base;
    case Type::Vector:
      return t.base + std::to_string(t.cols);
    case Type::Matrix:
      return std::string(t.rowMajor ? "row_major " : "column_major ") + "float" + std::to_string(t.rows) + "x" + std::to_string(t.cols);
    case Type::Struct:
      return t.def->name;
  }
  return "";
}
std::string Declare(const Member& m) {
  return TypeName(m.type) + " " + m.name + (m.type.count ? "[" + std::to_string(m.type.count) + "]" : "") + ";";
}

struct Layout {
  std::vector<const StructDef*> structs;  // in declaration order
  std::vector<Member> members;
};

const char* kReaders = R"(
RWStructuredBuffer<uint> output : register(u0);
[numthreads(64, 1, 1)] void CSMain(uint i : SV_DispatchThreadID) { if (i < kLeaves) output[i] = Leaf(i); }
struct V { float4 pos : SV_Position; nointerpolation uint value : VALUE; };
V VSMain(uint id : SV_VertexID) {
  V o;
  o.pos = float4((id + 0.5) / kLeaves * 2 - 1, 0, 0.5, 1);
  o.value = Leaf(id);
  return o;
}
uint PSPass(V v) : SV_Target { return v.value; }
float4 VSFullscreen(uint id : SV_VertexID) : SV_Position {
  float2 p = float2((id << 1) & 2, id & 2);
  return float4(p * float2(2, -2) + float2(-1, 1), 0, 1);
}
uint PSMain(float4 p : SV_Position) : SV_Target { return Leaf(uint(p.x)); }
)";

std::string Source(const Layout& l, const std::vector<Leaf>& leaves) {
  std::ostringstream s;
  for (const StructDef* d : l.structs) {
    s << "struct " << d->name << " {";
    for (const Member& m : d->members) s << " " << Declare(m);
    s << " };\n";
  }
  s << "cbuffer Packed : register(b1) {\n";
  for (const Member& m : l.members) s << "  " << Declare(m) << "\n";
  s << "};\nstatic const uint kLeaves = " << leaves.size() << ";\nuint Leaf(uint leafIndex) {\n  uint leafValues[kLeaves] = {";
  for (size_t i = 0; i < leaves.size(); ++i)
    s << (i ? ", " : "") << (leaves[i].base == "bool" ? "(" + leaves[i].expr + " ? 1u : 0u)" : "asuint(" + leaves[i].expr + ")");
  s << "};\n  return leafValues[leafIndex];\n}\n" << kReaders;
  return s.str();
}

// The buffer contents: poison everywhere, a distinct value at each leaf; `expected` is what the
// shader must output for each leaf.
uint32_t BufferSize(const Layout& l) {
  std::vector<uint32_t> o = Offsets(l.members);
  return Round16(o.back() + Size(l.members.back().type));
}
std::vector<uint32_t> Fill(const Layout& l, const std::vector<Leaf>& leaves, uint32_t seed, std::vector<uint32_t>* expected) {
  std::vector<uint32_t> words(BufferSize(l) / 4);
  for (uint32_t i = 0; i < words.size(); ++i) words[i] = 0x7f000000u + i;  // a large finite float, nonzero int
  expected->clear();
  for (uint32_t j = 0; j < leaves.size(); ++j) {
    const std::string& b = leaves[j].base;
    uint32_t v;
    if (b == "float") {
      float f = float(j + seed) * 1.25f + 0.5f;
      std::memcpy(&v, &f, 4);
    } else if (b == "int") {
      v = uint32_t(-int32_t(j + seed) * 1000 - 7);
    } else if (b == "uint") {
      v = 0x9e370000u + j + seed;
    } else {
      v = (j + seed) % 3 != 1 ? 1u : 0u;
    }
    words[leaves[j].offset / 4] = v;
    expected->push_back(v);
  }
  return words;
}

std::vector<Leaf> AllLeaves(const Layout& l) {
  std::vector<Leaf> leaves;
  std::vector<uint32_t> o = Offsets(l.members);
  for (size_t i = 0; i < o.size(); ++i) LeavesOf(l.members[i].type, l.members[i].name, o[i], leaves);
  return leaves;
}

// Runs the compute reader over `layout` with a buffer of `boundBytes` (0: the whole layout);
// leaves beyond a short buffer must read 0, as D3D11 defines out-of-bounds cbuffer reads.
Result CheckCompute(Device& device, const Layout& layout, const std::string& name, uint32_t boundBytes = 0) {
  DeviceContext& ctx = *device.GetImmediateContext();
  std::vector<Leaf> leaves = AllLeaves(layout);
  std::vector<uint32_t> expected;
  std::vector<uint32_t> words = Fill(layout, leaves, 3, &expected);
  uint32_t bytes = boundBytes ? boundBytes : uint32_t(words.size() * 4);
  Ref<Buffer> cb = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, words.data(), bytes);
  BufferViews out = MakeStructured(device, uint32_t(leaves.size()), 4);
  Ref<ComputeShader> cs = MakeCS(device, Source(layout, leaves), "cbuffer-" + name, "CSMain");
  ctx.CSSetShader(cs.get());
  ctx.CSSetConstantBuffers(1, {cb.get()});
  ctx.CSSetUnorderedAccessViews(0, {out.uav.get()});
  ctx.Dispatch((uint32_t(leaves.size()) + 63) / 64, 1, 1);
  std::vector<uint32_t> got = ReadBufferAs<uint32_t>(device, out.buffer.get());
  Mismatches m("members");
  for (size_t j = 0; j < leaves.size(); ++j) {
    bool inside = leaves[j].offset + 4 <= bytes;
    m.Check(got[j], inside ? expected[j] : 0u,
            leaves[j].expr + " (offset " + std::to_string(leaves[j].offset) + (inside ? ")" : ", beyond the buffer)"));
  }
  return m.Finish("members");
}

// --- The layouts

const StructDef kS1{"S1", {{"a", Sc("float")}, {"b", Vec("float", 3)}, {"c", Vec("float", 2)}}};
const StructDef kS2{"S2", {{"p", Vec("float", 2)}, {"inner", St(kS1)}, {"q", Sc("float")}}};

Layout Vectors() {
  return {{},
          {{"a", Sc("float")},
           {"b", Vec("float", 3)},
           {"c", Vec("float", 2)},
           {"d", Vec("float", 2)},
           {"e", Sc("float")},
           {"f", Vec("float", 3)},
           {"g", Vec("float", 2)},
           {"h", Vec("float", 3)},
           {"i", Sc("float")},
           {"j", Vec("float", 4)},
           {"k", Sc("float")},
           {"l", Vec("float", 2)},
           {"m", Vec("float", 2)},
           {"n", Sc("float")}}};
}
Layout Arrays() {
  return {{},
          {{"a", Sc("float")},
           {"arr", Arr(Sc("float"), 3)},
           {"b", Sc("float")},
           {"v2", Arr(Vec("float", 2), 2)},
           {"c", Sc("float")},
           {"v3", Arr(Vec("float", 3), 2)},
           {"d", Sc("float")},
           {"ia", Arr(Sc("int"), 2)},
           {"ub", Sc("uint")},
           {"v4", Arr(Vec("float", 4), 2)},
           {"e", Sc("float")}}};
}
Layout Structs() {
  return {{&kS1, &kS2},
          {{"x", Sc("float")},
           {"s", St(kS1)},
           {"y", Sc("float")},
           {"arr", Arr(St(kS1), 2)},
           {"z", Sc("float")},
           {"nested", St(kS2)},
           {"w", Sc("float")}}};
}
Layout Matrices(bool rowMajor) {
  Layout l;
  for (uint32_t r = 2; r <= 4; ++r)
    for (uint32_t c = 2; c <= 4; ++c) {
      std::string n = std::to_string(r) + std::to_string(c);
      l.members.push_back({"m" + n, Mat(r, c, rowMajor)});
      l.members.push_back({"f" + n, Sc("float")});
    }
  l.members.push_back({"marr", Arr(Mat(rowMajor ? 2 : 3, rowMajor ? 3 : 2, rowMajor), 2)});
  l.members.push_back({"tail", Sc("float")});
  return l;
}
Layout Scalars() {
  return {{},
          {{"b0", Sc("bool")},
           {"i0", Sc("int")},
           {"u0", Sc("uint")},
           {"b2", Vec("bool", 2)},
           {"i3", Vec("int", 3)},
           {"u1", Sc("uint")},
           {"b3", Vec("bool", 3)},
           {"i1", Sc("int")},
           {"u2", Vec("uint", 2)},
           {"b4", Sc("bool")},
           {"i4", Vec("int", 4)},
           {"u3", Sc("uint")}}};
}
Layout Mixed() {
  Layout l{{&kS1}, {}};
  for (const Layout& part : {Vectors(), Arrays(), Scalars()})
    for (const Member& m : part.members) l.members.push_back({m.name + "_" + std::to_string(l.members.size()), m.type});
  l.members.push_back({"s", St(kS1)});
  l.members.push_back({"m", Mat(3, 3, false)});
  l.members.push_back({"r", Mat(2, 3, true)});
  l.members.push_back({"last", Sc("float")});
  return l;
}

}  // namespace

SP_PROBE(kGroup, "packing: float3 after a float, float2/float3 never straddle a register",
         "vectors pack into the current 16-byte register when they fit and start the next one otherwise") {
  return CheckCompute(device, Vectors(), "vectors");
}
SP_PROBE(kGroup, "packing: arrays padded to 16 bytes per element, a float packs after the last",
         "every array element starts a register; the member after an array packs into the last element's register") {
  return CheckCompute(device, Arrays(), "arrays");
}
SP_PROBE(kGroup, "packing: structs, arrays of structs, nested structs",
         "structs start a register, are not padded at the end, and the next member packs into their last register") {
  return CheckCompute(device, Structs(), "structs");
}
SP_PROBE(kGroup, "packing: column_major matrices 2x2..4x4, a float after each",
         "a column_major floatRxC takes C registers of R components; the next float packs after the last column") {
  return CheckCompute(device, Matrices(false), "column-major");
}
SP_PROBE(kGroup, "packing: row_major matrices 2x2..4x4, a float after each",
         "a row_major floatRxC takes R registers of C components; the next float packs after the last row") {
  return CheckCompute(device, Matrices(true), "row-major");
}
SP_PROBE(kGroup, "packing: bool, int and uint scalars and vectors", "bool/int/uint members are 4 bytes each and pack like floats") {
  return CheckCompute(device, Scalars(), "scalars");
}

SP_PROBE(kGroup, "reflection reports D3D11's member offsets and cbuffer sizes",
         "the toolchain's reflection gives the offsets and size fxc's packing rules give") {
  Mismatches m("offsets");
  struct Named {
    const char* name;
    Layout layout;
  };
  for (const Named& n : {Named{"vectors", Vectors()}, Named{"arrays", Arrays()}, Named{"structs", Structs()}, Named{"column-major", Matrices(false)},
                         Named{"row-major", Matrices(true)}, Named{"scalars", Scalars()}, Named{"mixed", Mixed()}}) {
    ShaderBytecode b =
        gpu::CompileInline(Source(n.layout, AllLeaves(n.layout)), std::string("conformance/cbuffer-") + n.name + ".hlsl", "cs_5_0", "CSMain");
    const CBufferInfo* cb = b.reflection.FindCBuffer(1);
    if (!cb) return Fail(std::string("no cbuffer at b1 in the reflection of the ") + n.name + " layout");
    m.Check(cb->size, BufferSize(n.layout), std::string(n.name) + ": cbuffer size");
    std::map<std::string, uint32_t> reflected;
    for (const CBufferMember& mem : cb->members) reflected[mem.name] = mem.offset;
    std::vector<uint32_t> o = Offsets(n.layout.members);
    for (size_t i = 0; i < o.size(); ++i) {
      const std::string& name = n.layout.members[i].name;
      m.Expect(reflected.count(name) != 0, std::string(n.name) + ": member " + name + " missing from the reflection");
      if (reflected.count(name)) m.Check(reflected[name], o[i], std::string(n.name) + ": offset of " + name);
    }
  }
  return m.Finish("offsets");
}

SP_PROBE(kGroup, "vertex and pixel shaders read the same packing",
         "the packing is the same in every stage (VS output to a point per member, PS per pixel)") {
  DeviceContext& ctx = *device.GetImmediateContext();
  Layout layout = Mixed();
  std::vector<Leaf> leaves = AllLeaves(layout);
  std::vector<uint32_t> expected;
  std::vector<uint32_t> words = Fill(layout, leaves, 11, &expected);
  Ref<Buffer> cb = gpu::MakeBuffer(device, BIND_CONSTANT_BUFFER, words.data(), uint32_t(words.size() * 4));
  std::string src = Source(layout, leaves);
  uint32_t n = uint32_t(leaves.size());
  Mismatches m("members");
  {
    Ref<VertexShader> vs = MakeVS(device, src, "cbuffer-mixed", "VSMain");
    Ref<PixelShader> ps = MakePS(device, src, "cbuffer-mixed", "PSPass");
    DrawTarget t = MakeDrawTarget(device, n, 1, FORMAT_R32_UINT);
    t.Clear(ctx, 0);
    t.Bind(ctx);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_POINTLIST);
    ctx.VSSetShader(vs.get());
    ctx.PSSetShader(ps.get());
    ctx.VSSetConstantBuffers(1, {cb.get()});
    ctx.Draw(n, 0);
    std::vector<uint32_t> got = ReadTextureAs<uint32_t>(device, t.texture.get());
    for (uint32_t j = 0; j < n; ++j) m.Check(got[j], expected[j], "vertex shader: " + leaves[j].expr);
  }
  {
    Ref<VertexShader> vs = MakeVS(device, src, "cbuffer-mixed", "VSFullscreen");
    Ref<PixelShader> ps = MakePS(device, src, "cbuffer-mixed", "PSMain");
    DrawTarget t = MakeDrawTarget(device, n, 2, FORMAT_R32_UINT);
    t.Bind(ctx);
    ctx.IASetPrimitiveTopology(PRIMITIVE_TOPOLOGY_TRIANGLELIST);
    ctx.VSSetShader(vs.get());
    ctx.PSSetShader(ps.get());
    ctx.PSSetConstantBuffers(1, {cb.get()});
    ctx.Draw(3, 0);
    std::vector<uint32_t> got = ReadTextureAs<uint32_t>(device, t.texture.get());
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t j = 0; j < n; ++j) m.Check(got[y * n + j], expected[j], "pixel shader: " + leaves[j].expr);
  }
  return m.Finish("members");
}

SP_PROBE(kGroup, "a buffer smaller than the cbuffer reads 0 beyond its end",
         "D3D11 defines out-of-bounds constant-buffer reads to return 0 (the debug layer only warns)") {
  return CheckCompute(device, Vectors(), "vectors", 48);
}

}  // namespace sp::conformance
