#include "file_io.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "arcpress/core/error.hpp"

namespace arcpress::cli {
namespace {

/// The temporary file being written, for the signal handler: set before the file exists,
/// cleared once it is renamed or removed. A fixed buffer, as a handler may only read memory.
char g_temporary[PATH_MAX + 32] = {};
std::atomic<bool> g_temporary_set{false};
/// Whether standard output has failed: nothing more is written there.
bool g_stdout_failed = false;

extern "C" void on_fatal_signal(int sig) {
  if (g_temporary_set.load()) ::unlink(g_temporary);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

std::string error_text(int err) { return std::strerror(err); }

/// Writes all of `data` to `fd`; returns 0 or the errno of the failure.
int write_all(int fd, std::string_view data) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
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

void write_directly(const std::string& path, std::string_view data) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw Error(kExitIo, fmt::format("cannot open '{}' for writing: {}", path, error_text(errno)));
  const int err = write_all(fd, data);
  if (err != 0) {
    ::close(fd);
    throw Error(kExitIo, fmt::format("cannot write '{}': {}", path, error_text(err)));
  }
  if (::close(fd) != 0) throw Error(kExitIo, fmt::format("cannot finish writing '{}': {}", path, error_text(errno)));
}

/// The atomic write of a regular file at `path` (which exists when `old` is given).
void write_replacing(const std::string& path, std::string_view data, const struct stat* old) {
  std::string tmpl = path + ".arcpress-XXXXXX";
  if (tmpl.size() >= sizeof g_temporary) throw Error(kExitIo, fmt::format("output path too long: '{}'", path));
  // The handler may remove the file from the moment it exists: its name is set first.
  std::memcpy(g_temporary, tmpl.c_str(), tmpl.size() + 1);
  sigset_t block, saved;
  sigemptyset(&block);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&block, s);
  ::sigprocmask(SIG_BLOCK, &block, &saved);
  const int fd = ::mkstemp(g_temporary);
  const int made = errno;
  if (fd >= 0) g_temporary_set = true;
  ::sigprocmask(SIG_SETMASK, &saved, nullptr);
  if (fd < 0) throw Error(kExitIo, fmt::format("cannot create a temporary file beside '{}': {}", path, error_text(made)));
  const std::string tmp = g_temporary;
  auto fail = [&](const std::string& what, int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    g_temporary_set = false;
    throw Error(kExitIo, fmt::format("{} '{}': {}", what, path, error_text(err)));
  };
  // The mode, owner and group an existing file had; a new file gets 0666 less the umask.
  mode_t mode = 0666;
  if (old) {
    mode = old->st_mode & 07777;
    if (::fchown(fd, old->st_uid, old->st_gid) != 0 && (old->st_uid != ::geteuid() || old->st_gid != ::getegid()))
      std::fprintf(stderr, "arcpress: warning: cannot keep the owner and group of '%s' (%s): they are now this user's\n",
                   path.c_str(), std::strerror(errno));
  } else {
    const mode_t um = ::umask(0);
    ::umask(um);
    mode &= ~um;
  }
  if (::fchmod(fd, mode) != 0) fail("cannot set the mode of the output for", errno);
  if (const int err = write_all(fd, data); err != 0) fail("cannot write", err);
  if (::fsync(fd) != 0) fail("cannot finish writing", errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    g_temporary_set = false;
    throw Error(kExitIo, fmt::format("cannot finish writing '{}': {}", path, error_text(err)));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    g_temporary_set = false;
    throw Error(kExitIo, fmt::format("cannot rename the output into '{}': {}", path, error_text(err)));
  }
  g_temporary_set = false;
}

}  // namespace

std::string read_input(const std::string& path) {
  const int fd = path == "-" ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  const std::string name = path == "-" ? "standard input" : "'" + path + "'";
  if (fd < 0) throw Error(kExitIo, fmt::format("cannot open {}: {}", name, error_text(errno)));
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    if (fd != STDIN_FILENO) ::close(fd);
    throw Error(kExitIo, fmt::format("cannot read {}: it is a folder", name));
  }
  std::string data;
  if (S_ISREG(st.st_mode) && st.st_size > 0) data.reserve(size_t(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      if (fd != STDIN_FILENO) ::close(fd);
      throw Error(kExitIo, fmt::format("cannot read {}: {}", name, error_text(err)));
    }
    data.append(buf, size_t(n));
  }
  if (fd != STDIN_FILENO) ::close(fd);
  return data;
}

void write_stdout(std::string_view data) {
  if (g_stdout_failed) throw Error(kExitIo, "cannot write standard output");
  std::fflush(stdout);  // whatever stdio holds goes first
  if (const int err = write_all(STDOUT_FILENO, data); err != 0) {
    g_stdout_failed = true;
    throw Error(kExitIo, fmt::format("cannot write standard output: {}", error_text(err)));
  }
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

void write_output(const std::string& path, std::string_view data) {
  if (path == "-" || named_descriptor(path) == STDOUT_FILENO) return write_stdout(data);
  if (const int fd = named_descriptor(path); fd >= 0) {
    if (const int err = write_all(fd, data); err != 0)
      throw Error(kExitIo, fmt::format("cannot write '{}': {}", path, error_text(err)));
    return;
  }
  struct stat link {};
  const bool exists = ::lstat(path.c_str(), &link) == 0;
  if (!exists && errno != ENOENT)
    throw Error(kExitIo, fmt::format("cannot write '{}': {}", path, error_text(errno)));
  if (!exists) {
    if (!path.empty() && path.back() == '/')
      throw Error(kExitIo, fmt::format("cannot write '{}': no such folder", path));
    return write_replacing(path, data, nullptr);
  }
  // A link is followed to what it names: that is rewritten, and the link stays.
  std::string target = path;
  struct stat st = link;
  if (S_ISLNK(link.st_mode)) {
    if (::stat(path.c_str(), &st) != 0) throw Error(kExitIo, fmt::format("cannot write '{}': {} (a link to nothing)", path, error_text(errno)));
    target = resolved(path);
    if (target.empty()) throw Error(kExitIo, fmt::format("cannot follow the link '{}': {}", path, error_text(errno)));
  }
  if (S_ISDIR(st.st_mode)) throw Error(kExitIo, fmt::format("cannot write '{}': it is a folder", path));
  if (written_in_place(path, &st) || written_in_place(target, &st)) return write_directly(path, data);
  write_replacing(target, data, &st);
}

void remove_temporary_files_on_signals() {
  struct sigaction sa {};
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &sa, nullptr);
}

}  // namespace arcpress::cli
