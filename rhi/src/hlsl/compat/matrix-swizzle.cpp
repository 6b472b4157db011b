// Matrix swizzles: m._11_21_31 (one-based row/column) and m._m00_m10_m20 (zero-based), as
// r-values and as l-values. glslang parses them but cannot emit SPIR-V for more than one element
// ("Missing functionality: matrix swizzle", or a crash), so each becomes a call to a generated
// helper indexing m[row][column]. HLSL's m[row] is a row whatever the packing, so the helpers
// read the same elements of row_major and column_major matrices. Single elements (m._11) are
// left to glslang, which handles them.
#include <algorithm>
#include <cctype>

#include "compat.h"

namespace sp::hlsl::compat {
namespace {

struct Element {
  int row, column;
};

// "_11_21_31" / "_m00_m10" -> elements; empty when `name` is not a matrix swizzle.
std::vector<Element> ParseSwizzle(const std::string& name) {
  std::vector<Element> out;
  size_t i = 0;
  while (i < name.size()) {
    if (name[i] != '_') return {};
    bool zeroBased = i + 1 < name.size() && name[i + 1] == 'm';
    size_t d = i + (zeroBased ? 2 : 1);
    if (d + 2 > name.size()) return {};
    char r = name[d], c = name[d + 1];
    int lo = zeroBased ? '0' : '1';
    if (r < lo || r > lo + 3 || c < lo || c > lo + 3) return {};
    out.push_back({r - lo, c - lo});
    i = d + 2;
  }
  return out;
}

std::string CanonicalName(const std::vector<Element>& e) {
  std::string s;
  for (const Element& x : e) s += "_" + std::to_string(x.row) + std::to_string(x.column);
  return s;
}

const char* const kComponentTypes[] = {"float", "int", "uint"};

// Getter and setter for every matrix type the elements fit in (glslang has no 1xN matrices).
std::string Helpers(const std::vector<Element>& e) {
  int maxRow = 0, maxColumn = 0;
  for (const Element& x : e) maxRow = std::max(maxRow, x.row), maxColumn = std::max(maxColumn, x.column);
  std::string n = std::to_string(e.size());
  std::string name = CanonicalName(e);
  std::string code;
  for (const char* t : kComponentTypes)
    for (int rows = std::max(2, maxRow + 1); rows <= 4; ++rows)
      for (int cols = std::max(2, maxColumn + 1); cols <= 4; ++cols) {
        std::string mat = std::string(t) + std::to_string(rows) + "x" + std::to_string(cols);
        std::string vec = std::string(t) + n;
        std::string get = vec + " spcompat_mget" + name + "(" + mat + " m) { return " + vec + "(";
        std::string set = vec + " spcompat_mset" + name + "(inout " + mat + " m, " + vec + " v) { ";
        for (size_t k = 0; k < e.size(); ++k) {
          std::string at = "m[" + std::to_string(e[k].row) + "][" + std::to_string(e[k].column) + "]";
          get += (k ? ", " : "") + at;
          set += at + " = v[" + std::to_string(k) + "]; ";
        }
        code += get + "); }\n" + set + "return v; }\n";
      }
  return code;
}

bool IsAssignment(const Token& t) {
  static const char* const ops[] = {"=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>="};
  if (t.kind != TokenKind::Punct) return false;
  for (const char* op : ops)
    if (t.text == op) return true;
  return false;
}

// First token of the postfix expression ending at `last` (a.b[i].c, f(x).y, (expr)).
size_t PostfixStart(const Source& s, size_t last) {
  size_t j = last;
  while (true) {
    const Token& t = s[j];
    size_t start;
    if (t.Is(")") || t.Is("]")) {
      size_t open = s.MatchingOpen(j);
      if (open >= s.size()) s.Fail(j, "unbalanced brackets before a matrix swizzle");
      start = open;
      if (t.Is(")") && open > 0 && s[open - 1].IsIdentifier()) start = open - 1;  // a call or constructor
      else if (t.Is("]") && open > 0) {
        j = open - 1;  // the indexed expression continues to the left
        continue;
      }
    } else if (t.IsIdentifier()) {
      start = j;
    } else {
      s.Fail(j, "a matrix swizzle must follow a matrix expression");
    }
    if (start >= 2 && s.Is(start - 1, ".")) {  // member access or method call: keep going left
      j = start - 2;
      continue;
    }
    return start;
  }
}

// End (exclusive) of the expression starting at `first`: the first `;`, `,` or unmatched closing
// bracket at depth 0.
size_t ExpressionEnd(const Source& s, size_t first) {
  for (size_t i = first; i < s.size(); ++i) {
    const Token& t = s[i];
    if (t.Is("(") || t.Is("[") || t.Is("{")) {
      i = s.Matching(i);
      if (i >= s.size()) break;
    } else if (t.Is(";") || t.Is(",") || t.Is(")") || t.Is("]") || t.Is("}")) {
      return i;
    }
  }
  s.Fail(first, "the value assigned to a matrix swizzle has no end");
}

}  // namespace

void RewriteMatrixSwizzles(const Source& s, Edits& edits) {
  size_t editedUpTo = 0;  // one rewrite per region per run; Apply runs again for nested ones
  for (size_t i = 1; i + 1 < s.size(); ++i) {
    if (!s[i].Is(".") || !s[i + 1].IsIdentifier()) continue;
    std::vector<Element> e = ParseSwizzle(s[i + 1].text);
    if (e.size() < 2) continue;
    if (e.size() > 4) s.Fail(i + 1, "matrix swizzle '" + s[i + 1].text + "' names more than 4 elements");
    size_t start = PostfixStart(s, i - 1);
    if (s[start].begin < editedUpTo) continue;
    std::string name = CanonicalName(e);
    std::string base = s.Text(start, i);
    edits.AddPrelude("matrix-swizzle" + name, Helpers(e));
    size_t after = i + 2;
    bool incremented = (start > 0 && (s[start - 1].Is("++") || s[start - 1].Is("--"))) ||
                       (after < s.size() && (s[after].Is("++") || s[after].Is("--")));
    if (incremented) s.Fail(i + 1, "++/-- on a matrix swizzle is not supported; write m." + s[i + 1].text + " += 1");
    if (after < s.size() && IsAssignment(s[after])) {
      for (size_t a = 0; a < e.size(); ++a)
        for (size_t b = a + 1; b < e.size(); ++b)
          if (e[a].row == e[b].row && e[a].column == e[b].column)
            s.Fail(i + 1, "matrix swizzle '" + s[i + 1].text + "' names an element twice and cannot be assigned to");
      size_t rhsEnd = ExpressionEnd(s, after + 1);
      std::string rhs = s.Text(after + 1, rhsEnd);
      std::string value = rhs;
      if (!s[after].Is("=")) {
        // Compound assignment reads the base twice: only safe when evaluating it has no effects.
        for (size_t k = start; k < i; ++k)
          if (s[k].Is("(") || s[k].Is("++") || s[k].Is("--") || s[k].Is("="))
            s.Fail(i + 1, "compound assignment to a matrix swizzle of an expression with calls or side effects ('" + base +
                              "') is not supported; assign to a local matrix first");
        std::string op = s[after].text.substr(0, s[after].text.size() - 1);
        value = "spcompat_mget" + name + "(" + base + ") " + op + " (" + rhs + ")";
      }
      edits.Replace(s[start].begin, rhsEnd < s.size() ? s[rhsEnd].begin : s.text().size(),
                    "spcompat_mset" + name + "(" + base + ", " + value + ")");
      editedUpTo = rhsEnd < s.size() ? s[rhsEnd].begin : s.text().size();
    } else {
      edits.Replace(s[start].begin, s[i + 1].end, "spcompat_mget" + name + "(" + base + ")");
      editedUpTo = s[i + 1].end;
    }
  }
}

}  // namespace sp::hlsl::compat
