#include "spirv-edit.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <map>
#include <spirv/unified1/spirv.hpp>
#include <string>
#include <unordered_map>

namespace sp::hlsl {
namespace {

constexpr size_t kHeaderWords = 5;

// Iterates instructions: fn(opcode, wordCount, pointer to first word).
template <class Fn>
void ForEach(std::vector<uint32_t>& spirv, Fn fn) {
  for (size_t i = kHeaderWords; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16;
    if (wc == 0) break;
    fn(spv::Op(spirv[i] & 0xffff), wc, &spirv[i]);
    i += wc;
  }
}

template <class Fn>
void ForEachConst(const std::vector<uint32_t>& spirv, Fn fn) {
  for (size_t i = kHeaderWords; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16;
    if (wc == 0) break;
    fn(spv::Op(spirv[i] & 0xffff), wc, &spirv[i]);
    i += wc;
  }
}

// Word index (within the instruction) of the image-operands mask, or 0 when the opcode has none.
uint32_t ImageOperandsIndex(spv::Op op) {
  switch (op) {
    // result type, result, sampled image, coordinate, [mask]
    case spv::OpImageSampleImplicitLod:
    case spv::OpImageSampleExplicitLod:
    case spv::OpImageSampleProjImplicitLod:
    case spv::OpImageSampleProjExplicitLod:
    case spv::OpImageFetch:
    case spv::OpImageRead:
      return 5;
    // ... with a Dref or component operand before the mask
    case spv::OpImageSampleDrefImplicitLod:
    case spv::OpImageSampleDrefExplicitLod:
    case spv::OpImageSampleProjDrefImplicitLod:
    case spv::OpImageSampleProjDrefExplicitLod:
    case spv::OpImageGather:
    case spv::OpImageDrefGather:
      return 6;
    default:
      return 0;
  }
}

// Number of id operands that follow each image-operand bit (in bit order).
uint32_t OperandWords(uint32_t bit) {
  switch (bit) {
    case spv::ImageOperandsGradMask: return 2;
    default: return 1;
  }
}

// Follows OpLoad / OpAccessChain / OpCopyObject back to the variable an id was loaded from.
uint32_t RootVariable(const std::unordered_map<uint32_t, const uint32_t*>& defs, uint32_t id) {
  for (int guard = 0; guard < 16; ++guard) {
    auto it = defs.find(id);
    if (it == defs.end()) return 0;
    const uint32_t* in = it->second;
    spv::Op op = spv::Op(in[0] & 0xffff);
    if (op == spv::OpVariable) return id;
    if (op == spv::OpLoad || op == spv::OpAccessChain || op == spv::OpInBoundsAccessChain || op == spv::OpCopyObject) {
      id = in[3];
      continue;
    }
    return 0;
  }
  return 0;
}

std::unordered_map<uint32_t, const uint32_t*> ResultDefinitions(const std::vector<uint32_t>& spirv) {
  std::unordered_map<uint32_t, const uint32_t*> defs;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    switch (op) {
      case spv::OpVariable:
      case spv::OpLoad:
      case spv::OpAccessChain:
      case spv::OpInBoundsAccessChain:
      case spv::OpCopyObject:
      case spv::OpSampledImage:
      case spv::OpImage:
        if (wc >= 3) defs[in[2]] = in;
        break;
      default:
        break;
    }
  });
  return defs;
}

}  // namespace

void ConstOffsetsFromConstants(std::vector<uint32_t>& spirv) {
  std::vector<bool> isConst(spirv.size() > 3 ? spirv[3] : 0, false);
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    if ((op == spv::OpConstant || op == spv::OpConstantComposite || op == spv::OpConstantNull) && in[2] < isConst.size())
      isConst[in[2]] = true;
  });
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    uint32_t maskIdx = ImageOperandsIndex(op);
    if (!maskIdx || maskIdx >= wc) return;
    uint32_t mask = in[maskIdx];
    if (!(mask & spv::ImageOperandsOffsetMask)) return;
    uint32_t idx = maskIdx + 1;
    for (uint32_t bit = 1; bit < spv::ImageOperandsOffsetMask; bit <<= 1)
      if (mask & bit) idx += OperandWords(bit);
    if (idx < wc && in[idx] < isConst.size() && isConst[in[idx]])
      in[maskIdx] = (mask & ~uint32_t(spv::ImageOperandsOffsetMask)) | spv::ImageOperandsConstOffsetMask;
  });
}

