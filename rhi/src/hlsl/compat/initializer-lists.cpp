// Initializer lists as fxc reads them: values fill the declared type component by component, and
// braces inside the list may be left out. A full-screen-quad table written as
//   Vertex v[6] = { { -1, -1, 1, 1 }, { 0, 1 }, { -1, 1, 1, 1 }, { 0, 0 }, ... };
// (each member braced, no braces per element) or as a flat list of scalars is valid for fxc;
// glslang wants every aggregate braced ("'initializer list' : wrong number of structure members").
//
// For a declaration whose type is known here (scalar, vector and matrix types, structs defined in
// the source, arrays of them) and whose list is not already braced level by level, the list is
// re-braced: { { float4(-1, -1, 1, 1), float2(0, 1) }, ... }. Values are taken in order, exactly
// as fxc takes them; a list whose values cannot fill the type is an error with both counts.
// Lists of unknown types (typedefs, templates) and lists already braced are left to glslang.
#include <map>
#include <memory>
#include <regex>

#include "compat.h"

namespace sp::hlsl::compat {
namespace {

struct Type {
  std::string spelling;  // for constructors and messages
  int components = 0;    // scalars, vectors, matrices: number of scalars
  std::vector<std::shared_ptr<Type>> members;  // structs
  std::shared_ptr<Type> element;               // arrays
  long count = 0;                              // arrays: length, -1 when unsized
  bool IsNumeric() const { return components > 0; }
  bool IsArray() const { return element != nullptr; }
};
using TypePtr = std::shared_ptr<Type>;

TypePtr NumericType(const std::string& name) {
  NumericTypeName n;
  if (!ParseNumericTypeName(name, &n)) return nullptr;
  auto t = std::make_shared<Type>();
  t->spelling = name;
  t->components = n.components;
  return t;
}

TypePtr ArrayOf(TypePtr element, long count) {
  auto t = std::make_shared<Type>();
  t->element = std::move(element);
  t->count = count;
  t->spelling = t->element->spelling + "[" + (count < 0 ? std::string() : std::to_string(count)) + "]";
  return t;
}

// `[N][M]` after a declarator name, applied innermost last; false when a length is not a literal.
bool WrapInArrays(const Source& s, size_t& i, TypePtr& t) {
  std::vector<long> dims;
  while (s.Is(i, "[")) {
    size_t close = s.Matching(i);
    if (close == i + 1) dims.push_back(-1);
    else if (close == i + 2 && s[i + 1].kind == TokenKind::Number) dims.push_back(std::stol(s[i + 1].text, nullptr, 0));
    else return false;
    i = close + 1;
  }
  for (size_t d = dims.size(); d-- > 0;) t = ArrayOf(t, dims[d]);
  return true;
}

const std::regex& Modifiers() {
  static const std::regex re(
      R"(const|static|uniform|extern|volatile|precise|linear|nointerpolation|noperspective|centroid|sample|row_major|column_major|groupshared)");
  return re;
}

class Types {
 public:
  explicit Types(const Source& s) : s_(s) {}

  // The type named by token i: numeric, or a struct defined before it.
  TypePtr Named(size_t i) const {
    if (TypePtr t = NumericType(s_[i].text)) return t;
    auto it = structs_.find(s_[i].text);
    return it == structs_.end() ? nullptr : it->second;
  }

  // Reads `struct NAME { ... }` at token i (when it is one), so later declarations can use it.
  void MaybeStruct(size_t i) {
    if (!s_[i].Is("struct") || i + 2 >= s_.size() || !s_[i + 1].IsIdentifier() || !s_.Is(i + 2, "{")) return;
    size_t close = s_.Matching(i + 2);
    if (close >= s_.size()) return;
    auto t = std::make_shared<Type>();
    t->spelling = s_[i + 1].text;
    size_t j = i + 3;
    while (j < close) {
      size_t end = j;
      while (end < close && !s_[end].Is(";")) {
        if (s_[end].Is("(") || s_[end].Is("{") || s_[end].Is("<")) return;  // methods, nested types, templates
        ++end;
      }
      while (j < end && std::regex_match(s_[j].text, Modifiers())) ++j;
      if (j >= end) return;
      TypePtr memberType = Named(j);
      if (!memberType) return;
      for (auto [a, b] : s_.SplitCommas(j + 1, end)) {
        if (a >= b || !s_[a].IsIdentifier()) return;
        TypePtr m = memberType;
        size_t k = a + 1;
        if (!WrapInArrays(s_, k, m)) return;
        t->members.push_back(m);
      }
      j = end + 1;
    }
    structs_[t->spelling] = t;
  }

