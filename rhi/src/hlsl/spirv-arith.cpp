// Deterministic arithmetic for dot products, matrix products and lerp.
//
// Mesa lowers OpDot / matrix products / FMix from SPIR-V (lavapipe) and dot() / matrix products /
// mix() from GLSL (llvmpipe) to different sequences of multiplies, adds and fused multiply-adds, so the same
// HLSL gave results differing in the last bits on the two backends: enough to flip shadow
// comparisons where receiver and occluder depths meet. Explicit scalar multiplies and adds come
// out bit-identical on both, so these instructions are rewritten into them here, in one fixed
// order, before the SPIR-V reaches Vulkan or SPIRV-Cross.
#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/GLSL.std.450.h>
#include <spirv/unified1/spirv.hpp>

#include <stdexcept>
#include <unordered_map>

#include "spirv-edit.h"

namespace sp::hlsl {
namespace {

struct Type {
  spv::Op op = spv::OpNop;
  uint32_t component = 0;  // vector: component type; matrix: column type
  uint32_t count = 0;      // vector size or column count
};

class Lowering {
 public:
  // matricesOnly: only the column-by-column split of intrinsics on matrices, which must run
  // before legalisation (spirv-opt's folding turns lerp(m, n, 0.25) into invalid code first).
  Lowering(std::vector<uint32_t>& spirv, bool matricesOnly) : in_(spirv), matricesOnly_(matricesOnly) {}

  void Run() {
    Scan();
    std::vector<uint32_t> out(in_.begin(), in_.begin() + 5);
    for (size_t i = 5; i < in_.size();) {
      uint32_t wc = in_[i] >> 16;
      if (wc == 0) throw std::runtime_error("malformed SPIR-V");
      const uint32_t* w = &in_[i];
      if (!Rewrite(w, wc, out)) out.insert(out.end(), w, w + wc);
      i += wc;
    }
    out[3] = bound_;
    in_ = std::move(out);
  }

 private:
  void Scan() {
    bound_ = in_[3];
    for (size_t i = 5; i < in_.size();) {
      uint32_t wc = in_[i] >> 16;
      if (wc == 0) break;
      spv::Op op = spv::Op(in_[i] & 0xffff);
      const uint32_t* w = &in_[i];
      if (op == spv::OpTypeVector || op == spv::OpTypeMatrix) types_[w[1]] = {op, w[2], w[3]};
      if (op == spv::OpTypeFloat) types_[w[1]] = {op, 0, 1};
      if ((op == spv::OpConstantComposite || op == spv::OpCompositeConstruct) && wc > 3) constituents_[w[2]].assign(w + 3, w + wc);
      if (op == spv::OpExtInstImport && std::string(reinterpret_cast<const char*>(w + 2)) == "GLSL.std.450") glsl_ = w[1];
      bool hasResult = false, hasType = false;
      spv::HasResultAndType(op, &hasResult, &hasType);
      if (hasResult && hasType) typeOf_[w[2]] = w[1];
      i += wc;
    }
  }

  uint32_t NewId() { return bound_++; }

  uint32_t Emit(std::vector<uint32_t>& out, spv::Op op, uint32_t type, std::initializer_list<uint32_t> operands, uint32_t result = 0) {
    if (!result) result = NewId();
    out.push_back(uint32_t(3 + operands.size()) << 16 | op);
    out.push_back(type);
    out.push_back(result);
    out.insert(out.end(), operands.begin(), operands.end());
    typeOf_[result] = type;
    return result;
  }

  // a.x*b.x + a.y*b.y + ... left to right; the last add gets `result` when given.
  uint32_t Dot(std::vector<uint32_t>& out, uint32_t scalar, uint32_t a, uint32_t b, uint32_t n, uint32_t result = 0) {
    uint32_t sum = 0;
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t ai = Emit(out, spv::OpCompositeExtract, scalar, {a, i});
      uint32_t bi = Emit(out, spv::OpCompositeExtract, scalar, {b, i});
      bool last = i + 1 == n;
      uint32_t prod = Emit(out, spv::OpFMul, scalar, {ai, bi}, last && i == 0 ? result : 0);
      sum = i == 0 ? prod : Emit(out, spv::OpFAdd, scalar, {sum, prod}, last ? result : 0);
    }
    return sum;
  }

  // M * v: the columns of M weighted by v's components, summed in column order.
  uint32_t MatrixTimesVector(std::vector<uint32_t>& out, uint32_t resultType, uint32_t m, uint32_t v, uint32_t result = 0) {
    const Type& mt = types_.at(typeOf_.at(m));
    uint32_t scalar = types_.at(mt.component).component;
    uint32_t sum = 0;
    for (uint32_t c = 0; c < mt.count; ++c) {
      uint32_t col = Emit(out, spv::OpCompositeExtract, mt.component, {m, c});
      uint32_t vc = Emit(out, spv::OpCompositeExtract, scalar, {v, c});
      bool last = c + 1 == mt.count;
      uint32_t term = Emit(out, spv::OpVectorTimesScalar, resultType, {col, vc}, last && c == 0 ? result : 0);
      sum = c == 0 ? term : Emit(out, spv::OpFAdd, resultType, {sum, term}, last ? result : 0);
    }
    return sum;
  }