void RemapCounterBindings(std::vector<uint32_t>& spirv, uint32_t uavBase, uint32_t counterBase) {
  std::unordered_map<uint32_t, uint32_t> binding;        // variable -> binding
  std::unordered_map<uint32_t, uint32_t> counterOf;      // counter variable -> buffer variable
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    if (op == spv::OpDecorate && wc >= 4 && in[2] == spv::DecorationBinding) binding[in[1]] = in[3];
    if (op == spv::OpDecorateId && wc >= 4 && in[2] == spv::DecorationHlslCounterBufferGOOGLE) counterOf[in[3]] = in[1];
  });
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    if (op != spv::OpDecorate || wc < 4 || in[2] != spv::DecorationBinding) return;
    auto it = counterOf.find(in[1]);
    if (it == counterOf.end()) return;
    uint32_t owner = binding[it->second];
    if (owner >= uavBase) in[3] = counterBase + (owner - uavBase);
  });
}

void ShiftUnshiftedTextureBindings(std::vector<uint32_t>& spirv, uint32_t textureBase) {
  std::set<uint32_t> sampledImages;                     // OpTypeImage with Sampled = 1
  std::unordered_map<uint32_t, uint32_t> arrayElement;  // OpTypeArray -> element type
  std::unordered_map<uint32_t, uint32_t> pointee;       // UniformConstant pointer -> type
  std::set<uint32_t> textures;                          // variables of (arrays of) sampled images
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    if (op == spv::OpTypeImage && wc >= 9 && in[7] == 1) sampledImages.insert(in[1]);
    if ((op == spv::OpTypeArray || op == spv::OpTypeRuntimeArray) && wc >= 3) arrayElement[in[1]] = in[2];
    if (op == spv::OpTypePointer && wc >= 4 && in[2] == spv::StorageClassUniformConstant) pointee[in[1]] = in[3];
    if (op == spv::OpVariable && wc >= 4 && in[3] == spv::StorageClassUniformConstant) {
      auto p = pointee.find(in[1]);
      if (p == pointee.end()) return;
      uint32_t type = p->second;
      for (auto a = arrayElement.find(type); a != arrayElement.end(); a = arrayElement.find(type)) type = a->second;
      if (sampledImages.count(type)) textures.insert(in[2]);
    }
  });
  // The two variables share the HLSL name; the unshifted one is `textureBase` below the other.
  // It also lacks the resource set: glslang leaves it in set 0 (a pixel shader's textures are in
  // set 1), so the set is copied from the twin as well.
  std::unordered_map<uint32_t, std::string> names;
  std::unordered_map<uint32_t, uint32_t*> bindingWord, setWord;
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    if (op == spv::OpName && wc >= 3 && textures.count(in[1])) names[in[1]] = reinterpret_cast<const char*>(in + 2);
    if (op == spv::OpDecorate && wc >= 4 && in[2] == spv::DecorationBinding && textures.count(in[1])) bindingWord[in[1]] = &in[3];
    if (op == spv::OpDecorate && wc >= 4 && in[2] == spv::DecorationDescriptorSet && textures.count(in[1])) setWord[in[1]] = &in[3];
  });
  for (auto& [var, word] : bindingWord) {
    auto name = names.find(var);
    if (name == names.end()) continue;
    for (auto& [other, otherWord] : bindingWord) {
      auto otherName = names.find(other);
      if (other != var && otherName != names.end() && otherName->second == name->second && *otherWord == *word + textureBase) {
        *word = *otherWord;
        if (setWord.count(var) && setWord.count(other)) *setWord[var] = *setWord[other];
        break;
      }
    }
  }
}