 private:
  const Source& s_;
  std::map<std::string, TypePtr> structs_;
};

// The list as written: leaves are expressions (token ranges), groups are braced sub-lists.
struct Item {
  bool group = false;
  size_t first = 0, last = 0;  // leaf tokens [first, last)
  std::vector<Item> children;
};

Item ParseList(const Source& s, size_t open) {
  Item g;
  g.group = true;
  size_t close = s.Matching(open);
  for (auto [a, b] : s.SplitCommas(open + 1, close)) {
    if (a >= b) continue;  // a trailing comma
    if (s[a].Is("{") && s.Matching(a) == b - 1) g.children.push_back(ParseList(s, a));
    else g.children.push_back({false, a, b, {}});
  }
  return g;
}

// How many scalars a leaf provides: 1 for literals, n for `floatn(...)` and `.xyzw` swizzles,
// 0 when it cannot be told from the text (a variable, a call).
int LeafComponents(const Source& s, const Item& leaf) {
  size_t a = leaf.first, b = leaf.last;
  if (s[a].Is("-") || s[a].Is("+")) ++a;
  if (b == a + 1 && (s[a].kind == TokenKind::Number || s[a].Is("true") || s[a].Is("false"))) return 1;
  if (s[a].IsIdentifier() && s.Is(a + 1, "(") && s.Matching(a + 1) == b - 1)
    if (TypePtr t = NumericType(s[a].text)) return t->components;
  static const std::regex swizzle("[xyzw]{1,4}|[rgba]{1,4}");
  if (b >= a + 3 && s[b - 2].Is(".") && std::regex_match(s[b - 1].text, swizzle)) return int(s[b - 1].text.size());
  return 0;
}

void Leaves(const Item& item, std::vector<const Item*>& out) {
  if (!item.group) out.push_back(&item);
  for (const Item& c : item.children) Leaves(c, out);
}

// Whether the list is braced level by level already (then glslang reads it as fxc does).
bool NaturallyBraced(const Source& s, const Type& t, const Item& item) {
  if (t.IsNumeric()) {
    if (!item.group) return LeafComponents(s, item) == t.components || (LeafComponents(s, item) == 0 && t.components > 1) ||
                            t.components == 1;
    return false;
  }
  if (!item.group) return false;
  if (t.IsArray()) {
    if (t.count >= 0 && long(item.children.size()) != t.count) return false;
    for (const Item& c : item.children)
      if (!NaturallyBraced(s, *t.element, c)) return false;
    return true;
  }
  if (item.children.size() != t.members.size()) return false;
  for (size_t i = 0; i < t.members.size(); ++i)
    if (!NaturallyBraced(s, *t.members[i], item.children[i])) return false;
  return true;
}

// Fills `t` from items[pos...], fxc's way; appends the fully braced text to `out`. Returns false
// (with pos and out unspecified) when the values do not fit.
class Filler {
 public:
  explicit Filler(const Source& s) : s_(s) {}

  bool Fill(const Type& t, const std::vector<Item>& items, size_t& pos, std::string& out) {
    if (pos >= items.size()) return false;
    if (t.IsNumeric()) return FillNumeric(t, items, pos, out);
    // Its own braces first, then elided (its values continue the enclosing list).
    if (items[pos].group) {
      size_t inner = 0;
      std::string text;
      if (FillAggregate(t, items[pos].children, inner, text, true) && inner == items[pos].children.size()) {
        ++pos;
        out += text;
        return true;
      }
    }
    return FillAggregate(t, items, pos, out, false);
  }

 private:
  bool FillAggregate(const Type& t, const std::vector<Item>& items, size_t& pos, std::string& out, bool ownBraces) {
    std::string text = "{ ";
    size_t start = pos;
    if (t.IsArray()) {
      long n = 0;
      for (; t.count < 0 ? pos < items.size() : n < t.count; ++n) {
        if (n) text += ", ";
        if (!Fill(*t.element, items, pos, text)) return false;
      }
      if (t.count < 0 && !ownBraces) return false;  // an unsized array takes a whole list
    } else {
      for (size_t m = 0; m < t.members.size(); ++m) {
        if (m) text += ", ";
        if (!Fill(*t.members[m], items, pos, text)) return false;
      }
    }
    if (pos == start) return false;
    out += text + " }";
    return true;
  }

