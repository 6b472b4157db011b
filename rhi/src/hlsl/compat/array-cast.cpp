// Array casts: `static float s[8] = (float[8])packed;` with `float4 packed[2]` in a cbuffer, the
// classic way to index floats packed four to a register (a float[8] member would take eight
// registers). fxc reinterprets the source component by component in declaration order; glslang
// has no array casts ("array constructor needs one argument per array element"). The cast
// becomes an initializer list naming those components: { packed[0].x, packed[0].y, ... }.
// Only in a declaration's initializer, where a list is valid; only from a variable declared
// with a scalar or vector type (arrays of them included). Anything else is refused.
#include "compat.h"

namespace sp::hlsl::compat {
namespace {

struct NumericType {
  int components = 0;  // 1 for scalars, 2..4 for vectors; 0 when not a scalar or vector type
};

// Scalars and vectors only: a matrix's component order in a cast is not what this rewrite lists.
NumericType ParseNumeric(const std::string& t) {
  NumericTypeName n;
  if (!ParseNumericTypeName(t, &n) || n.matrix) return {};
  return {n.components};
}

// Array dimensions written as `[N]` after a name, multiplied; false when one is not a literal.
bool ArrayCount(const Source& s, size_t i, size_t* next, long* count) {
  *count = 1;
  while (s.Is(i, "[")) {
    size_t close = s.Matching(i);
    if (close != i + 2 || s[i + 1].kind != TokenKind::Number) return false;
    *count *= std::stol(s[i + 1].text, nullptr, 0);
    i = close + 1;
  }
  *next = i;
  return true;
}

// The declaration of `name` closest before token `use`: `TYPE name[...]` outside function bodies.
bool FindDeclaration(const Source& s, size_t use, const std::string& name, NumericType* type, long* count, bool* isArray) {
  for (size_t j = use; j-- > 1;) {
    if (!s[j].Is(name) || !s[j - 1].IsIdentifier()) continue;
    NumericType t = ParseNumeric(s[j - 1].text);
    size_t next;
    long n;
    if (!t.components || !ArrayCount(s, j + 1, &next, &n)) continue;
    if (!s.Is(next, ";") && !s.Is(next, ":") && !s.Is(next, "=") && !s.Is(next, ",")) continue;
    *type = t;
    *count = n;
    *isArray = s.Is(j + 1, "[");
    return true;
  }
  return false;
}

}  // namespace

void RewriteArrayCasts(const Source& s, Edits& edits) {
  for (size_t i = 0; i + 5 < s.size(); ++i) {
    // ( TYPE [ N ] ) source
    if (!s[i].Is("(") || !s[i + 1].IsIdentifier() || !s.Is(i + 2, "[")) continue;
    NumericType target = ParseNumeric(s[i + 1].text);
    if (!target.components) continue;
    size_t afterDims;
    long targetCount;
    if (!ArrayCount(s, i + 2, &afterDims, &targetCount) || !s.Is(afterDims, ")")) continue;
    size_t src = afterDims + 1;
    std::string cast = s.Text(i, src);
    if (!(i > 0 && s[i - 1].Is("=")))
      s.Fail(i, "the array cast " + cast + " is supported only as a declaration's initializer (T a[N] = " + cast + "x;)");
    if (src >= s.size() || !s[src].IsIdentifier() || (src + 1 < s.size() && !s.Is(src + 1, ";") && !s.Is(src + 1, ",")))
      s.Fail(i, "the array cast " + cast + " must be applied to a variable's name (e.g. a cbuffer member)");
    const std::string& name = s[src].text;
    NumericType source;
    long sourceCount;
    bool sourceIsArray;
    if (!FindDeclaration(s, i, name, &source, &sourceCount, &sourceIsArray))
      s.Fail(src, "the array cast " + cast + name + " needs '" + name +
                      "' declared before it with a scalar or vector type (or an array of one)");
    long need = targetCount * target.components, have = sourceCount * source.components;
    if (need > have)
      s.Fail(i, "the array cast " + cast + name + " needs " + std::to_string(need) + " components and '" + name + "' has " +
                    std::to_string(have));
    // Source components in D3D order: element by element, x y z w within each.
    std::vector<std::string> components;
    const char* xyzw = "xyzw";
    for (long e = 0; e < sourceCount; ++e)
      for (int c = 0; c < source.components; ++c) {
        std::string x = name;
        if (sourceIsArray) x += "[" + std::to_string(e) + "]";
        if (source.components > 1) x += std::string(".") + xyzw[c];
        components.push_back(x);
      }
    std::string list = "{";
    for (long e = 0; e < targetCount; ++e) {
      std::string item;
      for (int c = 0; c < target.components; ++c) item += (c ? ", " : "") + components[size_t(e * target.components + c)];
      if (target.components > 1) item = s[i + 1].text + "(" + item + ")";
      list += (e ? ", " : " ") + item;
    }
    list += " }";
    edits.Replace(s[i].begin, s[src].end, list);
    i = src;
  }
}

}  // namespace sp::hlsl::compat
