// ShaderBytecode: reflection lookups, the JSON form of reflection (hlslc's out.json, the shader
// cache) and the single-blob form used by Create*Shader(void*, size).
#include <sp/rhi/shader.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "bytecode-json.h"
#include "shader-bindings.h"

namespace sp {

using nlohmann::json;

const char* ShaderStageName(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return "vertex";
    case ShaderStage::Pixel: return "pixel";
    case ShaderStage::Geometry: return "geometry";
    case ShaderStage::Compute: return "compute";
  }
  return "?";
}

const char* ShaderStagePrefix(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return "VS";
    case ShaderStage::Pixel: return "PS";
    case ShaderStage::Geometry: return "GS";
    case ShaderStage::Compute: return "CS";
  }
  return "?";
}

char RegisterClassLetter(RegisterClass c) {
  switch (c) {
    case RegisterClass::ConstantBuffer: return 'b';
    case RegisterClass::ShaderResource: return 't';
    case RegisterClass::Sampler: return 's';
    case RegisterClass::UnorderedAccess: return 'u';
  }
  return '?';
}

const char* ShaderResourceTypeName(ShaderResourceType t) {
  switch (t) {
    case ShaderResourceType::ConstantBuffer: return "ConstantBuffer";
    case ShaderResourceType::Texture: return "Texture";
    case ShaderResourceType::TypedBuffer: return "TypedBuffer";
    case ShaderResourceType::StructuredBuffer: return "StructuredBuffer";
    case ShaderResourceType::ByteAddressBuffer: return "ByteAddressBuffer";
    case ShaderResourceType::Sampler: return "Sampler";
    case ShaderResourceType::ComparisonSampler: return "ComparisonSampler";
    case ShaderResourceType::RWTexture: return "RWTexture";
    case ShaderResourceType::RWTypedBuffer: return "RWTypedBuffer";
    case ShaderResourceType::RWStructuredBuffer: return "RWStructuredBuffer";
    case ShaderResourceType::RWByteAddressBuffer: return "RWByteAddressBuffer";
    case ShaderResourceType::UavCounter: return "UavCounter";
  }
  return "?";
}

const CBufferInfo* ShaderReflection::FindCBuffer(uint32_t reg) const {
  for (const CBufferInfo& c : cbuffers)
    if (c.registerIndex == reg) return &c;
  return nullptr;
}

const ShaderResourceBinding* ShaderReflection::FindResource(RegisterClass cls, uint32_t reg) const {
  for (const ShaderResourceBinding& r : resources)
    if (r.registerClass == cls && r.registerIndex == reg && r.type != ShaderResourceType::UavCounter) return &r;
  return nullptr;
}

