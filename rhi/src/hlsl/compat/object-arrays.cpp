// Arrays of texture and sampler objects: `Texture2D maps[4] : register(t0);`, read as
// `maps[2].Sample(s, uv)` or `maps[cascade].SampleCmpLevelZero(...)`. In D3D11 the array takes
// registers t0..t3, one texture each, bound with PSSetShaderResources(0, 4, ...); the RHI binds
// one resource per register. So the array becomes one object per register (`maps_sp0 : t0`, ...,
// the same registers D3D gives the elements), an element with a constant index becomes its object,
// and a method call on an element picked at run time becomes a chain of ?: over the elements,
// which gives the selected element's result (HLSL may evaluate every branch of ?:, so every
// element is read: SM 5.0 requires such an index to be uniform, no derivative breaks, and
// spirv-opt folds the chain where the index is constant, e.g. in [unroll] loops).
//
// Refused: the array used whole (passed to a function, or a parameter), an element picked at run time other than
// for a method call that returns a value (GetDimensions with a run-time index), arrays without
// an explicit register or of more than 32 elements.
#include <regex>

#include "compat.h"

namespace sp::hlsl::compat {
namespace {

bool IsObjectType(const std::string& t) {
  static const std::regex re(
      "(RW)?(Texture1D|Texture1DArray|Texture2D|Texture2DArray|Texture2DMS|Texture2DMSArray|Texture3D|TextureCube|TextureCubeArray|Buffer)|"
      "SamplerState|SamplerComparisonState");
  return std::regex_match(t, re);
}

struct ObjectArray {
  std::string name;
  int count = 0;
};

std::string Element(const std::string& name, int i) { return name + "_sp" + std::to_string(i); }

bool IntegerLiteral(const Source& s, size_t a, size_t b, long* value) {
  if (b != a + 1 || s[a].kind != TokenKind::Number) return false;
  char* end = nullptr;
  *value = std::strtol(s[a].text.c_str(), &end, 0);
  return end && (*end == 0 || *end == 'u' || *end == 'U');
}

}  // namespace

void RewriteObjectArrays(const Source& s, Edits& edits) {
  std::vector<ObjectArray> arrays;
  int depth = 0, parens = 0;
  for (size_t i = 0; i + 4 < s.size(); ++i) {
    if (s[i].Is("{")) ++depth;
    else if (s[i].Is("}")) --depth;
    else if (s[i].Is("(")) ++parens;
    else if (s[i].Is(")")) --parens;
    if (depth != 0 || !s[i].IsIdentifier() || !IsObjectType(s[i].text)) continue;
    if (parens > 0) {  // a parameter: `Texture2D maps[4]` passed whole
      size_t p = i + 1;  // the name, after the type's template arguments
      if (s.Is(p, "<"))
        while (p < s.size() && !s[p - 1].Is(">")) ++p;
      if (p + 1 < s.size() && s[p].IsIdentifier() && s.Is(p + 1, "["))
        s.Fail(p, "an array of objects as a parameter ('" + s[p].text + "') is not supported; pass its elements one by one");
      continue;
    }
    // TYPE [<...>] NAME [ N ] : register ( xK ) ;
    size_t n = i + 1;
    if (s.Is(n, "<")) {
      while (n < s.size() && !s[n].Is(">")) ++n;
      ++n;
    }
    if (n + 3 >= s.size() || !s[n].IsIdentifier() || !s.Is(n + 1, "[")) continue;
    size_t close = s.Matching(n + 1);
    long count;
    if (close >= s.size() || !IntegerLiteral(s, n + 2, close, &count)) continue;
    const std::string& name = s[n].text;
    if (!s.Is(close + 1, ":") || !s.Is(close + 2, "register") || !s.Is(close + 3, "(") || close + 6 >= s.size() || !s.Is(close + 5, ")"))
      s.Fail(n, "the object array '" + name + "' needs an explicit register (e.g. : register(t0)): its elements take consecutive registers");
    if (count < 1 || count > 32) s.Fail(n, "the object array '" + name + "' has " + std::to_string(count) + " elements (1 to 32 supported)");
    const std::string& reg = s[close + 4].text;  // t0, s1
    size_t digits = reg.find_first_of("0123456789");
    if (digits == std::string::npos || digits == 0) s.Fail(close + 4, "cannot read the register '" + reg + "'");
    int first = std::stoi(reg.substr(digits));
    std::string type = s.Text(i, n);
    std::string decls;
    for (int k = 0; k < count; ++k)
      decls += (k ? "; " : "") + type + " " + Element(name, k) + " : register(" + reg.substr(0, digits) + std::to_string(first + k) + ")";
    edits.Replace(s[i].begin, s[close + 5].end, decls);
    arrays.push_back({name, int(count)});
    i = close + 5;
  }
  if (arrays.empty()) return;

  for (size_t i = 0; i < s.size(); ++i) {
    const ObjectArray* a = nullptr;
    for (const ObjectArray& x : arrays)
      if (s[i].Is(x.name) && !(i > 0 && s[i - 1].Is("."))) a = &x;
    if (!a) continue;
    // Skip the declaration itself (rewritten above).
    if (i > 0 && (IsObjectType(s[i - 1].text) || s[i - 1].Is(">"))) continue;
    if (!s.Is(i + 1, "[")) s.Fail(i, "the object array '" + a->name + "' can only be used element by element (" + a->name + "[i])");
    size_t close = s.Matching(i + 1);
    if (close >= s.size()) s.Fail(i, "unbalanced brackets after '" + a->name + "'");
    long index;
    if (IntegerLiteral(s, i + 2, close, &index)) {
      if (index < 0 || index >= a->count) s.Fail(i + 2, "index " + std::to_string(index) + " is outside '" + a->name + "[" + std::to_string(a->count) + "]'");
      edits.Replace(s[i].begin, s[close].end, Element(a->name, int(index)));
      i = close;
      continue;
    }
    // A run-time index: only `name[expr].Method(args)` with a value.
    if (!s.Is(close + 1, ".") || close + 3 >= s.size() || !s[close + 2].IsIdentifier() || !s.Is(close + 3, "(") ||
        s[close + 2].Is("GetDimensions"))
      s.Fail(i, "an element of '" + a->name + "' chosen at run time can only call a method that returns a value (" + a->name +
                    "[i].Sample(...)); use a constant index or a Texture2DArray");
    size_t callClose = s.Matching(close + 3);
    if (callClose >= s.size()) s.Fail(i, "unbalanced parentheses in a call on '" + a->name + "'");
    std::string indexText = s.Text(i + 2, close);
    // .Method(args); elements of object arrays among the arguments (tex[i].Sample(samplers[1], uv))
    // must have constant indices here, since the call is copied into every branch.
    std::string call = s.Text(close + 1, callClose + 1);
    for (const ObjectArray& x : arrays) {
      std::regex literal("\\b" + x.name + "\\s*\\[\\s*([0-9]+)[uU]?\\s*\\]");
      call = std::regex_replace(call, literal, x.name + "_sp$1");
      if (std::regex_search(call, std::regex("\\b" + x.name + "\\s*\\[")))
        s.Fail(close + 3, "'" + x.name + "[...]' with a run-time index inside a call on an element of '" + a->name +
                              "' chosen at run time; use a constant index");
    }
    std::string chain = "(";
    for (int k = 0; k + 1 < a->count; ++k) chain += "(" + indexText + ") == " + std::to_string(k) + " ? " + Element(a->name, k) + call + " : ";
    chain += Element(a->name, a->count - 1) + call + ")";
    edits.Replace(s[i].begin, s[callClose].end, chain);
    i = callClose;
  }
}

}  // namespace sp::hlsl::compat
