// SPDX-License-Identifier: GPL-3.0-or-later
// The command line's platform layer on Linux and other POSIX systems: files (file_io.hpp),
// the process's arguments, streams and memory (console.hpp), and the allocation function
// that asks for huge pages.
#include <fcntl.h>

#include <fmt/format.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <sys/syscall.h>
#endif

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include "arcpress/core/error.hpp"
#include "console.hpp"
#include "file_io.hpp"

namespace arcpress::cli {
namespace {

/// The temporary files being written (one per program a batch writes at once), for the
/// signal handler: a slot's name is set before its file exists, and the slot freed once the
/// file is renamed or removed. Fixed buffers, as a handler may only read memory.
constexpr size_t kTemporarySlots = 1024;  // programs written at once: at most kMaxThreads
struct TemporarySlot {
  std::atomic<int> state{0};  // 0 free, 1 taken, 2 its file may exist
  char name[PATH_MAX + 32] = {};
};
TemporarySlot g_temporaries[kTemporarySlots];

int take_slot() {
  for (size_t k = 0; k < kTemporarySlots; ++k) {
    int free = 0;
    if (g_temporaries[k].state.compare_exchange_strong(free, 1)) return int(k);
  }
  return -1;
}

void free_slot(int& slot) {
  if (slot >= 0) g_temporaries[slot].state = 0;
  slot = -1;
}
/// Whether standard output has failed: nothing more is written there.
bool g_stdout_failed = false;

extern "C" void on_fatal_signal(int sig) {
  for (TemporarySlot& t : g_temporaries)
    if (t.state.load() == 2) ::unlink(t.name);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

std::string error_text(int err) { return std::strerror(err); }

/// Writes all of `data` to `fd`; returns 0 or the errno of the failure, and adds the bytes
/// that were written to `done`.
int write_all(int fd, std::string_view data, size_t& done) {
  for (size_t at = 0; at < data.size();) {
    const ssize_t n = ::write(fd, data.data() + at, data.size() - at);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    at += size_t(n);
    done += size_t(n);
  }
  return 0;
}

/// `path` with its symbolic links resolved, or empty where that fails (a dangling link).
std::string resolved(const std::string& path) {
  char buf[PATH_MAX];
  return ::realpath(path.c_str(), buf) ? std::string(buf) : std::string();
}

/// A destination that is written as it is: a device, FIFO or socket, or anything under
/// /dev or /proc (/dev/stdout and /dev/fd/N name whatever the descriptor is).
bool written_in_place(const std::string& path, const struct stat* st) {
  if (path.rfind("/dev/", 0) == 0 || path.rfind("/proc/", 0) == 0) return true;
  return st && !S_ISREG(st->st_mode) && !S_ISDIR(st->st_mode);
}

}  // namespace

/// OutputFile's steps that need the system's types.
struct OutputFileSystem {
  static void note_start(OutputFile& f);
  static void open_temporary(OutputFile& f, const std::string& target, const struct stat* old);
};

InputFile::InputFile(const std::string& path) : name_(path == "-" ? "standard input" : "'" + path + "'") {
  handle_ = path == "-" ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (handle_ < 0) throw Error(kExitIo, fmt::format("cannot open {}: {}", name_, error_text(errno)));
  owned_ = handle_ != STDIN_FILENO;
  struct stat st {};
  if (::fstat(int(handle_), &st) == 0 && S_ISDIR(st.st_mode)) {
    if (owned_) ::close(int(handle_));
    throw Error(kExitIo, fmt::format("cannot read {}: it is a folder", name_));
  }
  if (S_ISREG(st.st_mode)) {
    const off_t at = ::lseek(int(handle_), 0, SEEK_CUR);
    size_ = size_t(st.st_size) - size_t(at > 0 ? at : 0);
    start_ = at > 0 ? at : 0;
  }
}

InputFile::~InputFile() {
  if (owned_) ::close(int(handle_));
}

size_t InputFile::read(std::string& into, size_t max) {
  max = asked(max);
  const size_t had = into.size();
  into.resize(had + max);
  for (;;) {
    const ssize_t n = ::read(int(handle_), into.data() + had, max);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      into.resize(had);
      throw Error(kExitIo, fmt::format("cannot read {}: {}", name_, error_text(err)));
    }
    into.resize(had + size_t(n));
    taken_ += size_t(n);
    return size_t(n);
  }
}

std::string InputFile::read_at(size_t offset, size_t n) const {
  if (!size_ || offset >= *size_) return {};
  const size_t len = std::min(n, *size_ - offset);
  std::string out(len, '\0');
  size_t got = 0;
  while (got < len) {
    const ssize_t k = ::pread(int(handle_), out.data() + got, len - got, off_t(start_ + offset + got));
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) break;
    got += size_t(k);
  }
  out.resize(got);
  return out;
}