  bool IsFloat(uint32_t type) const {
    auto it = types_.find(type);
    return it != types_.end() && (it->second.op == spv::OpTypeFloat || IsFloatVector(type));
  }

  bool IsFloatVector(uint32_t type) const {
    auto it = types_.find(type);
    return it != types_.end() && it->second.op == spv::OpTypeVector && types_.count(it->second.component) &&
           types_.at(it->second.component).op == spv::OpTypeFloat;
  }

  // The scalar every component of vector `id` holds (a constant or constructed splat), or 0.
  uint32_t SplatScalar(uint32_t id) const {
    auto it = constituents_.find(id);
    if (it == constituents_.end() || it->second.empty()) return 0;
    for (uint32_t c : it->second)
      if (c != it->second[0]) return 0;
    return typeOf_.count(it->second[0]) && types_.count(typeOf_.at(it->second[0])) &&
                   types_.at(typeOf_.at(it->second[0])).op == spv::OpTypeFloat
               ? it->second[0]
               : 0;
  }

  bool IsFloatMatrix(uint32_t type) const {
    auto it = types_.find(type);
    return it != types_.end() && it->second.op == spv::OpTypeMatrix && IsFloatVector(it->second.component);
  }

  // HLSL's component-wise intrinsics take matrices (abs(m), saturate(m), max(m, n), lerp(a, b, s));
  // glslang emits the GLSL.std.450 instruction on the matrix type, which SPIR-V allows only on
  // scalars and vectors. Apply it to each column: the same values, component by component.
  bool ColumnByColumn(const uint32_t* w, uint32_t wc, std::vector<uint32_t>& out) {
    const Type& mt = types_.at(w[1]);
    uint32_t column = mt.component, n = types_.at(column).count;
    std::vector<uint32_t> operandCols[4];
    if (wc - 5 > 4) return false;
    for (uint32_t k = 5; k < wc; ++k) {  // check every operand before emitting anything
      uint32_t t = typeOf_.count(w[k]) ? typeOf_.at(w[k]) : 0;
      if (!types_.count(t) || !(IsFloatMatrix(t) || t == column || types_.at(t).op == spv::OpTypeFloat || SplatScalar(w[k])))
        return false;
    }
    for (uint32_t k = 5; k < wc; ++k) {
      uint32_t t = typeOf_.at(w[k]);
      for (uint32_t c = 0; c < mt.count; ++c) {
        if (IsFloatMatrix(t)) {
          operandCols[k - 5].push_back(Emit(out, spv::OpCompositeExtract, column, {w[k], c}));
        } else if (t == column) {
          operandCols[k - 5].push_back(w[k]);
        } else {
          // A scalar, or a vector holding one value in some size (glslang passes saturate's
          // bounds and lerp's literal weight that way): that value in every component.
          uint32_t scalar = types_.at(t).op == spv::OpTypeFloat ? w[k] : SplatScalar(w[k]);
          out.push_back(uint32_t(3 + n) << 16 | spv::OpCompositeConstruct);
          out.push_back(column);
          uint32_t id = NewId();
          out.push_back(id);
          for (uint32_t i = 0; i < n; ++i) out.push_back(scalar);
          typeOf_[id] = column;
          operandCols[k - 5].push_back(id);
        }
      }
    }
    std::vector<uint32_t> cols;
    for (uint32_t c = 0; c < mt.count; ++c) {
      if (w[4] == GLSLstd450FMix && wc == 8) {  // lerp: x + s * (y - x), as for vectors
        uint32_t x = operandCols[0][c], y = operandCols[1][c], t = operandCols[2][c];
        uint32_t d = Emit(out, spv::OpFSub, column, {y, x});
        uint32_t p = Emit(out, spv::OpFMul, column, {t, d});
        cols.push_back(Emit(out, spv::OpFAdd, column, {x, p}));
        continue;
      }
      uint32_t id = NewId();
      out.push_back(wc << 16 | spv::OpExtInst);
      out.push_back(column);
      out.push_back(id);
      out.push_back(glsl_);
      out.push_back(w[4]);
      for (uint32_t k = 5; k < wc; ++k) out.push_back(operandCols[k - 5][c]);
      typeOf_[id] = column;
      cols.push_back(id);
    }
    out.push_back(uint32_t(3 + cols.size()) << 16 | spv::OpCompositeConstruct);
    out.push_back(w[1]);
    out.push_back(w[2]);
    out.insert(out.end(), cols.begin(), cols.end());
    return true;
  }

