// `shadowport hlslc --survey DIR`: finds the entry points of a shader tree (or takes them from a
// manifest), compiles each one and writes a markdown report: how much ports as is, the failures
// grouped by cause, and which D3D11 compatibility rewrites were needed.
//
// Entry points are found from signatures, not by compiling, because a tree has no list of them:
// the build that knows them is the thing being ported. The rules are deliberately simple (see
// Classify) and the manifest is the escape hatch for whatever they get wrong.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sp/hlsl/compiler.h>
#include <sstream>
#include <stdexcept>

#include "cli.h"
#include "hlsl/compat/compat.h"
#include "hlsl/compat/source-tokens.h"

namespace fs = std::filesystem;
namespace compat = sp::hlsl::compat;

namespace sp::cli {

const char kSurveyUsage[] =
    "survey: shadowport hlslc --survey DIR [-D NAME[=VALUE]]... [-I dir]... [--manifest FILE] [-Zpr|-Zpc] [--no-cache] --out report.md\n"
    "  compiles every entry point under DIR and writes a markdown report (summary, failures grouped by\n"
    "  cause, a per-file table, the compatibility rewrites used); prints a one-line summary; exits 0\n"
    "  when the survey ran, failures included. Entry points are found in .hlsl .hlsli .fx .fxh .vsh .psh\n"
    "  .cs files: [numthreads] -> cs_5_0, [maxvertexcount] -> gs_5_0, [patchconstantfunc] -> hs_5_0 and\n"
    "  [domain] -> ds_5_0 (which fail: tessellation is not supported), a return semantic SV_Target*,\n"
    "  SV_Depth* or COLOR* (or a returned struct with SV_Target members) -> ps_5_0, SV_Position returned,\n"
    "  in a returned struct or as an out parameter -> vs_5_0; functions other functions call are not\n"
    "  entry points; in effect files, CompileShader(target, Entry()) names them. -D and -I apply to all.\n"
    "  --manifest FILE lists the entry points instead, one per line (paths relative to DIR; '#' starts\n"
    "  a comment):   file entry target [-D NAME[=VALUE]]...   e.g.  sdsm/reduce.hlsl ReduceFinal cs_5_0 -D SDSM_BINS=256\n";

namespace {

const char* const kExtensions[] = {".hlsl", ".hlsli", ".fx", ".fxh", ".vsh", ".psh", ".cs"};

struct Options {
  fs::path dir, manifest, out;
  hlsl::CompileOptions compile;
  bool help = false;
};

struct Entry {
  std::string file;  // relative to the surveyed folder, as the report names it
  std::string name, target;
  int line = 0;                      // where it was found (0: from the manifest)
  std::vector<hlsl::Define> defines;  // the manifest's, after the command line's
  // An effect technique's call when it passes uniform arguments ("PS(true)"): the function
  // compiled on its own takes them as shader inputs, which the report explains.
  std::string uniformCall;
};

struct Outcome {
  bool ok = false;
  std::string where;    // "file:line" of the first diagnostic, or the file
  std::string message;  // the first diagnostic
  std::vector<std::string> rewrites;
};

// -DNAME=V or -D NAME=V; also -I.
std::string ValueOf(const std::vector<std::string>& argv, size_t& i, const std::string& flag) {
  if (argv[i].size() > flag.size()) return argv[i].substr(flag.size());
  if (i + 1 >= argv.size()) throw std::invalid_argument(flag + " needs a value (hlslc --survey --help)");
  return argv[++i];
}

hlsl::Define ParseDefine(const std::string& text) {
  size_t eq = text.find('=');
  if (text.empty() || eq == 0) throw std::invalid_argument("-D needs a name: '" + text + "'");
  return {text.substr(0, eq), eq == std::string::npos ? "" : text.substr(eq + 1)};
}

Options Parse(const std::vector<std::string>& argv) {
  Options o;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    auto value = [&](const std::string& flag) { return ValueOf(argv, i, flag); };
    if (a == "--survey") {
      if (i + 1 >= argv.size() || argv[i + 1].rfind("-", 0) == 0) {
        if (i + 1 < argv.size() && (argv[i + 1] == "--help" || argv[i + 1] == "-h")) continue;
        throw std::invalid_argument("--survey needs the folder to survey");
      }
      o.dir = argv[++i];
    } else if (a == "--help" || a == "-h" || a == "-?" || a == "/?") o.help = true;
    else if (a == "--out" || a == "--manifest") {
      if (i + 1 >= argv.size()) throw std::invalid_argument(a + " needs a file");
      (a == "--out" ? o.out : o.manifest) = argv[++i];
    } else if (a.rfind("--out=", 0) == 0) o.out = a.substr(6);
    else if (a.rfind("--manifest=", 0) == 0) o.manifest = a.substr(11);
    else if (a == "--no-cache") o.compile.useCache = false;
    else if (a == "-Zpr" || a == "/Zpr") o.compile.flags1 |= hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR;
    else if (a == "-Zpc" || a == "/Zpc") o.compile.flags1 |= hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR;
    else if (a.rfind("-D", 0) == 0 || a.rfind("/D", 0) == 0) o.compile.defines.push_back(ParseDefine(value(a.substr(0, 2))));
    else if (a.rfind("-I", 0) == 0 || a.rfind("/I", 0) == 0) o.compile.includeDirs.push_back(value(a.substr(0, 2)));
    else if (a.empty() || (a[0] != '-' && a[0] != '/'))
      throw std::invalid_argument("unexpected argument '" + a + "' (the folder to survey follows --survey; see hlslc --survey --help)");
    else throw std::invalid_argument("unknown option for --survey: " + a + " (valid: --survey DIR, -D, -I, --manifest, -Zpr, -Zpc, --no-cache, --out, --help)");
  }
  if (o.help) return o;
  if (o.dir.empty()) throw std::invalid_argument("--survey needs the folder to survey");
  if (!fs::is_directory(o.dir)) throw std::invalid_argument(o.dir.string() + ": not a folder");
  if (o.out.empty()) throw std::invalid_argument("--survey needs --out report.md");
  return o;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::invalid_argument(p.string() + ": cannot open the file");
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

std::string Upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// ---- Finding entry points ---------------------------------------------------------------------

struct Param {
  bool out = false;
  std::string type, semantic;
};

struct Function {
  std::string name, returnType, semantic;
  std::vector<std::string> attributes;
  std::vector<Param> params;
  int line = 0;
};

// What one file declares at its top level, and what its function bodies call.
struct FileScan {
  std::map<std::string, std::vector<std::string>> structSemantics;  // upper case
  std::vector<Function> functions;
  std::vector<Entry> compileShaders;  // effect files' CompileShader(target, Entry(...)), file unset
  std::set<std::string> called;
};

bool IsKeywordBeforeParen(const std::string& s) {
  static const std::set<std::string> k = {"register", "packoffset", "if", "for", "while", "switch", "return", "CompileShader"};
  return k.count(s) != 0;
}

// Parameter `[first, last)`: "out float4 c : SV_Target0", "inout TriangleStream<GSOut> s".
Param ParseParam(const compat::Source& s, size_t first, size_t last) {
  static const std::set<std::string> kModifiers = {"in", "uniform", "const", "linear", "nointerpolation", "centroid", "noperspective",
                                                   "sample", "precise", "point", "line", "triangle", "lineadj", "triangleadj"};
  Param p;
  for (size_t i = first; i < last; ++i) {
    const compat::Token& t = s[i];
    if (t.Is(":") && i + 1 < last && s[i + 1].IsIdentifier()) p.semantic = Upper(s[i + 1].text);
    if (!t.IsIdentifier()) continue;
    if (t.text == "out" || t.text == "inout") p.out = true;
    else if (p.type.empty() && !kModifiers.count(t.text)) p.type = t.text;
  }
  return p;
}

FileScan Scan(const std::string& text, const std::string& file) {
  compat::Source s(text, file);
  FileScan scan;
  auto isBoundary = [&](size_t i) {
    const compat::Token& t = s[i];
    return t.kind == compat::TokenKind::Directive || t.Is(";") || t.Is("}") || t.Is("{") || t.Is("]");
  };
  // Effect files name their entry points exactly; wherever CompileShader appears, at the top
  // level or in a pass.
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    if (!s[i].Is("CompileShader") || !s.Is(i + 1, "(")) continue;
    size_t close = s.Matching(i + 1);
    auto args = s.SplitCommas(i + 2, close);
    if (args.size() < 2 || args[0].first >= args[0].second) continue;
    for (size_t j = args[1].first; j < args[1].second; ++j)
      if (s[j].IsIdentifier()) {
        Entry e{"", s[j].text, s[args[0].first].text, s[i].line, {}, ""};
        size_t open = j + 1;
        if (s.Is(open, "(") && s.Matching(open) > open + 1 && s.Matching(open) < s.size()) e.uniformCall = s.Text(j, s.Matching(open) + 1);
        scan.compileShaders.push_back(std::move(e));
        break;
      }
  }
  for (size_t i = 0; i < s.size(); ++i) {
    const compat::Token& t = s[i];
    if (t.kind == compat::TokenKind::Directive) continue;
    if (t.Is("[")) {
      i = std::min(s.Matching(i), s.size() - 1);
      continue;
    }
    if (t.Is("struct") && i + 2 < s.size() && s[i + 1].IsIdentifier() && s.Is(i + 2, "{")) {
      size_t close = std::min(s.Matching(i + 2), s.size() - 1);
      std::vector<std::string>& sems = scan.structSemantics[s[i + 1].text];
      for (size_t j = i + 3; j + 1 < close; ++j)
        if (s[j].Is(":") && s[j + 1].IsIdentifier()) sems.push_back(Upper(s[j + 1].text));
      i = close;
      continue;
    }
    if (t.Is("{")) {  // cbuffers, technique blocks, anything else with a body
      i = std::min(s.Matching(i), s.size() - 1);
      continue;
    }
    if (!t.IsIdentifier() || !s.Is(i + 1, "(") || i == 0 || IsKeywordBeforeParen(t.text)) continue;
    if (!s[i - 1].IsIdentifier() && !s[i - 1].Is(">")) continue;  // a return type comes first
    size_t close = s.Matching(i + 1);
    if (close >= s.size()) break;
    size_t next = close + 1;
    while (next < s.size() && s[next].kind == compat::TokenKind::Directive) ++next;
    Function f;
    if (s.Is(next, ":") && next + 2 < s.size() && s[next + 1].IsIdentifier() && s.Is(next + 2, "{")) {
      f.semantic = Upper(s[next + 1].text);
      next += 2;
    }
    if (!s.Is(next, "{")) continue;  // a declaration or a call
    f.name = t.text;
    f.returnType = s[i - 1].text;
    f.line = t.line;
    for (auto [a, b] : s.SplitCommas(i + 2, close)) f.params.push_back(ParseParam(s, a, b));
    // Attributes: the bracket groups right before the return type and its modifiers.
    size_t j = i - 1;
    while (j > 0 && !isBoundary(j - 1)) --j;
    while (j > 0 && s[j - 1].Is("]")) {
      size_t open = s.MatchingOpen(j - 1);
      if (open >= s.size()) break;
      if (open + 1 < s.size() && s[open + 1].IsIdentifier()) f.attributes.push_back(s[open + 1].text);
      j = open;
    }
    size_t bodyEnd = std::min(s.Matching(next), s.size() - 1);
    for (size_t k = next; k + 1 < bodyEnd; ++k)
      if (s[k].IsIdentifier() && s.Is(k + 1, "(")) scan.called.insert(s[k].text);
    scan.functions.push_back(std::move(f));
    i = bodyEnd;
  }
  return scan;
}

bool IsPixelOutput(const std::string& sem) { return sem.rfind("SV_TARGET", 0) == 0 || sem.rfind("SV_DEPTH", 0) == 0; }

// The target of an entry point, or "" for an ordinary function. `structs` finds a struct's member
// semantics (the file's own, else any in the tree: output structs often live in an include).
std::string Classify(const Function& f, const std::function<const std::vector<std::string>*(const std::string&)>& structs) {
  for (const std::string& a : f.attributes) {
    std::string u = Upper(a);
    if (u == "NUMTHREADS") return "cs_5_0";
    if (u == "MAXVERTEXCOUNT") return "gs_5_0";
  }
  // Tessellation is not supported; listing hull and domain shaders (which then fail on their
  // target) says so in the report instead of calling their files include-only.
  auto hasAttribute = [&](const char* name) {
    return std::any_of(f.attributes.begin(), f.attributes.end(), [&](const std::string& a) { return Upper(a) == name; });
  };
  if (hasAttribute("PATCHCONSTANTFUNC") || hasAttribute("OUTPUTCONTROLPOINTS")) return "hs_5_0";
  if (hasAttribute("DOMAIN")) return "ds_5_0";
  auto has = [&](const std::string& type, auto pred) {
    const std::vector<std::string>* sems = structs(type);
    return sems && std::any_of(sems->begin(), sems->end(), pred);
  };
  auto isPosition = [](const std::string& s) { return s == "SV_POSITION"; };
  if (IsPixelOutput(f.semantic) || f.semantic.rfind("COLOR", 0) == 0) return "ps_5_0";
  if (isPosition(f.semantic)) return "vs_5_0";
  // A vertex shader's output struct may carry COLOR members too: SV_Position decides first.
  if (has(f.returnType, isPosition)) return "vs_5_0";
  if (has(f.returnType, IsPixelOutput)) return "ps_5_0";
  for (const Param& p : f.params) {
    if (!p.out) continue;
    if (IsPixelOutput(p.semantic)) return "ps_5_0";
    if (isPosition(p.semantic) || has(p.type, isPosition)) return "vs_5_0";
  }
  return "";
}

bool HasHlslExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

// Entry points found in the tree; `includeOnly` receives the files without one.
std::vector<Entry> FindEntries(const fs::path& dir, std::vector<std::string>* includeOnly) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied))
    if (e.is_regular_file() && HasHlslExtension(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<std::pair<std::string, FileScan>> scans;
  std::map<std::string, std::vector<std::string>> treeStructs;
  std::set<std::string> called;
  for (const fs::path& p : files) {
    std::string text = ReadFile(p);
    if (text.find('\0') != std::string::npos) continue;  // binary, whatever its name says
    std::string rel = p.lexically_relative(dir).generic_string();
    FileScan scan = Scan(text, rel);
    for (const auto& [name, sems] : scan.structSemantics) treeStructs.emplace(name, sems);
    called.insert(scan.called.begin(), scan.called.end());
    scans.push_back({rel, std::move(scan)});
  }
  std::vector<Entry> entries;
  for (const auto& [rel, scan] : scans) {
    std::set<std::pair<std::string, std::string>> seen;  // a function in both branches of an #if is one entry
    size_t before = entries.size();
    for (Entry e : scan.compileShaders) {
      e.file = rel;
      if (seen.insert({e.name, e.target}).second) entries.push_back(std::move(e));
    }
    if (entries.size() == before) {
      auto structs = [&](const std::string& type) -> const std::vector<std::string>* {
        auto it = scan.structSemantics.find(type);
        if (it != scan.structSemantics.end()) return &it->second;
        it = treeStructs.find(type);
        return it == treeStructs.end() ? nullptr : &it->second;
      };
      for (const Function& f : scan.functions) {
        if (called.count(f.name)) continue;  // a helper with semantics, called by the real entry
        std::string target = Classify(f, structs);
        if (!target.empty() && seen.insert({f.name, target}).second) entries.push_back({rel, f.name, target, f.line, {}, ""});
      }
    }
    if (entries.size() == before) includeOnly->push_back(rel);
  }
  return entries;
}

// `file entry target [-D NAME[=VALUE]]...` lines; '#' starts a comment.
std::vector<Entry> ReadManifest(const fs::path& manifest, const fs::path& dir) {
  std::ifstream in(manifest);
  if (!in) throw std::invalid_argument(manifest.string() + ": cannot open the manifest");
  std::vector<Entry> entries;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w.empty()) continue;
    std::string where = manifest.string() + ":" + std::to_string(n) + ": ";
    if (w.size() < 3) throw std::invalid_argument(where + "expected 'file entry target [-D NAME[=VALUE]]...'");
    Entry e{w[0], w[1], w[2], 0, {}, ""};
    for (size_t i = 3; i < w.size(); ++i) {
      if (w[i].rfind("-D", 0) != 0) throw std::invalid_argument(where + "unexpected '" + w[i] + "' (only -D NAME[=VALUE] may follow the target)");
      if (w[i] == "-D" && i + 1 >= w.size()) throw std::invalid_argument(where + "-D needs a value");
      e.defines.push_back(ParseDefine(w[i] == "-D" ? w[++i] : w[i].substr(2)));
    }
    if (!fs::is_regular_file(dir / e.file)) throw std::invalid_argument(where + (dir / e.file).string() + ": no such file");
    entries.push_back(std::move(e));
  }
  return entries;
}