void InputFile::spool() {
  if (size_) return;
  const char* env = std::getenv("TMPDIR");
  const std::string folder = env && *env ? env : "/tmp";
  std::string path = folder + "/arcpress-input-XXXXXX";
  const int fd = ::mkstemp(path.data());
  auto fail = [&](int err) {
    if (fd >= 0) ::close(fd);
    return Error(kExitIo, fmt::format("cannot keep {} in a temporary file in '{}' to read it whole: {} (set TMPDIR "
                                      "to another folder, or give --stream)",
                                      name_, folder, error_text(err)));
  };
  if (fd < 0) throw fail(errno);
  ::unlink(path.c_str());  // (unnamed from here: nothing is left behind, whatever happens)
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  const size_t total = copy_rest([&](std::string_view data) {
    for (size_t put = 0; put < data.size();) {
      const ssize_t k = ::write(fd, data.data() + put, data.size() - put);
      if (k < 0 && errno == EINTR) continue;
      if (k < 0) throw fail(errno);
      put += size_t(k);
    }
  });
  if (::lseek(fd, 0, SEEK_SET) != 0) throw fail(errno);
  if (owned_) ::close(int(handle_));
  handle_ = fd;
  owned_ = true;
  size_ = total;
  start_ = 0;
  taken_ = 0;
}

/// The descriptor a path names outright: /dev/stdout, /dev/stderr, /dev/fd/N,
/// /proc/self/fd/N; -1 for any other path. Written through that descriptor, the output
/// keeps the offset and append mode the shell gave it.
static int named_descriptor(const std::string& path) {
  if (path == "/dev/stdout") return STDOUT_FILENO;
  if (path == "/dev/stderr") return STDERR_FILENO;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string p = prefix;
    if (path.rfind(p, 0) != 0 || path.size() == p.size() || path.size() > p.size() + 6) continue;
    int fd = 0;
    for (size_t k = p.size(); k < path.size(); ++k) {
      if (path[k] < '0' || path[k] > '9') return -1;
      fd = fd * 10 + (path[k] - '0');
    }
    return fd;
  }
  return -1;
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path == "-" || named_descriptor(path) >= 0) {
    handle_ = path == "-" ? STDOUT_FILENO : named_descriptor(path);
    is_stdout_ = handle_ == STDOUT_FILENO;
    if (is_stdout_ && g_stdout_failed) throw Error(kExitIo, "cannot write standard output");
    if (is_stdout_) std::fflush(stdout);  // whatever stdio holds goes first
    OutputFileSystem::note_start(*this);
    return;
  }
  struct stat link {};
  const bool exists = ::lstat(path.c_str(), &link) == 0;
  if (!exists && errno != ENOENT)
    throw Error(kExitIo, fmt::format("cannot write '{}': {}", path, error_text(errno)));
  if (!exists) {
    if (!path.empty() && path.back() == '/')
      throw Error(kExitIo, fmt::format("cannot write '{}': no such folder", path));
    OutputFileSystem::open_temporary(*this, path, nullptr);
    return;
  }
  // A link is followed to what it names: that is rewritten, and the link stays.
  std::string target = path;
  struct stat st = link;
  if (S_ISLNK(link.st_mode)) {
    if (::stat(path.c_str(), &st) != 0)
      throw Error(kExitIo, fmt::format("cannot write '{}': {} (a link to nothing)", path, error_text(errno)));
    target = resolved(path);
    if (target.empty()) throw Error(kExitIo, fmt::format("cannot follow the link '{}': {}", path, error_text(errno)));
  }
  if (S_ISDIR(st.st_mode)) throw Error(kExitIo, fmt::format("cannot write '{}': it is a folder", path));
  if (written_in_place(path, &st) || written_in_place(target, &st)) {
    handle_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (handle_ < 0) throw Error(kExitIo, fmt::format("cannot open '{}' for writing: {}", path, error_text(errno)));
    owned_ = true;
    return;
  }
  OutputFileSystem::open_temporary(*this, target, &st);
}

OutputFile::~OutputFile() {
  if (!done_) discard();
}