  bool Rewrite(const uint32_t* w, uint32_t wc, std::vector<uint32_t>& out) {
    spv::Op op = spv::Op(w[0] & 0xffff);
    if (matricesOnly_) return op == spv::OpExtInst && wc >= 6 && w[3] == glsl_ && IsFloatMatrix(w[1]) && ColumnByColumn(w, wc, out);
    switch (op) {
      case spv::OpDot: {
        uint32_t vt = typeOf_.at(w[3]);
        if (!IsFloatVector(vt)) return false;
        Dot(out, w[1], w[3], w[4], types_.at(vt).count, w[2]);
        return true;
      }
      case spv::OpMatrixTimesVector:
        MatrixTimesVector(out, w[1], w[3], w[4], w[2]);
        return true;
      case spv::OpVectorTimesMatrix: {
        // v * M: one dot product of v with each column of M.
        const Type& mt = types_.at(typeOf_.at(w[4]));
        uint32_t scalar = types_.at(w[1]).component;
        std::vector<uint32_t> parts;
        for (uint32_t c = 0; c < mt.count; ++c) {
          uint32_t col = Emit(out, spv::OpCompositeExtract, mt.component, {w[4], c});
          parts.push_back(Dot(out, scalar, w[3], col, types_.at(mt.component).count));
        }
        out.push_back(uint32_t(3 + parts.size()) << 16 | spv::OpCompositeConstruct);
        out.push_back(w[1]);
        out.push_back(w[2]);
        out.insert(out.end(), parts.begin(), parts.end());
        return true;
      }
      case spv::OpMatrixTimesMatrix: {
        // A * B: A times each column of B.
        const Type& rt = types_.at(w[1]);
        const Type& bt = types_.at(typeOf_.at(w[4]));
        std::vector<uint32_t> cols;
        for (uint32_t c = 0; c < rt.count; ++c) {
          uint32_t bc = Emit(out, spv::OpCompositeExtract, bt.component, {w[4], c});
          cols.push_back(MatrixTimesVector(out, rt.component, w[3], bc));
        }
        out.push_back(uint32_t(3 + cols.size()) << 16 | spv::OpCompositeConstruct);
        out.push_back(w[1]);
        out.push_back(w[2]);
        out.insert(out.end(), cols.begin(), cols.end());
        return true;
      }
      case spv::OpExtInst: {
        if (w[3] != glsl_ || wc < 6) return false;
        uint32_t inst = w[4], x = w[5];
        uint32_t xt = typeOf_.at(x);
        if (inst == GLSLstd450FMix && wc >= 8 && IsFloat(xt)) {
          // HLSL's lerp(x, y, s) = x + s * (y - x), the order fxc's mad uses.
          uint32_t d = Emit(out, spv::OpFSub, w[1], {w[6], x});
          uint32_t p = Emit(out, spv::OpFMul, w[1], {w[7], d});
          Emit(out, spv::OpFAdd, w[1], {x, p}, w[2]);
          return true;
        }
        if (!IsFloatVector(xt)) return false;  // scalars: abs/sqrt are exact enough and lowered alike
        uint32_t scalar = types_.at(xt).component, n = types_.at(xt).count;
        if (inst == GLSLstd450Length) {
          uint32_t d = Dot(out, scalar, x, x, n);
          Emit(out, spv::OpExtInst, w[1], {glsl_, GLSLstd450Sqrt, d}, w[2]);
          return true;
        }
        if (inst == GLSLstd450Normalize) {
          uint32_t d = Dot(out, scalar, x, x, n);
          uint32_t r = Emit(out, spv::OpExtInst, scalar, {glsl_, GLSLstd450InverseSqrt, d});
          Emit(out, spv::OpVectorTimesScalar, w[1], {x, r}, w[2]);
          return true;
        }
        if (inst == GLSLstd450Distance && wc >= 7) {
          uint32_t diff = Emit(out, spv::OpFSub, xt, {x, w[6]});
          uint32_t d = Dot(out, scalar, diff, diff, n);
          Emit(out, spv::OpExtInst, w[1], {glsl_, GLSLstd450Sqrt, d}, w[2]);
          return true;
        }
        return false;
      }
      default:
        return false;
    }
  }

  std::vector<uint32_t>& in_;
  std::unordered_map<uint32_t, Type> types_;
  std::unordered_map<uint32_t, uint32_t> typeOf_;
  std::unordered_map<uint32_t, std::vector<uint32_t>> constituents_;  // of composites (constant or constructed)
  uint32_t glsl_ = 0;
  uint32_t bound_ = 0;
  bool matricesOnly_ = false;
};

}  // namespace

void LowerDotAndMatrixProducts(std::vector<uint32_t>& spirv) { Lowering(spirv, false).Run(); }

void SplitMatrixIntrinsics(std::vector<uint32_t>& spirv) { Lowering(spirv, true).Run(); }

}  // namespace sp::hlsl