  bool FillNumeric(const Type& t, const std::vector<Item>& items, size_t& pos, std::string& out) {
    const Item& first = items[pos];
    if (first.group) {  // { 1, 2, 3, 4 } for a float4: a constructor of its values
      std::vector<const Item*> leaves;
      Leaves(first, leaves);
      int known = 0;
      bool unknown = false;
      for (const Item* l : leaves) {
        int c = LeafComponents(s_, *l);
        unknown |= c == 0;
        known += c;
      }
      if (leaves.empty() || (!unknown && known != t.components) || known > t.components) return false;
      out += Construct(t, leaves);
      ++pos;
      return true;
    }
    int c = LeafComponents(s_, first);
    if (c == t.components || (c == 0 && t.components > 1) || t.components == 1) {
      if (c > t.components) return false;
      out += s_.Text(first.first, first.last);
      ++pos;
      return true;
    }
    // Scalars filling a vector or matrix.
    std::vector<const Item*> leaves;
    int have = 0;
    while (have < t.components && pos < items.size() && !items[pos].group) {
      int k = LeafComponents(s_, items[pos]);
      if (k == 0) return false;  // cannot tell how much of the vector it fills
      have += k;
      leaves.push_back(&items[pos++]);
    }
    if (have != t.components) return false;
    out += Construct(t, leaves);
    return true;
  }

  std::string Construct(const Type& t, const std::vector<const Item*>& leaves) const {
    std::string text = t.components == 1 ? "" : t.spelling + "(";
    for (size_t i = 0; i < leaves.size(); ++i) text += (i ? ", " : "") + s_.Text(leaves[i]->first, leaves[i]->last);
    return t.components == 1 ? text : text + ")";
  }

  const Source& s_;
};

int CountScalars(const Source& s, const Item& item, bool* unknown) {
  if (!item.group) {
    int c = LeafComponents(s, item);
    *unknown |= c == 0;
    return c;
  }
  int n = 0;
  for (const Item& c : item.children) n += CountScalars(s, c, unknown);
  return n;
}

long TypeScalars(const Type& t) {
  if (t.IsNumeric()) return t.components;
  if (t.IsArray()) return t.count < 0 ? -1 : t.count * TypeScalars(*t.element);
  long n = 0;
  for (const TypePtr& m : t.members) n += TypeScalars(*m);
  return n;
}

}  // namespace

void RewriteInitializerLists(const Source& s, Edits& edits) {
  Types types(s);
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    types.MaybeStruct(i);
    // TYPE NAME [dims] [: SEMANTIC] = {
    if (!s[i].Is("=") || !s.Is(i + 1, "{")) continue;
    size_t nameEnd = i;
    if (nameEnd >= 2 && s[nameEnd - 2].Is(":")) nameEnd -= 2;
    while (nameEnd > 0 && s[nameEnd - 1].Is("]")) nameEnd = s.MatchingOpen(nameEnd - 1);
    if (nameEnd < 2 || nameEnd > s.size() || !s[nameEnd - 1].IsIdentifier() || !s[nameEnd - 2].IsIdentifier()) continue;
    TypePtr type = types.Named(nameEnd - 2);
    if (!type) continue;
    size_t dims = nameEnd;
    if (!WrapInArrays(s, dims, type)) continue;
    size_t close = s.Matching(i + 1);
    if (close >= s.size()) s.Fail(i + 1, "unbalanced braces in the initializer of '" + s[nameEnd - 1].text + "'");
    Item list = ParseList(s, i + 1);
    if (NaturallyBraced(s, *type, list)) {
      i = close;
      continue;
    }
    std::vector<Item> top = {list};
    size_t pos = 0;
    std::string text;
    Filler filler(s);
    if (!filler.Fill(*type, top, pos, text) || pos != 1) {
      bool unknown = false;
      int have = CountScalars(s, list, &unknown);
      long need = TypeScalars(*type);
      if (!unknown && need >= 0 && have != need)
        s.Fail(i + 1, "the initializer of '" + s[nameEnd - 1].text + "' has " + std::to_string(have) + " values; " +
                          type->spelling + " takes " + std::to_string(need));
      i = close;
      continue;  // left to glslang, which reports what it cannot read
    }
    edits.Replace(s[i + 1].begin, s[close].end, text);
    i = close;
  }
}

}  // namespace sp::hlsl::compat
