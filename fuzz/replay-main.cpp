// Drives a fuzz target without libFuzzer (gcc builds, the test suite): every file of the given
// corpus files and folders, then `--mutations N` inputs made from them by deterministic random
// edits (bit flips, byte insertions and deletions, repeated and spliced chunks, boundary
// values). What it finds is whatever the target finds, only far less of it than libFuzzer with
// coverage would; its job in the test suite is to keep the targets building and their seeds
// passing, and to catch the shallow regressions.
//   <target> [--mutations N] [--seed S] [--max-len BYTES] corpus...
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "fuzz-target.h"

namespace {

// The input being run, for the crash handler: like libFuzzer, a crash leaves the input that
// caused it in ./crash-input, so it can become a regression seed.
const uint8_t* gCurrent = nullptr;
size_t gCurrentSize = 0;

extern "C" void OnCrash(int sig) {
  int fd = open("crash-input", O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    ssize_t ignored = write(fd, gCurrent, gCurrentSize);
    (void)ignored;
    close(fd);
  }
  const char msg[] = "replay: crashed; the input is in ./crash-input\n";
  ssize_t ignored = write(2, msg, sizeof msg - 1);
  (void)ignored;
  signal(sig, SIG_DFL);
  raise(sig);
}

void Run(const std::vector<uint8_t>& d) {
  gCurrent = d.data();
  gCurrentSize = d.size();
  LLVMFuzzerTestOneInput(d.data(), d.size());
}

std::vector<uint8_t> ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void Mutate(std::vector<uint8_t>& d, const std::vector<std::vector<uint8_t>>& corpus, std::mt19937_64& rng, size_t maxLen) {
  auto pick = [&](size_t n) { return n ? size_t(rng() % n) : 0; };
  static const uint8_t kInteresting[] = {0, 1, 0x7f, 0x80, 0xff, '{', '}', '[', ']', '"', ':', ',', '\n', '=', '-', '9', '/', '#'};
  int edits = 1 + int(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    switch (rng() % 6) {
      case 0:
        if (!d.empty()) d[pick(d.size())] ^= uint8_t(1u << (rng() % 8));
        break;
      case 1:
        d.insert(d.begin() + long(pick(d.size() + 1)), kInteresting[pick(sizeof kInteresting)]);
        break;
      case 2:
        if (!d.empty()) {
          size_t at = pick(d.size()), n = 1 + pick(std::min<size_t>(d.size() - at, 16));
          d.erase(d.begin() + long(at), d.begin() + long(at + n));
        }
        break;
      case 3:
        if (!d.empty()) {  // repeat a chunk (deep nesting, long lists)
          size_t at = pick(d.size()), n = 1 + pick(std::min<size_t>(d.size() - at, 32));
          std::vector<uint8_t> chunk(d.begin() + long(at), d.begin() + long(at + n));
          for (int r = int(1 + rng() % 8); r > 0; --r) d.insert(d.begin() + long(at), chunk.begin(), chunk.end());
        }
        break;
      case 4: {  // splice in a piece of another input
        const std::vector<uint8_t>& o = corpus[pick(corpus.size())];
        if (!o.empty()) {
          size_t at = pick(o.size()), n = 1 + pick(std::min<size_t>(o.size() - at, 64));
          d.insert(d.begin() + long(pick(d.size() + 1)), o.begin() + long(at), o.begin() + long(at + n));
        }
        break;
      }
      default:
        if (!d.empty()) d[pick(d.size())] = kInteresting[pick(sizeof kInteresting)];
        break;
    }
  }
  if (d.size() > maxLen) d.resize(maxLen);
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 0;
  unsigned long long seed = 1;
  size_t maxLen = 1 << 16;
  std::vector<std::vector<uint8_t>> corpus;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if ((a == "--mutations" || a == "--seed" || a == "--max-len") && i + 1 < argc) {
      unsigned long long v = std::strtoull(argv[++i], nullptr, 10);
      (a == "--mutations" ? (void)(mutations = long(v)) : a == "--seed" ? (void)(seed = v) : (void)(maxLen = size_t(v)));
      continue;
    }
    std::filesystem::path p(a);
    if (std::filesystem::is_directory(p)) {
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::recursive_directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());  // the same order, so the same mutations, every run
      for (const auto& f : files) corpus.push_back(ReadFile(f));
    } else if (std::filesystem::is_regular_file(p)) {
      corpus.push_back(ReadFile(p));
    } else {
      std::fprintf(stderr, "%s: no such corpus file or folder: %s\n", argv[0], a.c_str());
      return 2;
    }
  }
  if (corpus.empty()) corpus.emplace_back();
  for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL}) signal(sig, OnCrash);
  for (const auto& c : corpus) Run(c);
  std::mt19937_64 rng(seed);
  for (long m = 0; m < mutations; ++m) {
    std::vector<uint8_t> d = corpus[rng() % corpus.size()];
    Mutate(d, corpus, rng, maxLen);
    Run(d);
  }
  std::printf("%s: %zu corpus inputs and %ld mutations ran without a finding\n", argv[0], corpus.size(), mutations);
  return 0;
}
