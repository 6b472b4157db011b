// The D3D11 compatibility pass: source rewrites between glslang's preprocessor and its parser,
// for constructs fxc has always accepted and glslang's HLSL front end does not.
//
// Each rewrite is one function over the preprocessed tokens (one file per construct, each with
// its own tests in tests/hlsl/compat-*-test.cpp). A rewrite changes only the construct it knows,
// keeps every line where it was (see Edits), and refuses what it cannot rewrite faithfully with
// a RewriteError naming the user's file:line: never a silently different shader.
#pragma once
#include <string>
#include <vector>

#include "source-tokens.h"

namespace sp::hlsl::compat {

struct Rewrite {
  const char* name;     // shown by `hlslc -P` and in the survey report
  const char* summary;  // one line: what fxc accepts that glslang does not
  void (*run)(const Source& source, Edits& edits);
};

// HLSL's numeric type names (float, int3, half4x4, min16float2, ...; not vector<T, N>): the
// number of scalars and whether it is a matrix. False for any other name.
struct NumericTypeName {
  int components = 0;
  bool matrix = false;
};
bool ParseNumericTypeName(const std::string& name, NumericTypeName* type);

// The rewrites, in the order they run (each sees the previous one's output).
const std::vector<Rewrite>& Rewrites();

struct Result {
  std::string source;
  std::vector<std::string> applied;  // names of the rewrites that changed something
};

// Runs every rewrite over `preprocessed` (glslang's preprocessor output for `mainFile`, compiled
// for `entryPoint`). Throws RewriteError.
Result Apply(const std::string& preprocessed, const std::string& mainFile, const std::string& entryPoint = {});

// One rewrite per construct (compat/<name>.cpp).
void RewriteEffectBlocks(const Source& source, Edits& edits);
void RewriteForLoopScope(const Source& source, Edits& edits);
void RewriteCbufferStatics(const Source& source, Edits& edits);
void RewriteArrayCasts(const Source& source, Edits& edits);
void RewriteInitializerLists(const Source& source, Edits& edits);
void RewriteMatrixSwizzles(const Source& source, Edits& edits);
void RewriteUniformParameters(const Source& source, Edits& edits);
void RewriteCoverageParameter(const Source& source, Edits& edits);
void RewriteObjectArrays(const Source& source, Edits& edits);

}  // namespace sp::hlsl::compat