// ---- Compiling --------------------------------------------------------------------------------

// A diagnostic's file as the report shows it: relative to the surveyed folder where it is inside.
std::string ShowPath(const std::string& file, const fs::path& dir) {
  if (file.empty()) return file;
  fs::path rel = fs::path(file).lexically_relative(dir);
  std::string r = rel.generic_string();
  return rel.empty() || r.rfind("..", 0) == 0 ? file : r;
}

Outcome CompileEntry(const Entry& e, const Options& o) {
  hlsl::CompileOptions opt = o.compile;
  opt.entryPoint = e.name;
  opt.target = e.target;
  opt.defines.insert(opt.defines.end(), e.defines.begin(), e.defines.end());
  fs::path path = o.dir / e.file;
  Outcome r;
  try {
    hlsl::CompileFile(path, opt);
    r.ok = true;
    // Compiling does not say which rewrites it needed; preprocessing again does, and is cheap.
    hlsl::Preprocess(ReadFile(path), path.string(), opt, &r.rewrites);
  } catch (const hlsl::CompileError& err) {
    if (r.ok) return r;  // compiled; the rewrites are unknown, which the report can live with
    const std::vector<hlsl::Diagnostic>& d = err.diagnostics();
    if (!d.empty()) {
      r.where = ShowPath(d[0].file, o.dir) + (d[0].line > 0 ? ":" + std::to_string(d[0].line) : "");
      r.message = d[0].message;
      while (!r.message.empty() && std::isspace(static_cast<unsigned char>(r.message.back()))) r.message.pop_back();
    } else {
      r.where = e.file;
      r.message = err.what();
    }
  } catch (const std::exception& err) {
    if (r.ok) return r;
    r.where = e.file;
    r.message = err.what();
  }
  if (r.where.empty()) r.where = e.file;
  return r;
}