/// A regular file behind a descriptor the shell opened (`> out.nc`): where it began, so that
/// discard() can cut it back there.
void OutputFileSystem::note_start(OutputFile& f) {
  auto& handle_ = f.handle_;
  auto& start_ = f.start_;
  struct stat st {};
  if (::fstat(int(handle_), &st) != 0 || !S_ISREG(st.st_mode)) return;
  const int flags = ::fcntl(int(handle_), F_GETFL);
  const off_t at = (flags >= 0 && (flags & O_APPEND)) ? st.st_size : ::lseek(int(handle_), 0, SEEK_CUR);
  if (at >= 0) start_ = at;
}

/// The temporary file beside `target` (which exists when `old` is given), renamed into place
/// by commit().
void OutputFileSystem::open_temporary(OutputFile& f, const std::string& target, const struct stat* old) {
  auto& handle_ = f.handle_;
  std::string tmpl = target + ".arcpress-XXXXXX";
  if (tmpl.size() >= sizeof g_temporaries[0].name)
    throw Error(kExitIo, fmt::format("output path too long: '{}'", target));
  int slot = take_slot();
  if (slot < 0) throw Error(kExitIo, fmt::format("cannot write '{}': too many outputs at once", target));
  TemporarySlot& t = g_temporaries[slot];
  // The handler may remove the file from the moment it exists: its name is set, and the
  // slot marked, first. (A signal may reach another thread while mkstemp() fills in the
  // name; at worst the handler then unlinks a name no file has.)
  std::memcpy(t.name, tmpl.c_str(), tmpl.size() + 1);
  sigset_t block, saved;
  sigemptyset(&block);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&block, sig);
  ::pthread_sigmask(SIG_BLOCK, &block, &saved);
  t.state = 2;
  handle_ = ::mkstemp(t.name);
  const int made = errno;
  ::pthread_sigmask(SIG_SETMASK, &saved, nullptr);
  if (handle_ < 0) {
    free_slot(slot);
    throw Error(kExitIo, fmt::format("cannot create a temporary file beside '{}': {}", target, error_text(made)));
  }
  f.owned_ = true;
  f.temporary_ = t.name;
  f.slot_ = slot;
  f.target_ = target;
  // The mode, owner and group an existing file had; a new file gets 0666 less the umask.
  mode_t mode = 0666;
  if (old) {
    mode = old->st_mode & 07777;
    if (::fchown(int(handle_), old->st_uid, old->st_gid) != 0 && (old->st_uid != ::geteuid() || old->st_gid != ::getegid()))
      std::fprintf(stderr, "arcpress: warning: cannot keep the owner and group of '%s' (%s): they are now this user's\n",
                   target.c_str(), std::strerror(errno));
  } else {
    const mode_t um = ::umask(0);
    ::umask(um);
    mode &= ~um;
  }
  if (::fchmod(int(handle_), mode) != 0) f.fail("cannot set the mode of the output for", errno);
}

void OutputFile::fail(const std::string& what, int err) {
  discard();
  if (is_stdout_) g_stdout_failed = true;
  throw Error(kExitIo, fmt::format("{} {}: {}", what, is_stdout_ ? std::string("standard output") : "'" + path_ + "'",
                                   error_text(err)));
}

void OutputFile::write(std::string_view data) {
  if (done_) throw Error(kExitIo, fmt::format("cannot write '{}': already closed", path_));
  const int err = write_all(int(handle_), data, written_);
  if (err == EPIPE) {
    // The reader went away (`arcpress big.gcode | head`): said as such, with how much it took.
    const size_t taken = written_;
    discard();
    if (is_stdout_) g_stdout_failed = true;
    throw Error(kExitIo, fmt::format("{} closed after {} bytes",
                                     is_stdout_ ? std::string("standard output") : "'" + path_ + "'", taken));
  }
  if (err != 0) fail("cannot write", err);
}

void OutputFile::commit() {
  if (done_) return;
  if (!temporary_.empty()) {
    if (::fsync(int(handle_)) != 0) fail("cannot finish writing", errno);
    const int fd = int(handle_);
    handle_ = -1;
    if (::close(fd) != 0) {
      const int err = errno;
      ::unlink(temporary_.c_str());
      free_slot(slot_);
      done_ = true;
      throw Error(kExitIo, fmt::format("cannot finish writing '{}': {}", path_, error_text(err)));
    }
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
      const int err = errno;
      ::unlink(temporary_.c_str());
      free_slot(slot_);
      done_ = true;
      throw Error(kExitIo, fmt::format("cannot rename the output into '{}': {}", path_, error_text(err)));
    }
    free_slot(slot_);
  } else if (owned_) {
    const int fd = int(handle_);
    handle_ = -1;
    if (::close(fd) != 0) {
      done_ = true;
      throw Error(kExitIo, fmt::format("cannot finish writing '{}': {}", path_, error_text(errno)));
    }
  }
  done_ = true;
}