std::set<uint32_t> ComparisonSamplerVariables(const std::vector<uint32_t>& spirv) {
  auto defs = ResultDefinitions(spirv);
  std::set<uint32_t> result;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    switch (op) {
      case spv::OpImageSampleDrefImplicitLod:
      case spv::OpImageSampleDrefExplicitLod:
      case spv::OpImageSampleProjDrefImplicitLod:
      case spv::OpImageSampleProjDrefExplicitLod:
      case spv::OpImageDrefGather: {
        auto it = defs.find(in[3]);  // the sampled image
        if (it == defs.end()) return;
        const uint32_t* si = it->second;
        if (spv::Op(si[0] & 0xffff) != spv::OpSampledImage) return;
        if (uint32_t var = RootVariable(defs, si[4])) result.insert(var);
        break;
      }
      default:
        break;
    }
  });
  return result;
}

static std::set<uint32_t> ReadImageVariables(const std::vector<uint32_t>& spirv) {
  auto defs = ResultDefinitions(spirv);
  std::set<uint32_t> read;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    if (op == spv::OpImageRead) {
      if (uint32_t v = RootVariable(defs, in[3])) read.insert(v);
    } else if (op == spv::OpImageTexelPointer) {
      if (uint32_t v = RootVariable(defs, in[3])) read.insert(v);
    }
  });
  return read;
}

void SetFormatOfReadImages(std::vector<uint32_t>& spirv) {
  std::set<uint32_t> read = ReadImageVariables(spirv);
  if (read.empty()) return;
  // variable -> pointer type -> image type
  std::unordered_map<uint32_t, uint32_t> varType, pointee;
  std::unordered_map<uint32_t, uint32_t*> imageTypes;
  std::unordered_map<uint32_t, uint32_t> scalarKind;  // type id -> 0 float, 1 uint, 2 int
  ForEach(spirv, [&](spv::Op op, uint32_t wc, uint32_t* in) {
    if (op == spv::OpVariable) varType[in[2]] = in[1];
    if (op == spv::OpTypePointer) pointee[in[1]] = in[3];
    if (op == spv::OpTypeArray || op == spv::OpTypeRuntimeArray) pointee[in[1]] = in[2];
    if (op == spv::OpTypeImage) imageTypes[in[1]] = in;
    if (op == spv::OpTypeFloat) scalarKind[in[1]] = 0;
    if (op == spv::OpTypeInt) scalarKind[in[1]] = in[3] ? 2 : 1;
  });
  for (uint32_t v : read) {
    uint32_t t = varType[v];
    for (int i = 0; i < 4 && !imageTypes.count(t); ++i) t = pointee[t];
    auto it = imageTypes.find(t);
    if (it == imageTypes.end()) continue;
    uint32_t* img = it->second;  // OpTypeImage: result, sampled type, dim, depth, arrayed, ms, sampled, format
    if (img[8] != spv::ImageFormatUnknown) continue;
    uint32_t kind = scalarKind[img[2]];
    img[8] = kind == 0 ? spv::ImageFormatR32f : kind == 1 ? spv::ImageFormatR32ui : spv::ImageFormatR32i;
  }
}

std::set<uint32_t> WriteOnlyImageVariables(const std::vector<uint32_t>& spirv) {
  std::set<uint32_t> read = ReadImageVariables(spirv);
  auto defs = ResultDefinitions(spirv);
  std::set<uint32_t> written;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    if (op == spv::OpImageWrite)
      if (uint32_t v = RootVariable(defs, in[1])) written.insert(v);
  });
  std::set<uint32_t> result;
  for (uint32_t v : written)
    if (!read.count(v)) result.insert(v);
  return result;
}

