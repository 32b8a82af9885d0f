#include "file_io.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "arcpress/core/error.hpp"

namespace arcpress::cli {

std::string read_input(const std::string& path) {
  if (path == "-") {
    std::ostringstream ss;
    ss << std::cin.rdbuf();
    if (std::cin.bad()) throw Error(kExitIo, "cannot read standard input");
    return ss.str();
  }
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(kExitIo, fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
  std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw Error(kExitIo, fmt::format("cannot read '{}'", path));
  return data;
}

void write_output(const std::string& path, const std::string& data) {
  if (path == "-") {
    std::fwrite(data.data(), 1, data.size(), stdout);
    if (std::fflush(stdout) != 0) throw Error(kExitIo, "cannot write standard output");
    return;
  }
  std::string tmpl = path + ".arcpress-XXXXXX";
  int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw Error(kExitIo, fmt::format("cannot create a temporary file beside '{}': {}", path, std::strerror(errno)));
  // Keep the mode an existing output file had; new files get the usual 0644 less umask.
  struct stat st {};
  mode_t mode = 0644;
  if (::stat(path.c_str(), &st) == 0) {
    mode = st.st_mode & 07777;
  } else {
    mode_t um = ::umask(0);
    ::umask(um);
    mode &= ~um;
  }
  ::fchmod(fd, mode);
  size_t done = 0;
  while (done < data.size()) {
    ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      int err = errno;
      ::close(fd);
      ::unlink(tmpl.c_str());
      throw Error(kExitIo, fmt::format("cannot write '{}': {}", tmpl, std::strerror(err)));
    }
    done += size_t(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    int err = errno;
    ::unlink(tmpl.c_str());
    throw Error(kExitIo, fmt::format("cannot finish writing '{}': {}", path, std::strerror(err)));
  }
  if (::rename(tmpl.c_str(), path.c_str()) != 0) {
    int err = errno;
    ::unlink(tmpl.c_str());
    throw Error(kExitIo, fmt::format("cannot rename the output into '{}': {}", path, std::strerror(err)));
  }
}

}  // namespace arcpress::cli
