// fxc's old for-loop scoping: a variable declared in a for initialiser stays visible after the
// loop, to the end of the enclosing block (fxc warns X3078 when a later declaration reuses the
// name, and uses the most recent one). glslang scopes it to the loop: "'i' : unknown variable".
//
// Where the variable is used after its loop, the declaration moves in front of the loop
// (`int i = 0; for (; i < n; ++i)`), which gives fxc's visibility and leaves the loop the same.
// A second loop in the same block declaring the same name and used after it becomes an assignment
// (`i = 0; for (; ...)`), as fxc's "most recent declaration" amounts to. Loops whose variable is
// not used after them are left alone.
#include <map>
#include <set>

#include "compat.h"

namespace sp::hlsl::compat {
namespace {

// One past the last token of the statement starting at `i`.
size_t StatementEnd(const Source& s, size_t i) {
  if (i >= s.size()) return s.size();
  if (s[i].Is("{")) return std::min(s.Matching(i), s.size() - 1) + 1;
  if (s[i].Is("[")) return StatementEnd(s, s.Matching(i) + 1);  // [unroll], [branch], ...
  if (s[i].Is("if") || s[i].Is("for") || s[i].Is("while") || s[i].Is("switch")) {
    if (!s.Is(i + 1, "(")) s.Fail(i, "expected '(' after '" + s[i].text + "'");
    size_t end = StatementEnd(s, s.Matching(i + 1) + 1);
    if (s[i].Is("if") && s.Is(end, "else")) end = StatementEnd(s, end + 1);
    return end;
  }
  if (s[i].Is("do")) {
    size_t end = StatementEnd(s, i + 1);  // body; then `while (...) ;`
    if (s.Is(end, "while") && s.Is(end + 1, "(")) return s.Matching(end + 1) + 2;
    return end;
  }
  for (size_t j = i; j < s.size(); ++j) {
    if (s[j].Is("(") || s[j].Is("[") || s[j].Is("{")) j = s.Matching(j);
    else if (s[j].Is(";")) return j + 1;
  }
  return s.size();
}

// Index of the `}` closing the block that contains token `i` (size() at file scope).
size_t EnclosingBlockEnd(const Source& s, size_t i) {
  int depth = 0;
  for (size_t j = i; j < s.size(); ++j) {
    if (s[j].Is("{")) ++depth;
    else if (s[j].Is("}") && --depth < 0) return j;
  }
  return s.size();
}

struct Declaration {
  size_t typeFirst, typeLast;  // [first, last): the type tokens
  std::vector<size_t> names;   // token index of each declarator's name
};

// `[const] TYPE a = 0, b = 1` in [first, last); false when the initialiser is an expression.
bool ParseDeclaration(const Source& s, size_t first, size_t last, Declaration* d) {
  std::vector<std::pair<size_t, size_t>> parts = s.SplitCommas(first, last);
  if (parts.empty()) return false;
  size_t a = parts[0].first, b = parts[0].second;
  size_t eq = a;
  while (eq < b && !s[eq].Is("=")) ++eq;
  size_t nameEnd = eq;
  if (nameEnd > a && s[nameEnd - 1].Is("]")) nameEnd = s.MatchingOpen(nameEnd - 1);  // int i[2]
  if (nameEnd < a + 2 || !s[nameEnd - 1].IsIdentifier()) return false;
  for (size_t k = a; k + 1 < nameEnd; ++k)
    if (!s[k].IsIdentifier() && !s[k].Is("<") && !s[k].Is(">") && !s[k].Is(",")) return false;
  d->typeFirst = a;
  d->typeLast = nameEnd - 1;
  d->names = {nameEnd - 1};
  for (size_t p = 1; p < parts.size(); ++p) {
    if (parts[p].first >= parts[p].second || !s[parts[p].first].IsIdentifier()) return false;
    d->names.push_back(parts[p].first);
  }
  return true;
}

bool DeclaresName(const Source& s, size_t j, const std::string& name) {
  // `TYPE name =|;|,|[` where TYPE is an identifier that is not a keyword taking an expression.
  if (!s[j].Is(name) || j == 0 || !s[j - 1].IsIdentifier()) return false;
  static const std::set<std::string> notTypes = {"return", "case", "else", "do"};
  if (notTypes.count(s[j - 1].text)) return false;
  return s.Is(j + 1, "=") || s.Is(j + 1, ";") || s.Is(j + 1, ",") || s.Is(j + 1, "[") || s.Is(j + 1, ":");
}

// Whether `name` is read or written in (from, to) before something declares it anew.
bool UsedAfter(const Source& s, size_t from, size_t to, const std::string& name) {
  for (size_t j = from; j < to; ++j) {
    if (s[j].Is("for") && s.Is(j + 1, "(")) {
      // A later loop declaring the same name takes over from here (it is rewritten on its own).
      Declaration d;
      size_t close = s.Matching(j + 1);
      size_t semi = j + 2;
      while (semi < close && !s[semi].Is(";")) ++semi;
      if (ParseDeclaration(s, j + 2, semi, &d))
        for (size_t n : d.names)
          if (s[n].Is(name)) return false;
    }
    if (DeclaresName(s, j, name)) return false;
    if (s[j].Is(name) && !(j > 0 && s[j - 1].Is("."))) return true;
  }
  return false;
}

}  // namespace

void RewriteForLoopScope(const Source& s, Edits& edits) {
  // (enclosing block end, name) -> type text of the declaration already moved out of a loop.
  std::map<std::pair<size_t, std::string>, std::string> hoisted;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (!s[i].Is("for") || !s.Is(i + 1, "(")) continue;
    size_t open = i + 1, close = s.Matching(open);
    if (close >= s.size()) s.Fail(i, "unbalanced parentheses in a for statement");
    size_t semi = open + 1;
    while (semi < close && !s[semi].Is(";")) ++semi;
    Declaration d;
    if (semi >= close || !ParseDeclaration(s, open + 1, semi, &d)) continue;
    size_t loopEnd = StatementEnd(s, close + 1);
    size_t blockEnd = EnclosingBlockEnd(s, i);
    bool used = false;
    for (size_t n : d.names) used = used || UsedAfter(s, loopEnd, blockEnd, s[n].text);
    if (!used) continue;

    // The declaration goes in front of the loop and its attributes ([unroll] for (...)).
    size_t first = i;
    while (first > 0 && s[first - 1].Is("]")) first = s.MatchingOpen(first - 1);
    bool statementStart = first == 0 || s[first - 1].Is(";") || s[first - 1].Is("{") || s[first - 1].Is("}") ||
                          s[first - 1].Is(":") || s[first - 1].kind == TokenKind::Directive;
    if (!statementStart)
      s.Fail(i, "the variable '" + s[d.names[0]].text + "' of this for loop is used after the loop (fxc's scoping), but the loop is "
                "the body of another statement; put the loop in braces { } or declare the variable before it");
    std::string type = s.Text(d.typeFirst, d.typeLast);
    std::string declaration = s.Text(open + 1, semi);
    auto key = std::make_pair(blockEnd, s[d.names[0]].text);
    auto previous = hoisted.find(key);
    if (previous != hoisted.end()) {
      if (previous->second != type)
        s.Fail(i, "'" + key.second + "' is declared again in this for loop as '" + type + "' after an earlier loop's '" +
                      previous->second + "', and both are used after their loops; rename one");
      declaration = s.Text(d.typeLast, semi);  // the same variable, assigned anew
    }
    hoisted[key] = type;
    edits.Insert(s[first].begin, declaration + "; ");
    edits.Replace(s[open + 1].begin, s[semi].begin, "");
  }
}

}  // namespace sp::hlsl::compat
