// Runs a piece of work in a forked child process and returns the bytes it produced, so that a
// crash or a hang in a library we do not control (glslang: "not written as an HLSL validator",
// in its maintainers' words, and some invalid sources crash it) becomes an error for the caller
// instead of taking the user's program down.
//
// The child is a copy of the caller at the time of the call: it sees the same memory, files and
// globals, runs `work` on the calling thread only, writes its result to a pipe and leaves with
// _exit (no destructors, no atexit handlers: nothing of the parent's device or driver state is
// touched). Nothing the child changes reaches the parent except those bytes, so `work` must
// return everything the caller needs. glibc's fork keeps malloc usable in the child of a
// multi-threaded parent, which is all the work here needs.
#pragma once
#include <functional>
#include <string>

namespace sp::hlsl::isolation {

struct IsolatedResult {
  bool completed = false;  // the child returned normally; `bytes` is what work() returned
  int signal = 0;          // the signal that ended the child (SIGSEGV, SIGABRT, ...), 0 if none
  bool timedOut = false;   // killed after `timeoutSeconds`
  std::string bytes;
  std::string failure;     // why no result came back, in words ("crashed with signal 11 (Segmentation fault)")
};

// `work` may throw: the exception's what() comes back as `failure` with completed = false.
IsolatedResult RunIsolated(const std::function<std::string()>& work, unsigned timeoutSeconds);

// Length-prefixed fields for what crosses the pipe.
void PutString(std::string& out, const std::string& s);
void PutU32(std::string& out, uint32_t v);
class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : b_(bytes) {}
  uint32_t U32();
  std::string String();
  bool ok() const { return ok_; }

 private:
  const std::string& b_;
  size_t at_ = 0;
  bool ok_ = true;
};

}  // namespace sp::hlsl::isolation