void DropBiasFromGathers(std::vector<uint32_t>& spirv) {
  if (spirv.size() <= kHeaderWords) return;
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + kHeaderWords);
  out.reserve(spirv.size());
  bool changed = false;
  for (size_t i = kHeaderWords; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16;
    if (wc == 0 || i + wc > spirv.size()) {
      out.insert(out.end(), spirv.begin() + i, spirv.end());
      break;
    }
    spv::Op op = spv::Op(spirv[i] & 0xffff);
    // glslang declares the AMD gather-bias extension for that operand; no driver here has it.
    bool amdBias = (op == spv::OpCapability && wc == 2 && spirv[i + 1] == spv::CapabilityImageGatherBiasLodAMD) ||
                   (op == spv::OpExtension && wc >= 2 &&
                    std::string(reinterpret_cast<const char*>(&spirv[i + 1]), (wc - 1) * 4).c_str() == std::string("SPV_AMD_texture_gather_bias_lod"));
    uint32_t maskIdx = op == spv::OpImageGather || op == spv::OpImageDrefGather ? ImageOperandsIndex(op) : 0;
    if (amdBias) {
      changed = true;
    } else if (maskIdx && maskIdx < wc && (spirv[i + maskIdx] & spv::ImageOperandsBiasMask)) {
      // Bias is the lowest image-operand bit, so its id is the word right after the mask.
      std::vector<uint32_t> in(spirv.begin() + i, spirv.begin() + i + wc);
      in.erase(in.begin() + maskIdx + 1);
      in[maskIdx] &= ~uint32_t(spv::ImageOperandsBiasMask);
      if (in[maskIdx] == 0) in.erase(in.begin() + maskIdx);
      in[0] = (uint32_t(in.size()) << 16) | uint32_t(op);
      out.insert(out.end(), in.begin(), in.end());
      changed = true;
    } else {
      out.insert(out.end(), spirv.begin() + i, spirv.begin() + i + wc);
    }
    i += wc;
  }
  if (changed) spirv.swap(out);
}

}  // namespace sp::hlsl

// ---------------------------------------------------------------------------------------------
// Variants and facts the SPIR-V target (target-spirv.cpp) gives the Vulkan backend.

namespace sp::hlsl {

std::string EntryPointName(const std::vector<uint32_t>& spirv) {
  std::string name = "main";
  bool found = false;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    if (op != spv::OpEntryPoint || wc <= 3 || found) return;
    const char* s = reinterpret_cast<const char*>(in + 3);
    name.assign(s, strnlen(s, (wc - 3) * 4));
    found = true;
  });
  return name;
}

std::vector<uint32_t> DualSourceVariant(const std::vector<uint32_t>& spirv) {
  std::set<uint32_t> outputs;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    if (op == spv::OpVariable && wc >= 4 && in[3] == spv::StorageClassOutput) outputs.insert(in[2]);
  });
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + std::min(spirv.size(), kHeaderWords));
  out.reserve(spirv.size() + 4);
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* in) {
    bool target1 = op == spv::OpDecorate && wc == 4 && in[2] == spv::DecorationLocation && in[3] == 1 && outputs.count(in[1]);
    if (!target1) {
      out.insert(out.end(), in, in + wc);
      return;
    }
    out.insert(out.end(), {(4u << 16) | spv::OpDecorate, in[1], uint32_t(spv::DecorationLocation), 0u});
    out.insert(out.end(), {(4u << 16) | spv::OpDecorate, in[1], uint32_t(spv::DecorationIndex), 1u});
  });
  return out;
}

namespace {
// Instructions that may appear among the types, constants and global variables.
bool IsGlobalDeclaration(spv::Op op) {
  return (op >= spv::OpTypeVoid && op <= spv::OpTypeForwardPointer) || (op >= spv::OpConstantTrue && op <= spv::OpSpecConstantOp) ||
         op == spv::OpVariable;
}
constexpr uint32_t kFloatOne = 0x3f800000;
}  // namespace

