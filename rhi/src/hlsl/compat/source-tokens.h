// Tokens of preprocessed HLSL, for the D3D11 compatibility rewrites (see compat.h).
//
// The text is glslang's preprocessor output: macros expanded, includes inlined, `#line N "file"`
// directives marking where each part came from. Every token knows its position in the user's
// file, so a rewrite that refuses a construct names the file:line the user wrote it on. Rewrites
// do not re-print the source: they replace byte ranges (Edits) and keep the number of newlines,
// so glslang's own messages on the result still point at the user's lines.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sp::hlsl::compat {

enum class TokenKind { Identifier, Number, String, Punct, Directive };

struct Token {
  TokenKind kind;
  std::string text;
  size_t begin = 0, end = 0;  // byte range in the source
  int line = 0;               // in the user's file
  int file = 0;               // index into Source::files
  bool Is(std::string_view s) const { return kind != TokenKind::Directive && text == s; }
  bool IsIdentifier() const { return kind == TokenKind::Identifier; }
};

// A construct a rewrite cannot turn into HLSL glslang accepts, at the user's file:line.
struct RewriteError : std::runtime_error {
  RewriteError(std::string file, int line, const std::string& message)
      : std::runtime_error(message), file(std::move(file)), line(line) {}
  std::string file;
  int line;
};

class Source {
 public:
  // `mainFile` names lines before the first #line directive; `entryPoint` is the function being
  // compiled (some fxc rules differ for it), empty when not known.
  Source(std::string text, const std::string& mainFile, std::string entryPoint = {});

  const std::string& text() const { return text_; }
  const std::vector<Token>& tokens() const { return tokens_; }
  size_t size() const { return tokens_.size(); }
  const Token& operator[](size_t i) const { return tokens_[i]; }
  // Whether token i exists and is (not a directive and) spelled `s`.
  bool Is(size_t i, std::string_view s) const { return i < tokens_.size() && tokens_[i].Is(s); }
  const std::string& FileOf(size_t i) const { return files_[tokens_[i].file]; }
  const std::string& mainFile() const { return files_[0]; }
  const std::string& entryPoint() const { return entryPoint_; }

  // Index of the bracket closing the one at `open` ((, [, {), or size() when unbalanced.
  size_t Matching(size_t open) const;
  // Index of the bracket opening the one at `close` (), ], }), or size() when unbalanced.
  size_t MatchingOpen(size_t close) const;
  // Source text of tokens [first, last) as written (with their whitespace, comments removed by
  // the preprocessor already).
  std::string Text(size_t first, size_t last) const;
  // Splits [first, last) at top-level commas into ranges of token indices.
  std::vector<std::pair<size_t, size_t>> SplitCommas(size_t first, size_t last) const;

  [[noreturn]] void Fail(size_t token, const std::string& message) const;

 private:
  std::string text_;
  std::vector<Token> tokens_;
  std::vector<std::string> files_;
  std::string entryPoint_;
};

// Replacements of byte ranges of one Source, applied together. Overlapping edits are a bug in
// the rewrite (std::logic_error). Replacements keep the line structure: the newlines of the
// replaced range are appended to the replacement, so every later line keeps its number.
class Edits {
 public:
  void Replace(size_t begin, size_t end, std::string text) { edits_.push_back({begin, end, std::move(text)}); }
  void Insert(size_t at, std::string text) { Replace(at, at, std::move(text)); }
  // Declarations the rewritten code calls (helper functions), put before the first line.
  void AddPrelude(const std::string& key, const std::string& code);
  bool empty() const { return edits_.empty() && prelude_.empty(); }
  std::string Apply(const Source& source) const;

 private:
  struct Edit {
    size_t begin, end;
    std::string text;
  };
  std::vector<Edit> edits_;
  std::vector<std::string> preludeKeys_;
  std::string prelude_;
};

}  // namespace sp::hlsl::compat
