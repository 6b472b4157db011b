// Operand types of atomics on RWByteAddressBuffer.
//
// glslang translates RWByteAddressBuffer.Interlocked*(offset, value, ...) into an atomic on the
// buffer's uint words but passes `value` (and the comparator) with the HLSL argument's type, so
// an int argument, including an int literal such as `1` or `0`, gives SPIR-V that spirv-val
// rejects. It also always picks the unsigned min/max, while D3D11 has int overloads of
// InterlockedMin/InterlockedMax on RWByteAddressBuffer that compare signed. Typed and structured
// UAVs (InterlockedMin(buffer[i], value)) are converted by glslang itself and never reach here
// with mismatched types.
#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.hpp>
#include <stdexcept>
#include <unordered_map>

#include "spirv-edit.h"

namespace sp::hlsl {

void FixAtomicOperandTypes(std::vector<uint32_t>& spirv) {
  struct Int {
    uint32_t width = 0;
    bool isSigned = false;
  };
  std::unordered_map<uint32_t, Int> ints;         // OpTypeInt result -> width, signedness
  std::unordered_map<uint32_t, uint32_t> typeOf;  // result id -> type id
  bool anyAtomic = false;
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16;
    if (wc == 0) throw std::runtime_error("malformed SPIR-V");
    spv::Op op = spv::Op(spirv[i] & 0xffff);
    if (op == spv::OpTypeInt && wc >= 4) ints[spirv[i + 1]] = {spirv[i + 2], spirv[i + 3] != 0};
    anyAtomic |= op >= spv::OpAtomicLoad && op <= spv::OpAtomicXor;
    bool hasResult = false, hasType = false;
    spv::HasResultAndType(op, &hasResult, &hasType);
    if (hasResult && hasType) typeOf[spirv[i + 2]] = spirv[i + 1];
    i += wc;
  }
  if (!anyAtomic) return;

  uint32_t bound = spirv[3];
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + 5);
  for (size_t i = 5; i < spirv.size();) {
    uint32_t wc = spirv[i] >> 16;
    spv::Op op = spv::Op(spirv[i] & 0xffff);
    std::vector<uint32_t> inst(spirv.begin() + i, spirv.begin() + i + wc);
    i += wc;
    // Word indices of the value operands: after result type, result, pointer, scope, semantics.
    std::vector<uint32_t> values;
    switch (op) {
      case spv::OpAtomicExchange:
      case spv::OpAtomicIAdd:
      case spv::OpAtomicISub:
      case spv::OpAtomicSMin:
      case spv::OpAtomicUMin:
      case spv::OpAtomicSMax:
      case spv::OpAtomicUMax:
      case spv::OpAtomicAnd:
      case spv::OpAtomicOr:
      case spv::OpAtomicXor:
        if (wc >= 7) values = {6};
        break;
      case spv::OpAtomicCompareExchange:
        if (wc >= 9) values = {7, 8};  // after the two semantics operands
        break;
      default:
        break;
    }
    uint32_t resultType = inst.size() > 1 ? inst[1] : 0;
    auto rt = ints.find(resultType);
    bool signedOperand = false;
    for (uint32_t v : values) {
      auto t = typeOf.find(inst[v]);
      if (rt == ints.end() || t == typeOf.end() || t->second == resultType) continue;
      auto vt = ints.find(t->second);
      if (vt == ints.end() || vt->second.width != rt->second.width) continue;
      signedOperand |= vt->second.isSigned;
      uint32_t cast = bound++;
      out.insert(out.end(), {4u << 16 | spv::OpBitcast, resultType, cast, inst[v]});
      typeOf[cast] = resultType;
      inst[v] = cast;
    }
    // D3D11's int overloads of RWByteAddressBuffer.InterlockedMin/Max compare signed.
    if (signedOperand && op == spv::OpAtomicUMin) inst[0] = wc << 16 | spv::OpAtomicSMin;
    if (signedOperand && op == spv::OpAtomicUMax) inst[0] = wc << 16 | spv::OpAtomicSMax;
    out.insert(out.end(), inst.begin(), inst.end());
  }
  out[3] = bound;
  spirv = std::move(out);
}

}  // namespace sp::hlsl
