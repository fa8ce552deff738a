#include "symbolic_apart.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

namespace semo::checker::detail {
namespace {

// What goes through the pipe: frames of a type byte, a 32-bit size and the payload, written and
// read by the same program (no versioning needed), in the machine's byte order.
constexpr char kProgressFrame = 'P';
constexpr char kOutcomeFrame = 'R';

std::atomic<std::uint64_t> childSearches{0};

class Writer {
 public:
  template <class T>
  void put(T value) {
    out_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void put(const std::string& s) {
    put(static_cast<std::uint32_t>(s.size()));
    out_ += s;
  }
  [[nodiscard]] const std::string& bytes() const { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& in) : in_(in) {}
  template <class T>
  T get() {
    T value{};
    if (in_.size() - at_ < sizeof value) throw std::runtime_error("a short frame from the symbolic search's process");
    std::memcpy(&value, in_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }
  std::string text() {
    const auto n = get<std::uint32_t>();
    if (in_.size() - at_ < n) throw std::runtime_error("a short frame from the symbolic search's process");
    std::string s = in_.substr(at_, n);
    at_ += n;
    return s;
  }

 private:
  const std::string& in_;
  std::size_t at_ = 0;
};

std::string encode(const Progress& p) {
  Writer w;
  w.put(p.states);
  w.put(p.transitions);
  w.put(p.bytes);
  w.put(p.depth);
  w.put(p.seconds);
  w.put(static_cast<std::uint8_t>(p.counted));
  return w.bytes();
}

Progress decodeProgress(const std::string& frame) {
  Reader r(frame);
  Progress p;
  p.states = r.get<std::uint64_t>();
  p.transitions = r.get<std::uint64_t>();
  p.bytes = r.get<std::uint64_t>();
  p.depth = r.get<std::uint32_t>();
  p.seconds = r.get<double>();
  p.counted = r.get<std::uint8_t>() != 0;
  return p;
}

std::string encode(const SymbolicOutcome& o) {
  Writer w;
  w.put(static_cast<std::uint8_t>(o.kind));
  w.put(o.reachable);
  w.put(o.worlds);
  w.put(o.openPoints);
  w.put(static_cast<std::uint8_t>(o.overApproximated));
  w.put(o.why);
  w.put(o.seconds);
  w.put(static_cast<std::uint8_t>(o.lasso.has_value()));
  if (o.lasso) {
    const Trace& t = *o.lasso;
    w.put(t.property);
    w.put(t.kind);
    w.put(static_cast<std::uint32_t>(t.initial.size()));
    for (std::int32_t v : t.initial) w.put(v);
    w.put(static_cast<std::uint32_t>(t.steps.size()));
    for (const Step& s : t.steps) {
      w.put(static_cast<std::uint64_t>(s.rule));
      w.put(static_cast<std::uint64_t>(s.branch));
      w.put(static_cast<std::uint32_t>(s.changes.size()));
      for (const Change& c : s.changes) {
        w.put(static_cast<std::uint32_t>(c.var));
        w.put(c.before);
        w.put(c.after);
      }
    }
    w.put(static_cast<std::uint64_t>(t.loopStart));
  }
  return w.bytes();
}

SymbolicOutcome decodeOutcome(const std::string& frame) {
  Reader r(frame);
  SymbolicOutcome o;
  o.kind = static_cast<SymbolicOutcome::Kind>(r.get<std::uint8_t>());
  o.reachable = r.get<double>();
  o.worlds = r.get<std::uint32_t>();
  o.openPoints = r.get<std::uint32_t>();
  o.overApproximated = r.get<std::uint8_t>() != 0;
  o.why = r.text();
  o.seconds = r.get<double>();
  if (r.get<std::uint8_t>() == 0) return o;
  Trace t;
  t.property = r.text();
  t.kind = r.text();
  for (auto n = r.get<std::uint32_t>(); n > 0; --n) t.initial.push_back(r.get<std::int32_t>());
  for (auto n = r.get<std::uint32_t>(); n > 0; --n) {
    Step s;
    s.rule = static_cast<std::size_t>(r.get<std::uint64_t>());
    s.branch = static_cast<std::size_t>(r.get<std::uint64_t>());
    for (auto c = r.get<std::uint32_t>(); c > 0; --c) {
      Change change{};
      change.var = r.get<std::uint32_t>();
      change.before = r.get<std::int32_t>();
      change.after = r.get<std::int32_t>();
      s.changes.push_back(change);
    }
    t.steps.push_back(std::move(s));
  }
  t.loopStart = static_cast<std::size_t>(r.get<std::uint64_t>());
  o.lasso = std::move(t);
  return o;
}

// The child's side: whole frames or nothing; a pipe that broke means the parent is gone.
void writeFrame(int fd, char type, const std::string& payload) {
  std::string frame(1, type);
  const auto size = static_cast<std::uint32_t>(payload.size());
  frame.append(reinterpret_cast<const char*>(&size), sizeof size);
  frame += payload;
  for (std::size_t done = 0; done < frame.size();) {
    const ssize_t n = ::write(fd, frame.data() + done, frame.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);
    done += static_cast<std::size_t>(n);
  }
}

// The parent's side: false at the end of the stream.
bool readExactly(int fd, char* into, std::size_t size) {
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::read(fd, into + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// In the child: only this thread exists, a copy of the parent's memory around it. The search
// touches its own objects and a package of its own; nothing else of the parent's state is used,
// and the child ends with _exit, leaving the parent's buffers and exit handlers alone.
[[noreturn]] void runChild(int fd, pid_t parent, const SymbolicLimits& limits, const SymbolicSearch& search) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a child outliving its parent would search for nobody
  if (::getppid() != parent) ::_exit(4);
  SymbolicLimits mine = limits;
  if (limits.onProgress) mine.onProgress = [fd](const Progress& p) { writeFrame(fd, kProgressFrame, encode(p)); };
  SymbolicOutcome out;
  try {
    out = search(mine);
  } catch (const std::exception& e) {
    out = SymbolicOutcome{};
    out.why = std::string("internal error: ") + e.what();
  }
  writeFrame(fd, kOutcomeFrame, encode(out));
  ::_exit(0);
}

std::string howItEnded(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return "the symbolic search's process was ended by signal " + std::to_string(sig) + (name != nullptr ? std::string(" (") + name + ")" : "");
  }
  return "the symbolic search's process ended without an answer (exit code " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
}

}  // namespace

std::optional<SymbolicOutcome> searchInChildProcess(const SymbolicLimits& limits, const SymbolicSearch& search) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return std::nullopt;
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    runChild(fds[1], parent, limits, search);
  }
  ::close(fds[1]);
  if (pid < 0) {
    ::close(fds[0]);
    return std::nullopt;
  }
  ++childSearches;
  SymbolicOutcome out;
  bool answered = false;
  std::string why;
  try {
    while (true) {
      char header[5];
      if (!readExactly(fds[0], header, sizeof header)) break;
      std::uint32_t size = 0;
      std::memcpy(&size, header + 1, sizeof size);
      std::string payload(size, '\0');
      if (!readExactly(fds[0], payload.data(), size)) break;
      if (header[0] == kProgressFrame) {
        if (limits.onProgress) limits.onProgress(decodeProgress(payload));
      } else if (header[0] == kOutcomeFrame) {
        // Done: not waiting for the end of the stream, which a sibling child forked meanwhile by
        // another thread holds open (its copy of this pipe's writing end) until it ends.
        out = decodeOutcome(payload);
        answered = true;
        break;
      }
    }
  } catch (const std::exception& e) {
    why = e.what();
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (answered && why.empty()) return out;
  SymbolicOutcome failed;
  failed.why = why.empty() ? howItEnded(status) : why;
  return failed;
}

std::uint64_t searchesInChildProcesses() { return childSearches.load(); }

}  // namespace semo::checker::detail