// ---- The report -------------------------------------------------------------------------------

// One cause for messages that differ only in names, numbers and places: "'foo' : undeclared
// identifier" and "'bar' : undeclared identifier" are the same problem twice.
std::string Normalize(const std::string& message) {
  std::string m = message, out;
  // A leading "file:line: " (messages taken from what()).
  size_t colon = m.find(": ");
  if (colon != std::string::npos) {
    size_t c2 = m.rfind(':', colon - 1);
    if (c2 != std::string::npos && c2 + 1 < colon &&
        std::all_of(m.begin() + long(c2) + 1, m.begin() + long(colon), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      m = m.substr(colon + 2);
  }
  if (m.rfind("error: ", 0) == 0) m = m.substr(7);
  for (size_t i = 0; i < m.size(); ++i) {
    char c = m[i];
    if (c == '\'' || c == '"') {
      size_t e = m.find(c, i + 1);
      if (e != std::string::npos) {
        out += c;
        out += "...";
        out += c;
        i = e;
        continue;
      }
    }
    if (c == '%' && i + 1 < m.size() && (std::isalnum(static_cast<unsigned char>(m[i + 1])) || m[i + 1] == '_')) {
      while (i + 1 < m.size() && (std::isalnum(static_cast<unsigned char>(m[i + 1])) || m[i + 1] == '_')) ++i;
      out += "%...";  // spirv-val names the shader's own variables
      continue;
    }
    bool wordStart = i == 0 || !(std::isalnum(static_cast<unsigned char>(m[i - 1])) || m[i - 1] == '_');
    // Unquoted file names ("... header name: sdsm/analysis.hlsli") differ per file, not per cause.
    if (wordStart && !std::isspace(static_cast<unsigned char>(c))) {
      size_t e = i;
      while (e < m.size() && !std::isspace(static_cast<unsigned char>(m[e]))) ++e;
      std::string word = m.substr(i, e - i);
      if (word.find('/') != std::string::npos || word.find('\\') != std::string::npos || HasHlslExtension(fs::path(word))) {
        out += "FILE";
        i = e - 1;
        continue;
      }
    }
    if (std::isdigit(static_cast<unsigned char>(c)) && wordStart) {
      while (i + 1 < m.size() && (std::isalnum(static_cast<unsigned char>(m[i + 1])) || m[i + 1] == '.')) ++i;
      out += 'N';
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!out.empty() && out.back() != ' ') out += ' ';
      continue;
    }
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// What to do about causes seen in real trees (matched on the normalised message).
const char* Hint(const std::string& cause) {
  struct KnownCause {
    const char* text;
    const char* hint;
  };
  static const KnownCause kKnown[] = {
      {"unknown variable",
       "a name declared nowhere the compiler looked: usually a define the build passes (survey with its -D), an include "
       "folder (-I), or a declaration the including file provides (list the real permutations in a --manifest)"},
      {"undeclared identifier",
       "a name declared nowhere the compiler looked: usually a define the build passes (survey with its -D), an include "
       "folder (-I), or a function the including file provides (list the real permutations in a --manifest)"},
      {"unknown target", "hull and domain shaders and Shader Model 2/3 targets are not supported; see docs/porting.md, Targets"},
      {"Entry point not found", "the entry point is not in the compiled source: it may exist only under a define (pass -D) or be misdetected (use a --manifest)"},
      {"entry point", "the entry point is not in the compiled source: it may exist only under a define (pass -D) or be misdetected (use a --manifest)"},
      {"include", "an #include that was not found: pass the folders the build searches with -I"},
      {"no matching overloaded function",
       "a call to a function declared nowhere the compiler looked (a missing include, or one the including file provides: "
       "list the real permutations in a --manifest), or one fxc resolves with an implicit conversion glslang does not "
       "(add an explicit cast)"},
      {"spirv-val", "glslang produced SPIR-V the validator rejects: see docs/porting.md, What to know when bringing existing shaders"},
  };
  for (const KnownCause& k : kKnown)
    if (cause.find(k.text) != std::string::npos) return k.hint;
  return nullptr;
}

// Effect-file syntax fails with whatever glslang expected at that point ("'declaration' :
// Expected"), so it is recognised from the line the diagnostic names instead of the message.
bool IsEffectSyntax(const std::string& where, const fs::path& dir) {
  size_t colon = where.rfind(':');
  if (colon == std::string::npos) return false;
  fs::path file = dir / where.substr(0, colon);
  int line = std::atoi(where.c_str() + colon + 1);
  std::ifstream in(file);
  std::string text;
  for (int n = 1; n <= line && std::getline(in, text); ++n) {
  }
  if (!in) return false;
  for (const char* word : {"technique", "pass ", "sampler_state", "BlendState", "DepthStencilState", "RasterizerState", "CompileShader"})
    if (text.find(word) != std::string::npos) return true;
  return false;
}

const char kEffectHint[] =
    "effect-file syntax (technique/pass blocks, state objects) outside what the effect-blocks rewrite reads: a fragment "
    "of a block (an .fxh included inside a pass) is not a shader on its own; other cases: `hlslc --fx FILE` names the "
    "construct";

const char kUniformCallHint[] =
    "the technique passes uniform arguments (see the Entry column): compiled on its own, the function takes them as "
    "shader inputs, which fails or means something else; an effect compiles such a pass with the arguments bound";

// Markdown table cells: no pipes, no newlines.
std::string Cell(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '|') r += "\\|";
    else if (c == '\n' || c == '\r') r += ' ';
    else r += c;
  }
  return r;
}

std::string Percent(size_t n, size_t total) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", total ? 100.0 * double(n) / double(total) : 0.0);
  return buf;
}

