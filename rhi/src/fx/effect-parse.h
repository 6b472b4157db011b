// Reading FX11 effect blocks from preprocessed HLSL. One parser serves two callers: the
// compatibility rewrite (hlsl/compat/effect-blocks.cpp), which hides the blocks from glslang, and
// sp::fx::Effect, which turns them into descs. Both therefore accept and refuse the same files.
#pragma once
#include <sp/fx/effect.h>

#include <string>
#include <vector>

#include "hlsl/compat/source-tokens.h"

namespace sp::fx::detail {

// A shader expression of a pass or a shader variable, before compilation.
struct ShaderExpr {
  bool isNull = false;
  std::string target, function, variable;
  std::vector<std::string> arguments;
  SourceLocation location;
};

struct ShaderVariable {
  std::string name;
  ShaderStage stage;
  ShaderExpr shader;
};

struct ParsedPass {
  PassDesc desc;  // without bytecode; shaders[] hold the expressions' fields
};

struct ParsedTechnique {
  std::string name, group;
  SourceLocation location;
  std::vector<ParsedPass> passes;
};

struct ParsedEffect {
  std::vector<StateObjectDesc> states;
  std::vector<ShaderVariable> shaderVariables;
  std::vector<ParsedTechnique> techniques;
  // Token ranges [first, last] (inclusive) that glslang must not see.
  std::vector<std::pair<size_t, size_t>> hidden;
};

// Throws hlsl::compat::RewriteError at the user's file:line for what it does not understand.
ParsedEffect ParseEffect(const hlsl::compat::Source& source);

// Sets `field` (with its [index], -1 when none) of `state` from the value tokens [first, last).
// Throws through source.Fail.
void SetStateField(StateObjectDesc& state, const hlsl::compat::Source& source, size_t fieldToken, int index, size_t first,
                   size_t last);
// Blend: IndependentBlendEnable from whether the render targets differ.
void FinishState(StateObjectDesc& state);

// Parses a number token range ("0x0F", "-1", "0.5f", "TRUE"); false when it is not one.
bool ParseNumber(const hlsl::compat::Source& source, size_t first, size_t last, double* value);

}  // namespace sp::fx::detail
