// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Runs a command as a child process, its standard output and error thrown away, and reports
// what the kernel measured of it: wall and CPU seconds, peak resident set and page faults
// (wait4).
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

extern char** environ;

namespace arcpress::bench {

struct ChildRun {
  int exit_code = -1;       ///< -1: it could not start, or a signal ended it
  double seconds = 0;       ///< wall time
  double cpu_seconds = 0;   ///< user and system time of all its threads
  double peak_mib = 0;      ///< peak resident set, MiB
  long minor_faults = 0;    ///< pages the kernel mapped in for it (no disk read)
};

/// Runs `words` (the program first) and waits for it; what it prints goes to `stdout_path`.
inline ChildRun run_child(std::vector<std::string> words, const std::string& stdout_path = "/dev/null") {
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  ChildRun r;
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const int err = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) return r;
  int status = 0;
  struct rusage use {};
  if (wait4(pid, &status, 0, &use) != pid) return r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu_seconds = double(use.ru_utime.tv_sec + use.ru_stime.tv_sec) +
                  1e-6 * double(use.ru_utime.tv_usec + use.ru_stime.tv_usec);
  r.peak_mib = double(use.ru_maxrss) / 1024.0;  // kilobytes on Linux
  r.minor_faults = use.ru_minflt;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace arcpress::bench