std::string OptionsText(const Options& o) {
  std::string s;
  for (const hlsl::Define& d : o.compile.defines) s += " -D " + d.name + (d.value.empty() ? "" : "=" + d.value);
  for (const fs::path& p : o.compile.includeDirs) s += " -I " + p.string();
  if (o.compile.flags1 & hlsl::COMPILE_PACK_MATRIX_ROW_MAJOR) s += " -Zpr";
  if (o.compile.flags1 & hlsl::COMPILE_PACK_MATRIX_COLUMN_MAJOR) s += " -Zpc";
  if (!o.manifest.empty()) s += " --manifest " + o.manifest.string();
  return s.empty() ? "none" : s.substr(1);
}

struct Cause {
  std::string text;
  size_t count = 0;
  size_t example = 0;  // index into the entries
};

}  // namespace

int RunHlslcSurvey(const std::vector<std::string>& argv) {
  Options o = Parse(argv);
  if (o.help) {
    std::fputs(kSurveyUsage, stdout);
    return 0;
  }
  std::vector<std::string> includeOnly;
  std::vector<Entry> entries = o.manifest.empty() ? FindEntries(o.dir, &includeOnly) : ReadManifest(o.manifest, o.dir);
  std::vector<Outcome> outcomes;
  for (const Entry& e : entries) {
    // A large tree takes a while: say how far it got.
    std::fprintf(stderr, "survey [%zu/%zu] %s %s %s\n", outcomes.size() + 1, entries.size(), e.file.c_str(), e.name.c_str(), e.target.c_str());
    outcomes.push_back(CompileEntry(e, o));
  }

  size_t ok = size_t(std::count_if(outcomes.begin(), outcomes.end(), [](const Outcome& r) { return r.ok; }));
  size_t failed = outcomes.size() - ok;
  std::vector<Cause> causes;
  std::map<std::string, size_t> rewriteUse;
  for (size_t i = 0; i < outcomes.size(); ++i) {
    for (const std::string& r : outcomes[i].rewrites) ++rewriteUse[r];
    if (outcomes[i].ok) continue;
    std::string c = Normalize(outcomes[i].message);
    auto it = std::find_if(causes.begin(), causes.end(), [&](const Cause& x) { return x.text == c; });
    if (it == causes.end()) causes.push_back({c, 1, i});
    else ++it->count;
  }
  std::stable_sort(causes.begin(), causes.end(), [](const Cause& a, const Cause& b) { return a.count > b.count; });

  std::ostringstream md;
  std::set<std::string> filesWithEntries;
  for (const Entry& e : entries) filesWithEntries.insert(e.file);
  md << "# HLSL survey of " << o.dir.string() << "\n\n";
  auto count = [](size_t n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); };
  md << "- **" << count(entries.size(), "entry point") << "** in " << count(filesWithEntries.size(), "file");
  if (o.manifest.empty()) md << " (and " << count(includeOnly.size(), "include-only file") << ")";
  md << ": **" << ok << " compile (" << Percent(ok, entries.size()) << ")**, " << failed << " fail";
  if (failed) md << " (" << count(causes.size(), "cause") << ")";
  md << ".\n";
  md << "- Entry points " << (o.manifest.empty() ? "found from function signatures and effect-file CompileShader calls" : "listed in the manifest")
     << "; options: `" << OptionsText(o) << "`.\n\n";

  md << "## Failures by cause\n\n";
  if (causes.empty()) md << "None.\n\n";
  for (const Cause& c : causes) {
    const Entry& e = entries[c.example];
    const Outcome& r = outcomes[c.example];
    md << "### " << c.count << " x `" << c.text << "`\n\n";
    md << "- Example: `" << Cell(r.where + ": " + r.message) << "` (" << e.file << ", " << e.name << ", " << e.target << ")\n";
    const char* hint = e.uniformCall.empty() ? Hint(c.text) : kUniformCallHint;
    if (!hint && IsEffectSyntax(r.where, o.dir)) hint = kEffectHint;
    if (hint) md << "- Hint: " << hint << "\n";
    md << "\n";
  }

  md << "## Compatibility rewrites used\n\n";
  if (rewriteUse.empty()) md << "None: every entry point that compiles is accepted by glslang as written.\n\n";
  else {
    md << "| Rewrite | Entry points | What fxc accepts that glslang does not |\n|---|---|---|\n";
    for (const hlsl::compat::Rewrite& rw : hlsl::compat::Rewrites()) {
      auto it = rewriteUse.find(rw.name);
      if (it != rewriteUse.end()) md << "| " << rw.name << " | " << it->second << " | " << Cell(rw.summary) << " |\n";
    }
    md << "\n";
  }

  md << "## Per file\n\n| File | Entry | Target | Result |\n|---|---|---|---|\n";
  std::vector<std::pair<std::string, std::string>> rows;  // (file, row), include-only files in their place
  for (size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    const Outcome& r = outcomes[i];
    std::string name = e.uniformCall.empty() ? e.name : e.name + " (technique: " + e.uniformCall + ")";
    for (const hlsl::Define& d : e.defines) name += " -D" + d.name + (d.value.empty() ? "" : "=" + d.value);
    std::string result;
    if (r.ok) {
      result = "ok";
      if (!r.rewrites.empty()) {
        result += " (rewrites:";
        for (const std::string& w : r.rewrites) result += " " + w;
        result += ")";
      }
    } else {
      result = "**failed**: " + r.where + ": " + r.message;
    }
    rows.push_back({e.file, "| " + Cell(e.file + (e.line ? ":" + std::to_string(e.line) : "")) + " | " + Cell(name) + " | " + e.target +
                                " | " + Cell(result) + " |\n"});
  }
  for (const std::string& f : includeOnly) rows.push_back({f, "| " + Cell(f) + " | - | - | include-only (no entry point found) |\n"});
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& row : rows) md << row.second;

  std::ofstream out(o.out, std::ios::binary);
  if (!(out << md.str())) throw std::runtime_error(o.out.string() + ": cannot write the report");
  std::printf("survey %s: %zu entry points, %zu ok (%s), %zu failed (%zu %s); report: %s\n", o.dir.string().c_str(), entries.size(), ok,
              Percent(ok, entries.size()).c_str(), failed, causes.size(), causes.size() == 1 ? "cause" : "causes", o.out.string().c_str());
  return 0;
}

}  // namespace sp::cli
