// See isolated-run.h.
#include "isolated-run.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <sys/wait.h>
#include <unistd.h>

namespace sp::hlsl::isolation {

namespace {

bool WriteAll(int fd, const char* p, size_t n) {
  while (n > 0) {
    ssize_t w = write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w, n -= size_t(w);
  }
  return true;
}

}  // namespace

IsolatedResult RunIsolated(const std::function<std::string()>& work, unsigned timeoutSeconds) {
  IsolatedResult r;
  int fds[2];
  if (pipe(fds) != 0) {
    r.failure = std::string("pipe() failed: ") + std::strerror(errno);
    return r;
  }
  pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]), close(fds[1]);
    r.failure = std::string("fork() failed: ") + std::strerror(errno);
    return r;
  }
  if (pid == 0) {
    close(fds[0]);
    // The parent's crash handlers (a fuzzer's, a sanitizer's, an application's) would report the
    // child's crash as the parent's own: the child dies plainly and the parent reports it.
    for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGALRM}) signal(sig, SIG_DFL);
    alarm(timeoutSeconds);  // a hang becomes SIGALRM
    std::string out;
    char status = 0;
    try {
      out = work();
    } catch (const std::exception& e) {
      status = 1, out = e.what();
    } catch (...) {
      status = 1, out = "an exception that is not a std::exception";
    }
    bool ok = WriteAll(fds[1], &status, 1) && WriteAll(fds[1], out.data(), out.size());
    close(fds[1]);
    _exit(ok ? 0 : 3);
  }
  close(fds[1]);
  std::string got;
  char buf[65536];
  for (;;) {
    ssize_t n = read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got.append(buf, size_t(n));
  }
  close(fds[0]);
  int st = 0;
  while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(st)) {
    r.signal = WTERMSIG(st);
    r.timedOut = r.signal == SIGALRM;
    r.failure = r.timedOut ? "took more than " + std::to_string(timeoutSeconds) + " s and was stopped"
                           : "crashed with signal " + std::to_string(r.signal) + " (" + strsignal(r.signal) + ")";
    return r;
  }
  if (!WIFEXITED(st) || WEXITSTATUS(st) != 0 || got.empty()) {
    r.failure = "ended without a result (exit status " + std::to_string(WIFEXITED(st) ? WEXITSTATUS(st) : -1) + ")";
    return r;
  }
  if (got[0] != 0) {
    r.failure = got.substr(1);
    return r;
  }
  r.completed = true;
  r.bytes = got.substr(1);
  return r;
}

void PutU32(std::string& out, uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

void PutString(std::string& out, const std::string& s) {
  PutU32(out, uint32_t(s.size()));
  out += s;
}

uint32_t ByteReader::U32() {
  if (!ok_ || b_.size() - at_ < 4) {
    ok_ = false;
    return 0;
  }
  uint32_t v;
  std::memcpy(&v, b_.data() + at_, 4);
  at_ += 4;
  return v;
}

std::string ByteReader::String() {
  uint32_t n = U32();
  if (!ok_ || b_.size() - at_ < n) {
    ok_ = false;
    return {};
  }
  std::string s = b_.substr(at_, n);
  at_ += n;
  return s;
}

}  // namespace sp::hlsl::isolation