size_t OutputFile::discard() {
  if (done_) return 0;
  done_ = true;
  size_t left = 0;
  if (!temporary_.empty()) {
    ::close(int(handle_));
    ::unlink(temporary_.c_str());
    free_slot(slot_);
  } else {
    // A file the shell opened is cut back to where it began; a pipe or terminal keeps what
    // it has been given.
    if (start_ < 0 || ::ftruncate(int(handle_), start_) != 0) left = written_;
    else if (::lseek(int(handle_), start_, SEEK_SET) < 0) left = written_;
    if (owned_) ::close(int(handle_));
  }
  handle_ = -1;
  return left;
}

void remove_temporary_files_on_signals() {
  // A reader that closes its end makes a write fail with EPIPE, reported as an I/O error
  // (exit 3), rather than kill the process without a word.
  ::signal(SIGPIPE, SIG_IGN);
  struct sigaction sa {};
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &sa, nullptr);
}

std::vector<std::string> start_process(int argc, char** argv) {
#if defined(__GLIBC__)
  // Each piece of a program allocates and frees about the same memory as the last: keep
  // what is freed for the next rather than give it back and fault it in again.
  ::mallopt(M_MMAP_THRESHOLD, 64 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 128 << 20);
  ::mallopt(M_TOP_PAD, 32 << 20);
#endif
  return std::vector<std::string>(argv, argv + argc);
}

bool is_terminal(int stream) { return ::isatty(stream) == 1; }

}  // namespace arcpress::cli

#if defined(__linux__)
// Linux: the program's allocation function, replaced (as C++ allows an executable to) so
// that its memory lies on huge pages.
//
// A whole program read at once (`arcpress diff` reads two) fills hundreds of MB of fresh
// memory that the kernel maps a 4 KiB page at a time, and the diff's spatial searches then
// walk it beyond the TLB's reach. Where the system leaves huge pages to the program's asking
// (transparent huge pages in `madvise` mode, Debian's default), asking for them maps memory
// 2 MiB at a time: the heap as it grows (malloc's main arena, where main() keeps allocations
// of up to 64 MiB), and any allocation large enough to hold a whole huge page of its own.
// `arcpress diff` of the bunny and its compressed output runs in less than half the time
// (docs/benchmarks.md). Where the system decides otherwise the requests change nothing.

namespace {

constexpr std::uintptr_t kHugePageBytes = std::uintptr_t(2) << 20;
/// Allocations from this size on look whether the heap grew (it grows by such steps).
constexpr std::size_t kLookAtHeapBytes = std::size_t(64) << 10;

std::uintptr_t huge_page_below(std::uintptr_t a) { return a & ~(kHugePageBytes - 1); }

/// Asks for huge pages over the whole huge pages inside [begin, end): a hint, whose refusal
/// changes nothing.
void advise(std::uintptr_t begin, std::uintptr_t end) {
  begin = huge_page_below(begin + kHugePageBytes - 1);
  end = huge_page_below(end);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

/// The heap's end up to which huge pages were asked for (0: not yet looked at).
std::atomic<std::uintptr_t> heap_advised{0};

/// Asks for huge pages over what the heap grew by since the last look. (The break is asked
/// of the kernel: sbrk(0) reads malloc's copy, which another thread may be writing.)
void advise_heap_growth() {
  const std::uintptr_t end = static_cast<std::uintptr_t>(::syscall(SYS_brk, 0));
  std::uintptr_t from = heap_advised.load(std::memory_order_relaxed);
  if (from == 0) {  // the heap so far holds the small start-up allocations: left as it is
    heap_advised.compare_exchange_strong(from, huge_page_below(end));
    return;
  }
  const std::uintptr_t to = huge_page_below(end);
  if (to > from && heap_advised.compare_exchange_strong(from, to)) advise(from, to);
}

}  // namespace

// The other forms (arrays, nothrow, sized delete) call these in libstdc++; the aligned
// forms keep the library's own pair.
void* operator new(std::size_t bytes) {
  void* p = std::malloc(bytes > 0 ? bytes : 1);
  if (p == nullptr) throw std::bad_alloc();
  if (bytes >= kLookAtHeapBytes) {
    advise_heap_growth();
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    if (bytes >= kHugePageBytes) advise(at, at + bytes);  // (one malloc mapped on its own)
  }
  return p;
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif  // __linux__