std::vector<uint32_t> WritePointSizeVariant(const std::vector<uint32_t>& in) {
  size_t entryIdx = 0, firstGlobal = 0, firstFunction = 0;
  uint32_t entryFn = 0, floatId = 0, ptrId = 0, oneId = 0;
  bool ownPointSize = false;
  for (size_t i = kHeaderWords; i < in.size();) {
    uint32_t wc = in[i] >> 16;
    if (wc == 0) break;
    spv::Op op = spv::Op(in[i] & 0xffff);
    const uint32_t* w = &in[i];
    if (op == spv::OpEntryPoint && w[1] == spv::ExecutionModelVertex && !entryIdx) entryIdx = i, entryFn = w[2];
    if ((op == spv::OpDecorate && wc >= 4 && w[2] == spv::DecorationBuiltIn && w[3] == spv::BuiltInPointSize) ||
        (op == spv::OpMemberDecorate && wc >= 5 && w[3] == spv::DecorationBuiltIn && w[4] == spv::BuiltInPointSize))
      ownPointSize = true;
    if (op == spv::OpTypeFloat && w[2] == 32) floatId = w[1];
    if (op == spv::OpTypePointer && w[2] == spv::StorageClassOutput && floatId && w[3] == floatId) ptrId = w[1];
    if (op == spv::OpConstant && floatId && w[1] == floatId && w[3] == kFloatOne) oneId = w[2];
    if (IsGlobalDeclaration(op) && !firstGlobal && !firstFunction) firstGlobal = i;
    if (op == spv::OpFunction && !firstFunction) firstFunction = i;
    i += wc;
  }
  if (ownPointSize || !entryIdx || !firstGlobal || !firstFunction) return in;
  uint32_t bound = in[3];
  uint32_t var = bound++;
  std::vector<uint32_t> out(in.begin(), in.begin() + kHeaderWords);
  bool inEntry = false, afterLabel = false, stored = false;
  for (size_t i = kHeaderWords; i < in.size();) {
    uint32_t wc = in[i] >> 16;
    if (wc == 0) break;
    spv::Op op = spv::Op(in[i] & 0xffff);
    if (i == firstGlobal) out.insert(out.end(), {(4u << 16) | spv::OpDecorate, var, uint32_t(spv::DecorationBuiltIn), uint32_t(spv::BuiltInPointSize)});
    if (i == firstFunction) {
      if (!floatId) out.insert(out.end(), {(3u << 16) | spv::OpTypeFloat, floatId = bound++, 32u});
      if (!ptrId) out.insert(out.end(), {(4u << 16) | spv::OpTypePointer, ptrId = bound++, uint32_t(spv::StorageClassOutput), floatId});
      if (!oneId) out.insert(out.end(), {(4u << 16) | spv::OpConstant, floatId, oneId = bound++, kFloatOne});
      out.insert(out.end(), {(4u << 16) | spv::OpVariable, ptrId, var, uint32_t(spv::StorageClassOutput)});
    }
    if (op == spv::OpFunction) inEntry = in[i + 2] == entryFn;
    if (inEntry && afterLabel && !stored && op != spv::OpVariable && op != spv::OpLine && op != spv::OpNoLine) {
      out.insert(out.end(), {(3u << 16) | spv::OpStore, var, oneId});
      stored = true;
    }
    if (i == entryIdx) {
      // The new output joins the entry point's interface.
      out.push_back(((wc + 1) << 16) | op);
      out.insert(out.end(), in.begin() + i + 1, in.begin() + i + wc);
      out.push_back(var);
    } else {
      out.insert(out.end(), in.begin() + i, in.begin() + i + wc);
    }
    if (inEntry && op == spv::OpLabel) afterLabel = true;
    i += wc;
  }
  out[3] = bound;
  return out;
}

