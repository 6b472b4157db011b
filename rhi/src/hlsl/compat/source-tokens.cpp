#include "source-tokens.h"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace sp::hlsl::compat {
namespace {

bool IdentStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IdentChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Longest first, so `<<=` is not read as `<<` `=`.
constexpr const char* kPuncts[] = {"<<=", ">>=", "++", "--", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "==", "!=",
                                   "<=",  ">=",  "&&", "||", "<<", ">>", "::", "->"};

}  // namespace

Source::Source(std::string text, const std::string& mainFile, std::string entryPoint)
    : text_(std::move(text)), entryPoint_(std::move(entryPoint)) {
  files_.push_back(mainFile);
  int file = 0, line = 1;
  bool lineStart = true;
  const std::string& s = text_;
  size_t i = 0;
  auto fileIndex = [&](const std::string& name) {
    auto it = std::find(files_.begin(), files_.end(), name);
    if (it != files_.end()) return int(it - files_.begin());
    files_.push_back(name);
    return int(files_.size() - 1);
  };
  while (i < s.size()) {
    char c = s[i];
    if (c == '\n') {
      ++line;
      lineStart = true;
      ++i;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '/') {
      while (i < s.size() && s[i] != '\n') ++i;
      continue;
    }
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '*') {
      size_t e = s.find("*/", i + 2);
      e = e == std::string::npos ? s.size() : e + 2;
      line += int(std::count(s.begin() + long(i), s.begin() + long(e), '\n'));
      i = e;
      continue;
    }
    Token t;
    t.begin = i;
    t.line = line;
    t.file = file;
    if (c == '#' && lineStart) {
      size_t e = s.find('\n', i);
      if (e == std::string::npos) e = s.size();
      t.kind = TokenKind::Directive;
      t.text = s.substr(i, e - i);
      t.end = e;
      tokens_.push_back(t);
      // `#line N "file"` sets the number of the next line.
      const char* d = t.text.c_str() + 1;
      while (*d == ' ' || *d == '\t') ++d;
      if (std::strncmp(d, "line", 4) == 0) {
        char* after = nullptr;
        long n = std::strtol(d + 4, &after, 10);
        if (after != d + 4) {
          line = int(n) - 1;  // the newline ending the directive adds one
          const char* q = std::strchr(after, '"');
          if (q) {
            const char* q2 = std::strchr(q + 1, '"');
            if (q2) file = fileIndex(std::string(q + 1, q2));
          }
        }
      }
      i = e;
      continue;
    }
    lineStart = false;
    if (IdentStart(c)) {
      size_t e = i;
      while (e < s.size() && IdentChar(s[e])) ++e;
      t.kind = TokenKind::Identifier;
      t.end = e;
    } else if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
      size_t e = i;
      while (e < s.size()) {
        char d = s[e];
        bool exponentSign = (d == '+' || d == '-') && e > i && (s[e - 1] == 'e' || s[e - 1] == 'E') &&
                            !(s.size() > i + 1 && (s[i + 1] == 'x' || s[i + 1] == 'X'));
        if (IdentChar(d) || d == '.' || exponentSign) ++e;
        else break;
      }
      t.kind = TokenKind::Number;
      t.end = e;
    } else if (c == '"') {
      size_t e = i + 1;
      while (e < s.size() && s[e] != '"' && s[e] != '\n') e += s[e] == '\\' ? 2 : 1;
      t.kind = TokenKind::String;
      t.end = std::min(e + 1, s.size());
    } else {
      t.kind = TokenKind::Punct;
      t.end = i + 1;
      for (const char* p : kPuncts)
        if (s.compare(i, std::strlen(p), p) == 0) {
          t.end = i + std::strlen(p);
          break;
        }
    }
    t.text = s.substr(t.begin, t.end - t.begin);
    i = t.end;
    tokens_.push_back(std::move(t));
  }
}

size_t Source::Matching(size_t open) const {
  const std::string& o = tokens_[open].text;
  const char* close = o == "(" ? ")" : o == "[" ? "]" : o == "{" ? "}" : nullptr;
  if (!close) return size();
  int depth = 0;
  for (size_t i = open; i < size(); ++i) {
    if (tokens_[i].kind != TokenKind::Punct) continue;
    if (tokens_[i].text == o) ++depth;
    else if (tokens_[i].text == close && --depth == 0) return i;
  }
  return size();
}

size_t Source::MatchingOpen(size_t close) const {
  const std::string& c = tokens_[close].text;
  const char* open = c == ")" ? "(" : c == "]" ? "[" : c == "}" ? "{" : nullptr;
  if (!open) return size();
  int depth = 0;
  for (size_t i = close + 1; i-- > 0;) {
    if (tokens_[i].kind != TokenKind::Punct) continue;
    if (tokens_[i].text == c) ++depth;
    else if (tokens_[i].text == open && --depth == 0) return i;
  }
  return size();
}

std::string Source::Text(size_t first, size_t last) const {
  if (first >= last) return {};
  std::string t = text_.substr(tokens_[first].begin, tokens_[last - 1].end - tokens_[first].begin);
  std::replace(t.begin(), t.end(), '\n', ' ');
  return t;
}

std::vector<std::pair<size_t, size_t>> Source::SplitCommas(size_t first, size_t last) const {
  std::vector<std::pair<size_t, size_t>> parts;
  size_t start = first;
  for (size_t i = first; i < last; ++i) {
    const Token& t = tokens_[i];
    if (t.kind == TokenKind::Punct && (t.text == "(" || t.text == "[" || t.text == "{")) {
      size_t m = Matching(i);
      if (m < last) i = m;
    } else if (t.Is(",")) {
      parts.push_back({start, i});
      start = i + 1;
    }
  }
  if (start < last || !parts.empty()) parts.push_back({start, last});
  return parts;
}

void Source::Fail(size_t token, const std::string& message) const {
  size_t i = std::min(token, size() ? size() - 1 : 0);
  if (tokens_.empty()) throw RewriteError(files_[0], 0, message);
  throw RewriteError(files_[tokens_[i].file], tokens_[i].line, message);
}

void Edits::AddPrelude(const std::string& key, const std::string& code) {
  if (std::find(preludeKeys_.begin(), preludeKeys_.end(), key) != preludeKeys_.end()) return;
  preludeKeys_.push_back(key);
  prelude_ += code;
  prelude_ += "\n";
}

std::string Edits::Apply(const Source& source) const {
  std::vector<Edit> sorted = edits_;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
  const std::string& in = source.text();
  std::string out;
  size_t at = 0;
  for (const Edit& e : sorted) {
    if (e.begin < at) throw std::logic_error("overlapping compatibility rewrites at byte " + std::to_string(e.begin));
    out.append(in, at, e.begin - at);
    std::string text = e.text;
    std::replace(text.begin(), text.end(), '\n', ' ');
    out += text;
    out.append(size_t(std::count(in.begin() + long(e.begin), in.begin() + long(e.end), '\n')), '\n');
    at = e.end;
  }
  out.append(in, at, std::string::npos);
  if (prelude_.empty()) return out;
  // The helpers come first; `#line 1` gives the user's first line its number back.
  return "// ShadowPort D3D11 compatibility helpers\n" + prelude_ + "#line 1 \"" + source.mainFile() + "\"\n" + out;
}

}  // namespace sp::hlsl::compat