const SignatureElement* ShaderReflection::FindInput(std::string_view semantic, uint32_t index) const {
  for (const SignatureElement& e : inputs)
    if (e.semanticName == semantic && e.semanticIndex == index) return &e;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// JSON

namespace {

template <class E>
struct Names {
  E value;
  const char* name;
};

const Names<ShaderResourceType> kTypeNames[] = {
    {ShaderResourceType::ConstantBuffer, "ConstantBuffer"},   {ShaderResourceType::Texture, "Texture"},
    {ShaderResourceType::TypedBuffer, "TypedBuffer"},         {ShaderResourceType::StructuredBuffer, "StructuredBuffer"},
    {ShaderResourceType::ByteAddressBuffer, "ByteAddressBuffer"}, {ShaderResourceType::Sampler, "Sampler"},
    {ShaderResourceType::ComparisonSampler, "ComparisonSampler"}, {ShaderResourceType::RWTexture, "RWTexture"},
    {ShaderResourceType::RWTypedBuffer, "RWTypedBuffer"},     {ShaderResourceType::RWStructuredBuffer, "RWStructuredBuffer"},
    {ShaderResourceType::RWByteAddressBuffer, "RWByteAddressBuffer"}, {ShaderResourceType::UavCounter, "UavCounter"}};

const Names<SRV_DIMENSION> kDimNames[] = {
    {SRV_DIMENSION_UNKNOWN, "UNKNOWN"},           {SRV_DIMENSION_BUFFER, "BUFFER"},
    {SRV_DIMENSION_TEXTURE1D, "TEXTURE1D"},       {SRV_DIMENSION_TEXTURE1DARRAY, "TEXTURE1DARRAY"},
    {SRV_DIMENSION_TEXTURE2D, "TEXTURE2D"},       {SRV_DIMENSION_TEXTURE2DARRAY, "TEXTURE2DARRAY"},
    {SRV_DIMENSION_TEXTURE2DMS, "TEXTURE2DMS"},   {SRV_DIMENSION_TEXTURE2DMSARRAY, "TEXTURE2DMSARRAY"},
    {SRV_DIMENSION_TEXTURE3D, "TEXTURE3D"},       {SRV_DIMENSION_TEXTURECUBE, "TEXTURECUBE"},
    {SRV_DIMENSION_TEXTURECUBEARRAY, "TEXTURECUBEARRAY"}, {SRV_DIMENSION_BUFFEREX, "BUFFEREX"}};

const Names<ComponentType> kCompNames[] = {{ComponentType::Float, "float"},
                                           {ComponentType::UInt, "uint"},
                                           {ComponentType::SInt, "int"},
                                           {ComponentType::Unknown, "unknown"}};

const Names<GlBindingKind> kGlKindNames[] = {{GlBindingKind::CombinedSampler, "combined-sampler"},
                                             {GlBindingKind::UniformBlock, "uniform-block"},
                                             {GlBindingKind::StorageBlock, "storage-block"},
                                             {GlBindingKind::Image, "image"}};

const Names<ShaderStage> kStageNames[] = {{ShaderStage::Vertex, "vertex"},
                                          {ShaderStage::Pixel, "pixel"},
                                          {ShaderStage::Geometry, "geometry"},
                                          {ShaderStage::Compute, "compute"}};

template <class E, size_t N>
const char* NameOf(const Names<E> (&table)[N], E v) {
  for (const auto& n : table)
    if (n.value == v) return n.name;
  return "?";
}

template <class E, size_t N>
E ValueOf(const Names<E> (&table)[N], const std::string& s) {
  for (const auto& n : table)
    if (s == n.name) return n.value;
  throw Error(ErrorId::INVALID_ARGUMENT, "ShaderBytecode::Deserialize", "reflection", "unknown name '" + s + "'");
}

RegisterClass ClassOf(const std::string& s) {
  if (s == "b") return RegisterClass::ConstantBuffer;
  if (s == "t") return RegisterClass::ShaderResource;
  if (s == "s") return RegisterClass::Sampler;
  if (s == "u") return RegisterClass::UnorderedAccess;
  throw Error(ErrorId::INVALID_ARGUMENT, "ShaderBytecode::Deserialize", "reflection", "unknown register class '" + s + "'");
}

json SignatureToJson(const std::vector<SignatureElement>& sig) {
  json a = json::array();
  for (const SignatureElement& e : sig) {
    a.push_back({{"semantic", e.semanticName},
                 {"index", e.semanticIndex},
                 {"location", e.location},
                 {"componentType", NameOf(kCompNames, e.componentType)},
                 {"components", e.componentCount},
                 {"systemValue", e.systemValue}});
  }
  return a;
}

std::vector<SignatureElement> SignatureFromJson(const json& a) {
  std::vector<SignatureElement> v;
  for (const json& j : a) {
    SignatureElement e;
    e.semanticName = j.at("semantic").get<std::string>();
    e.semanticIndex = j.at("index").get<uint32_t>();
    e.location = j.at("location").get<uint32_t>();
    e.componentType = ValueOf(kCompNames, j.at("componentType").get<std::string>());
    e.componentCount = j.at("components").get<uint32_t>();
    e.systemValue = j.at("systemValue").get<bool>();
    v.push_back(e);
  }
  return v;
}

// SPIR-V variants travel in the JSON (the cache keeps three files per shader) as base64 words.
constexpr char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string WordsToBase64(const std::vector<uint32_t>& words) {
  std::string bytes(words.size() * 4, '\0');
  std::memcpy(bytes.data(), words.data(), bytes.size());
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= uint8_t(bytes[i + 2]);
    out += kBase64[(n >> 18) & 63];
    out += kBase64[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kBase64[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kBase64[n & 63] : '=';
  }
  return out;
}

std::vector<uint32_t> WordsFromBase64(const std::string& text) {
  std::string bytes;
  uint32_t n = 0;
  int bits = 0;
  for (char ch : text) {
    if (ch == '=') break;
    const char* at = std::strchr(kBase64, ch);
    if (!at || !ch) throw Error(ErrorId::INVALID_ARGUMENT, "ShaderBytecode::Deserialize", "SPIR-V variant", "not base64");
    n = (n << 6) | uint32_t(at - kBase64);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes += char((n >> bits) & 0xff);
    }
  }
  if (bytes.size() % 4) throw Error(ErrorId::INVALID_ARGUMENT, "ShaderBytecode::Deserialize", "SPIR-V variant", "not a whole number of words");
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  return words;
}

using VariantField = std::vector<uint32_t> detail::SpirvProducts::*;
const std::pair<const char*, VariantField> kVariantFields[] = {
    {"instanceFromZero", &detail::SpirvProducts::instanceFromZero},
    {"pointSize", &detail::SpirvProducts::pointSize},
    {"pointSizeInstanceFromZero", &detail::SpirvProducts::pointSizeInstanceFromZero},
    {"dualSource", &detail::SpirvProducts::dualSource}};

json RangesToJson(const std::vector<CBufferCopyRange>& ranges) {
  json rp = json::array();
  for (const CBufferCopyRange& c : ranges) rp.push_back({c.src, c.dst, c.size});
  return rp;
}

std::vector<CBufferCopyRange> RangesFromJson(const json& a) {
  std::vector<CBufferCopyRange> out;
  for (const json& c : a) out.push_back({c.at(0).get<uint32_t>(), c.at(1).get<uint32_t>(), c.at(2).get<uint32_t>()});
  return out;
}

json SpirvProductsToJson(const detail::SpirvProducts& p) {
  json j;
  j["entryPoint"] = p.entryPoint;
  json repacks = json::array();
  for (const CBufferRepack& r : p.repacks)
    repacks.push_back({{"register", "b" + std::to_string(r.reg)}, {"size", r.size}, {"ranges", RangesToJson(r.ranges)}});
  j["repacks"] = repacks;
  json pairs = json::array();
  for (const SampledPair& s : p.sampledPairs)
    pairs.push_back({{"texture", "t" + std::to_string(s.textureReg)}, {"sampler", "s" + std::to_string(s.samplerReg)}, {"filtered", s.filtered}, {"compared", s.compared}});
  j["sampledPairs"] = pairs;
  for (const auto& [name, field] : kVariantFields)
    if (!(p.*field).empty()) j["variants"][name] = WordsToBase64(p.*field);
  return j;
}

detail::SpirvProducts SpirvProductsFromJson(const json& j) {
  detail::SpirvProducts p;
  p.entryPoint = j.at("entryPoint").get<std::string>();
  for (const json& r : j.at("repacks"))
    p.repacks.push_back({uint32_t(std::stoul(r.at("register").get<std::string>().substr(1))), r.at("size").get<uint32_t>(), RangesFromJson(r.at("ranges"))});
  for (const json& s : j.at("sampledPairs"))
    p.sampledPairs.push_back({uint32_t(std::stoul(s.at("texture").get<std::string>().substr(1))), uint32_t(std::stoul(s.at("sampler").get<std::string>().substr(1))),
                              s.at("filtered").get<bool>(), s.at("compared").get<bool>()});
  if (j.contains("variants"))
    for (const auto& [name, field] : kVariantFields)
      if (j["variants"].contains(name)) p.*field = WordsFromBase64(j["variants"][name].get<std::string>());
  return p;
}

}  // namespace

std::string BytecodeToJson(const ShaderBytecode& b, const json& extra) {
  const ShaderReflection& r = b.reflection;
  json j;
  j["stage"] = NameOf(kStageNames, b.stage);
  j["source"] = b.sourceName;
  j["entryPoint"] = r.entryPoint;
  if (b.stage == ShaderStage::Compute) j["threadGroupSize"] = r.threadGroupSize;
  json cbs = json::array();
  for (const CBufferInfo& c : r.cbuffers) {
    json members = json::array();
    for (const CBufferMember& m : c.members)
      members.push_back({{"name", m.name}, {"type", m.typeName}, {"offset", m.offset}, {"size", m.size}});
    cbs.push_back({{"name", c.name}, {"register", "b" + std::to_string(c.registerIndex)}, {"size", c.size},
                   {"vkSet", c.vkSet}, {"vkBinding", c.vkBinding}, {"members", members}});
  }
  j["cbuffers"] = cbs;
  json res = json::array();
  for (const ShaderResourceBinding& x : r.resources) {
    json e = {{"name", x.name},
              {"register", std::string(1, RegisterClassLetter(x.registerClass)) + std::to_string(x.registerIndex)},
              {"type", NameOf(kTypeNames, x.type)},
              {"vkSet", x.vkSet},
              {"vkBinding", x.vkBinding}};
    if (x.dimension != SRV_DIMENSION_UNKNOWN) e["dimension"] = NameOf(kDimNames, x.dimension);
    if (x.type == ShaderResourceType::Texture || x.type == ShaderResourceType::TypedBuffer ||
        x.type == ShaderResourceType::RWTexture || x.type == ShaderResourceType::RWTypedBuffer)
      e["returnType"] = NameOf(kCompNames, x.returnType);
    if (x.structureStride) e["stride"] = x.structureStride;
    if (x.appendConsume) e["appendConsume"] = true;
    res.push_back(e);
  }
  j["resources"] = res;
  j["inputs"] = SignatureToJson(r.inputs);
  j["outputs"] = SignatureToJson(r.outputs);
  json gl = json::array();
  for (const GlBinding& g : detail::GlBindingsOf(b)) {
    json e = {{"kind", NameOf(kGlKindNames, g.kind)},
              {"binding", g.glBinding},
              {"register", std::string(1, RegisterClassLetter(g.registerClass)) + std::to_string(g.registerIndex)}};
    if (g.kind == GlBindingKind::CombinedSampler)
      e["sampler"] = g.samplerRegister < 0 ? json(nullptr) : json("s" + std::to_string(g.samplerRegister));
    if (g.uavCounter) e["uavCounter"] = true;
    if (g.kind == GlBindingKind::UniformBlock && !g.repack.empty()) {
      e["std140Size"] = g.glBlockSize;
      e["repack"] = RangesToJson(g.repack);
    }
    gl.push_back(e);
  }
  j["glBindings"] = gl;
  const detail::TargetProducts& targets = detail::TargetsOf(b);
  if (!targets.gl.dualSourceGlsl.empty()) j["glDualSource"] = targets.gl.dualSourceGlsl;
  j["vulkan"] = SpirvProductsToJson(targets.spirv);
  for (auto it = extra.begin(); it != extra.end(); ++it) j[it.key()] = it.value();
  return j.dump(2);
}

ShaderBytecode BytecodeFromJson(const std::string& text, std::vector<uint32_t> spirv, std::string glsl, json* extra) {
  json j = json::parse(text);
  ShaderBytecode b;
  b.stage = ValueOf(kStageNames, j.at("stage").get<std::string>());
  b.sourceName = j.at("source").get<std::string>();
  ShaderReflection& r = b.reflection;
  r.stage = b.stage;
  r.entryPoint = j.at("entryPoint").get<std::string>();
  if (j.contains("threadGroupSize")) r.threadGroupSize = j["threadGroupSize"].get<std::array<uint32_t, 3>>();
  for (const json& c : j.at("cbuffers")) {
    CBufferInfo info;
    info.name = c.at("name").get<std::string>();
    info.registerIndex = std::stoul(c.at("register").get<std::string>().substr(1));
    info.size = c.at("size").get<uint32_t>();
    info.vkSet = c.at("vkSet").get<uint32_t>();
    info.vkBinding = c.at("vkBinding").get<uint32_t>();
    for (const json& m : c.at("members"))
      info.members.push_back({m.at("name").get<std::string>(), m.at("type").get<std::string>(), m.at("offset").get<uint32_t>(),
                              m.at("size").get<uint32_t>()});
    r.cbuffers.push_back(std::move(info));
  }
  for (const json& e : j.at("resources")) {
    ShaderResourceBinding x;
    x.name = e.at("name").get<std::string>();
    std::string reg = e.at("register").get<std::string>();
    x.registerClass = ClassOf(reg.substr(0, 1));
    x.registerIndex = std::stoul(reg.substr(1));
    x.type = ValueOf(kTypeNames, e.at("type").get<std::string>());
    x.vkSet = e.at("vkSet").get<uint32_t>();
    x.vkBinding = e.at("vkBinding").get<uint32_t>();
    if (e.contains("dimension")) x.dimension = ValueOf(kDimNames, e["dimension"].get<std::string>());
    if (e.contains("returnType")) x.returnType = ValueOf(kCompNames, e["returnType"].get<std::string>());
    if (e.contains("stride")) x.structureStride = e["stride"].get<uint32_t>();
    if (e.contains("appendConsume")) x.appendConsume = e["appendConsume"].get<bool>();
    r.resources.push_back(std::move(x));
  }
  r.inputs = SignatureFromJson(j.at("inputs"));
  r.outputs = SignatureFromJson(j.at("outputs"));
  detail::TargetProducts targets;
  std::vector<GlBinding>& glBindings = targets.gl.bindings;
  for (const json& e : j.at("glBindings")) {
    GlBinding g;
    g.kind = ValueOf(kGlKindNames, e.at("kind").get<std::string>());
    g.glBinding = e.at("binding").get<uint32_t>();
    std::string reg = e.at("register").get<std::string>();
    g.registerClass = ClassOf(reg.substr(0, 1));
    g.registerIndex = std::stoul(reg.substr(1));
    if (e.contains("sampler") && !e["sampler"].is_null()) g.samplerRegister = std::stoi(e["sampler"].get<std::string>().substr(1));
    if (e.contains("uavCounter")) g.uavCounter = e["uavCounter"].get<bool>();
    if (e.contains("repack")) {
      g.glBlockSize = e.at("std140Size").get<uint32_t>();
      g.repack = RangesFromJson(e["repack"]);
    }
    glBindings.push_back(std::move(g));
  }
  if (j.contains("glDualSource")) targets.gl.dualSourceGlsl = j["glDualSource"].get<std::string>();
  targets.spirv = SpirvProductsFromJson(j.at("vulkan"));
  detail::SetTargets(b, std::move(targets));
  b.spirv = std::move(spirv);
  b.glsl = std::move(glsl);
  if (extra) *extra = j;
  return b;
}

std::string ShaderBytecode::ReflectionJson() const { return BytecodeToJson(*this, json::object()); }

// Blob layout: "SPBC", version, then three length-prefixed sections: reflection JSON, SPIR-V
// words, GLSL text. Little-endian, as every platform ShadowPort runs on.
static constexpr uint32_t kMagic = 0x43425053;  // "SPBC"
// Version 2: the reflection JSON carries the per-target products (its "vulkan" section).
static constexpr uint32_t kVersion = 2;

std::vector<uint8_t> ShaderBytecode::Serialize() const {
  std::string js = ReflectionJson();
  std::vector<uint8_t> out;
  auto put32 = [&](uint32_t v) {
    uint8_t b[4];
    std::memcpy(b, &v, 4);
    out.insert(out.end(), b, b + 4);
  };
  auto putBytes = [&](const void* p, size_t n) {
    put32(uint32_t(n));
    const uint8_t* c = static_cast<const uint8_t*>(p);
    out.insert(out.end(), c, c + n);
  };
  put32(kMagic);
  put32(kVersion);
  putBytes(js.data(), js.size());
  putBytes(spirv.data(), spirv.size() * 4);
  putBytes(glsl.data(), glsl.size());
  return out;
}

ShaderBytecode ShaderBytecode::Deserialize(const void* data, size_t size) {
  const uint8_t* p = static_cast<const uint8_t*>(data);
  size_t pos = 0;
  auto fail = [](const std::string& why) -> void {
    throw Error(ErrorId::INVALID_ARGUMENT, "ShaderBytecode::Deserialize", "bytecode blob", why);
  };
  auto get32 = [&]() {
    if (pos + 4 > size) fail("truncated blob");
    uint32_t v;
    std::memcpy(&v, p + pos, 4);
    pos += 4;
    return v;
  };
  auto getBytes = [&]() {
    uint32_t n = get32();
    if (pos + n > size) fail("truncated blob");
    std::string s(reinterpret_cast<const char*>(p + pos), n);
    pos += n;
    return s;
  };
  if (!data) fail("null data");
  if (get32() != kMagic) fail("not a ShadowPort bytecode blob (bad magic); compile HLSL with sp::hlsl::Compile or shadowport hlslc");
  if (get32() != kVersion) fail("unsupported bytecode blob version");
  std::string js = getBytes();
  std::string spv = getBytes();
  std::string glsl = getBytes();
  if (spv.size() % 4) fail("SPIR-V section is not a whole number of words");
  std::vector<uint32_t> words(spv.size() / 4);
  std::memcpy(words.data(), spv.data(), spv.size());
  try {
    return BytecodeFromJson(js, std::move(words), std::move(glsl), nullptr);
  } catch (const json::exception& e) {
    fail(std::string("reflection JSON is malformed: ") + e.what());
  }
  return {};
}

namespace detail {

const TargetProducts& TargetsOf(const ShaderBytecode& b) {
  static const TargetProducts kNone;
  return b.targets ? *b.targets : kNone;
}

void SetTargets(ShaderBytecode& b, TargetProducts products) { b.targets = std::make_shared<const TargetProducts>(std::move(products)); }

const std::vector<uint32_t>& SpirvFor(const ShaderBytecode& b, SpirvVariant v) {
  const SpirvProducts& p = TargetsOf(b).spirv;
  if (v.dualSource && !p.dualSource.empty()) return p.dualSource;
  if (v.pointSize && v.instanceFromZero && !p.pointSizeInstanceFromZero.empty()) return p.pointSizeInstanceFromZero;
  if (v.pointSize && !p.pointSize.empty()) return p.pointSize;
  if (v.instanceFromZero && !p.instanceFromZero.empty()) return p.instanceFromZero;
  return b.spirv;
}

const std::vector<GlBinding>& GlBindingsOf(const ShaderBytecode& b) { return TargetsOf(b).gl.bindings; }

bool TextureIsCompared(const ShaderBytecode& b, uint32_t textureRegister) {
  for (const GlBinding& g : GlBindingsOf(b)) {
    if (g.kind != GlBindingKind::CombinedSampler || g.registerIndex != textureRegister || g.samplerRegister < 0) continue;
    const ShaderResourceBinding* s = b.reflection.FindResource(RegisterClass::Sampler, uint32_t(g.samplerRegister));
    if (s && s->type == ShaderResourceType::ComparisonSampler) return true;
  }
  return false;
}

}  // namespace detail
}  // namespace sp