std::vector<uint32_t> InstanceIdFromZeroVariant(const std::vector<uint32_t>& in) {
  uint32_t instVar = 0, ptrType = 0;
  bool hasBase = false;
  ForEachConst(in, [&](spv::Op op, uint32_t wc, const uint32_t* w) {
    if (op == spv::OpDecorate && wc >= 4 && w[2] == spv::DecorationBuiltIn && w[3] == spv::BuiltInInstanceIndex) instVar = w[1];
    if (op == spv::OpDecorate && wc >= 4 && w[2] == spv::DecorationBuiltIn && w[3] == spv::BuiltInBaseInstance) hasBase = true;
  });
  if (!instVar || hasBase) return in;
  ForEachConst(in, [&](spv::Op op, uint32_t wc, const uint32_t* w) {
    if (op == spv::OpVariable && w[2] == instVar) ptrType = w[1];
  });
  uint32_t bound = in[3];
  uint32_t baseVar = bound++;
  std::vector<uint32_t> out(in.begin(), in.begin() + kHeaderWords);
  out.insert(out.end(), {(2u << 16) | spv::OpCapability, uint32_t(spv::CapabilityDrawParameters)});
  bool decorated = false;
  ForEachConst(in, [&](spv::Op op, uint32_t wc, const uint32_t* w) {
    if (op == spv::OpEntryPoint) {
      out.push_back(((wc + 1) << 16) | op);
      out.insert(out.end(), w + 1, w + wc);
      out.push_back(baseVar);
    } else if (op == spv::OpLoad && w[3] == instVar) {
      // InstanceIndex - BaseInstance, where the shader read InstanceIndex.
      uint32_t raw = bound++, base = bound++;
      out.insert(out.end(), {(4u << 16) | spv::OpLoad, w[1], raw, instVar});
      out.insert(out.end(), {(4u << 16) | spv::OpLoad, w[1], base, baseVar});
      out.insert(out.end(), {(5u << 16) | spv::OpISub, w[1], w[2], raw, base});
    } else {
      out.insert(out.end(), w, w + wc);
      if (op == spv::OpDecorate && w[1] == instVar && !decorated) {
        out.insert(out.end(), {(4u << 16) | spv::OpDecorate, baseVar, uint32_t(spv::DecorationBuiltIn), uint32_t(spv::BuiltInBaseInstance)});
        decorated = true;
      }
      if (op == spv::OpVariable && w[2] == instVar) out.insert(out.end(), {(4u << 16) | spv::OpVariable, ptrType, baseVar, w[3]});
    }
  });
  out[3] = bound;
  return out;
}

std::vector<SampledPair> SampledPairs(const std::vector<uint32_t>& spirv, uint32_t textureBase, uint32_t samplerBase) {
  std::unordered_map<uint32_t, uint32_t> binding, source;               // variable -> binding; loaded id -> variable
  std::unordered_map<uint32_t, std::pair<uint32_t, uint32_t>> sampled;  // OpSampledImage result -> (image var, sampler var)
  std::map<std::pair<uint32_t, uint32_t>, SampledPair> pairs;
  ForEachConst(spirv, [&](spv::Op op, uint32_t wc, const uint32_t* w) {
    if (op == spv::OpDecorate && wc >= 4 && w[2] == spv::DecorationBinding) binding[w[1]] = w[3];
    if (op == spv::OpLoad && wc >= 4) source[w[2]] = source.count(w[3]) ? source[w[3]] : w[3];
    if (op == spv::OpCopyObject && wc >= 4 && source.count(w[3])) source[w[2]] = source[w[3]];
    if (op == spv::OpSampledImage && wc >= 5 && source.count(w[3]) && source.count(w[4])) sampled[w[2]] = {source[w[3]], source[w[4]]};
    bool dref = false, gather = false;
    switch (op) {
      case spv::OpImageSampleImplicitLod:
      case spv::OpImageSampleExplicitLod:
      case spv::OpImageSampleProjImplicitLod:
      case spv::OpImageSampleProjExplicitLod: break;
      case spv::OpImageSampleDrefImplicitLod:
      case spv::OpImageSampleDrefExplicitLod:
      case spv::OpImageSampleProjDrefImplicitLod:
      case spv::OpImageSampleProjDrefExplicitLod: dref = true; break;
      case spv::OpImageGather: gather = true; break;
      case spv::OpImageDrefGather: dref = gather = true; break;
      default: return;
    }
    // Sampling instructions take the sampled image as their third word.
    if (wc < 4 || !sampled.count(w[3])) return;
    auto [img, smp] = sampled[w[3]];
    if (!binding.count(img) || !binding.count(smp)) return;
    SampledPair& p = pairs[{binding[img], binding[smp]}];
    p.textureReg = binding[img] - textureBase;
    p.samplerReg = binding[smp] - samplerBase;
    p.compared |= dref;
    p.filtered |= !dref && !gather;
  });
  std::vector<SampledPair> out;
  for (auto& [k, p] : pairs) out.push_back(p);
  return out;
}

}  // namespace sp::hlsl
