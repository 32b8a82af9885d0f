// SPDX-License-Identifier: GPL-3.0-or-later
// Never lose or corrupt a byte: every destination written as it is meant to be, every write
// checked, nothing partial left behind, whatever the destination, the disk or a signal does.
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "support.hpp"

namespace fs = std::filesystem;
using arcpress::test::run_arcpress;
using arcpress::test::run_shell;

namespace {

const fs::path kSample = fs::path(ARCPRESS_SOURCE_DIR) / "samples" / "contour.nc";

/// What arcpress writes for the sample on standard output.
std::string sample_output() {
  auto c = run_arcpress("'" + kSample.string() + "'");
  REQUIRE(c.exit_code == 0);
  REQUIRE(c.out.size() > 100);
  return c.out;
}

/// Files in `dir` whose name holds ".arcpress-": temporaries left behind.
size_t temporaries_in(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".arcpress-") != std::string::npos;
  return n;
}

}  // namespace

TEST_CASE("a failed write on standard output is an error, never a zero exit", "[cli][output]") {
  if (!fs::exists("/dev/full")) {
    WARN("/dev/full is absent: skipped");
    return;
  }
  const std::string in = "'" + kSample.string() + "'";
  for (const std::string& args : {in, in + " --passthrough", "diff " + in + " " + in, "diff --json " + in + " " + in,
                                  std::string("--help"), std::string("diff --help"), std::string("dialects")}) {
    INFO(args);
    auto full = run_shell("\"$ARCPRESS\" " + args + " > /dev/full");
    CHECK(full.exit_code == 3);
    CHECK(full.err.find("cannot write standard output") != std::string::npos);
    auto closed = run_shell("\"$ARCPRESS\" " + args + " >&-");
    CHECK(closed.exit_code == 3);
  }
  auto to_full = run_arcpress(in + " -o /dev/full");
  CHECK(to_full.exit_code == 3);
  CHECK(to_full.err.find("cannot write '/dev/full': No space left on device") != std::string::npos);
}

TEST_CASE("a reader that closes the pipe early gets exit 3 and how many bytes it took, never a silent death",
          "[cli][output]") {
  auto d = arcpress::test::temp_dir("pipe");
  // Output far larger than a pipe holds, so that writes go on after `head` has left.
  std::string program = "G21 G90\n";
  for (int k = 0; k < 60000; ++k) program += fmt::format("G1 X{:.3f} Y{:.3f} F600\nM117 step {}\n", k * 0.1, (k % 7) * 0.5, k);
  arcpress::test::write_file(d / "big.nc", program);
  auto head = run_shell(fmt::format("cd '{}'\n\"$ARCPRESS\" big.nc | head -c 1000 > /dev/null\necho ${{PIPESTATUS[0]}}",
                                    d.string()));
  CHECK(head.out == "3\n");
  CHECK(head.err.find("arcpress: standard output closed after ") != std::string::npos);
  CHECK(head.err.find(" bytes\n") != std::string::npos);
  // The reader is gone before diff writes its report: the same.
  auto diff = run_shell(fmt::format("cd '{}'\n(sleep 0.5; \"$ARCPRESS\" diff --json big.nc big.nc) | true\n"
                                    "echo ${{PIPESTATUS[0]}}",
                                    d.string()));
  CHECK(diff.out == "3\n");
  CHECK(diff.err.find("arcpress: standard output closed after 0 bytes") != std::string::npos);
}

TEST_CASE("devices, FIFOs and /dev/stdout are written directly, never replaced", "[cli][output]") {
  auto d = arcpress::test::temp_dir("devices");
  const std::string expected = sample_output();
  // /dev/null stays the device (as root this used to replace it with a regular file).
  auto null = run_arcpress("'" + kSample.string() + "' -o /dev/null");
  CHECK(null.exit_code == 0);
  struct stat st {};
  REQUIRE(::stat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
  // /dev/stdout and /dev/fd/1 are whatever standard output is: here a file the shell opened.
  for (const char* name : {"/dev/stdout", "/dev/fd/1"}) {
    auto c = run_shell(fmt::format("\"$ARCPRESS\" '{}' -o {} > '{}'", kSample.string(), name, (d / "shell.nc").string()));
    CHECK(c.exit_code == 0);
    CHECK(arcpress::test::read_file(d / "shell.nc") == expected);
  }
  // A FIFO is written into, and its reader gets the whole program.
  const fs::path fifo = d / "fifo", got = d / "from-fifo.nc";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  auto c = run_shell(fmt::format("cat '{}' > '{}' & reader=$!\n\"$ARCPRESS\" '{}' -o '{}'; status=$?\nwait $reader\nexit $status",
                                 fifo.string(), got.string(), kSample.string(), fifo.string()));
  CHECK(c.exit_code == 0);
  REQUIRE(::stat(fifo.c_str(), &st) == 0);
  CHECK(S_ISFIFO(st.st_mode));
  CHECK(arcpress::test::read_file(got) == expected);
  CHECK(temporaries_in(d) == 0);
}

TEST_CASE("in place through a symbolic link, arcpress rewrites its target and keeps the link", "[cli][output]") {
  auto d = arcpress::test::temp_dir("symlink");
  fs::copy_file(kSample, d / "real.nc");
  fs::create_symlink("real.nc", d / "link.nc");
  auto c = run_arcpress("'" + (d / "link.nc").string() + "' --in-place");
  CHECK(c.exit_code == 0);
  CHECK(fs::is_symlink(d / "link.nc"));
  CHECK(fs::read_symlink(d / "link.nc") == "real.nc");
  CHECK(arcpress::test::read_file(d / "real.nc") == sample_output());
  // -o through a link likewise.
  fs::create_symlink("other.nc", d / "to-other.nc");
  arcpress::test::write_file(d / "other.nc", "old\n");
  CHECK(run_arcpress("'" + kSample.string() + "' -o '" + (d / "to-other.nc").string() + "'").exit_code == 0);
  CHECK(fs::is_symlink(d / "to-other.nc"));
  CHECK(arcpress::test::read_file(d / "other.nc") == sample_output());
  CHECK(temporaries_in(d) == 0);
}

TEST_CASE("in place, arcpress keeps the file's mode, owner and group", "[cli][output]") {
  auto d = arcpress::test::temp_dir("owner");
  fs::copy_file(kSample, d / "part.nc");
  REQUIRE(::chmod((d / "part.nc").c_str(), 0640) == 0);
  if (::geteuid() != 0) {
    WARN("not running as root: the owner cannot be given away, only the mode is checked");
  } else {
    REQUIRE(::chown((d / "part.nc").c_str(), 65534, 65534) == 0);  // nobody
  }
  struct stat before {};
  REQUIRE(::stat((d / "part.nc").c_str(), &before) == 0);
  CHECK(run_arcpress("'" + (d / "part.nc").string() + "' --in-place").exit_code == 0);
  struct stat after {};
  REQUIRE(::stat((d / "part.nc").c_str(), &after) == 0);
  CHECK(after.st_ino != before.st_ino);  // replaced atomically, not written over
  CHECK((after.st_mode & 07777) == 0640);
  CHECK(after.st_uid == before.st_uid);
  CHECK(after.st_gid == before.st_gid);
}

TEST_CASE("a folder is neither read nor written as a program", "[cli][output]") {
  auto d = arcpress::test::temp_dir("folder");
  fs::create_directories(d / "sub");
  // A folder is the programs in it, written into another folder or in place.
  auto in = run_arcpress("'" + (d / "sub").string() + "'");
  CHECK(in.exit_code == 2);
  CHECK(in.err.find("are written with --in-place or -o FOLDER") != std::string::npos);
  for (const std::string out : {(d / "sub").string(), (d / "sub").string() + "/", (d / "none").string() + "/"}) {
    auto c = run_arcpress("'" + kSample.string() + "' -o '" + out + "'");
    CHECK(c.exit_code == 3);
    CHECK(c.err.find("cannot write '" + out + "'") != std::string::npos);
  }
  CHECK(temporaries_in(d / "sub") == 0);
}

TEST_CASE("a signal during the write leaves no temporary file and ends the program as the signal does",
          "[cli][output][signal]") {
  auto d = arcpress::test::temp_dir("signal");
  // A program large enough that writing and syncing it takes a while (about 40 MB).
  std::string big = "G21 G90\nG0 X0 Y0 Z0\nG1 F100\n";
  big.reserve(42u << 20);
  for (int i = 0; i < 2000000; ++i) big += fmt::format("G1 X{:.4f} Y{:.4f}\n", i * 0.001, (i % 7) * 0.01);
  arcpress::test::write_file(d / "big.nc", big);
  // Watch for the temporary file, then send the signal while it is there.
  const std::string script = fmt::format(
      "cd '{}'\nfor sig in TERM INT HUP; do\n"
      "  \"$ARCPRESS\" --passthrough big.nc -o out.nc & pid=$!\n"
      "  while ! ls | grep -q arcpress-; do kill -0 $pid 2>/dev/null || break; done\n"
      "  kill -$sig $pid; wait $pid; echo \"$sig $?\"\n"
      "  ls | grep -c arcpress- || true\n"
      "done\n",
      d.string());
  auto c = run_shell(script);
  INFO(c.out << c.err);
  // Each run either was stopped by its signal (128 + number) or had finished first.
  CHECK((c.out.find("TERM 143\n0\n") != std::string::npos || c.out.find("TERM 0\n0\n") != std::string::npos));
  CHECK((c.out.find("INT 130\n0\n") != std::string::npos || c.out.find("INT 0\n0\n") != std::string::npos));
  CHECK((c.out.find("HUP 129\n0\n") != std::string::npos || c.out.find("HUP 0\n0\n") != std::string::npos));
  if (c.out.find("TERM 143") == std::string::npos && c.out.find("INT 130") == std::string::npos &&
      c.out.find("HUP 129") == std::string::npos)
    WARN("every run finished before its signal arrived: the removal itself was not exercised");
  CHECK(temporaries_in(d) == 0);
}

TEST_CASE("diff prints its verdict before a plot that cannot be written, and a folder is no dialect file",
          "[cli][output]") {
  auto d = arcpress::test::temp_dir("plot");
  const std::string in = "'" + kSample.string() + "'";
  auto c = run_arcpress("diff " + in + " " + in + " --plot '" + (d / "no" / "such" / "plot.svg").string() + "'");
  CHECK(c.exit_code == 3);
  CHECK(c.out.find("SAME: max deviation") != std::string::npos);
  CHECK(c.err.find("plot.svg") != std::string::npos);
  auto folder = run_arcpress(in + " --dialect-file '" + d.string() + "'");
  CHECK(folder.exit_code == 3);
  CHECK(folder.err.find("it is a folder") != std::string::npos);
}

TEST_CASE("a diff report whose quoted blocks hold a NUL byte still ends with its verdict", "[cli][output]") {
  auto d = arcpress::test::temp_dir("nul");
  arcpress::test::write_file(d / "a.nc", std::string("G0 X0 Y0 Z0\n(note \0 one)\nG1 X1 F100\nM2\n", 39));
  arcpress::test::write_file(d / "b.nc", std::string("G0 X0 Y0 Z0\n(note \0 two)\nG1 X1 F100\nM2\n", 39));
  auto c = run_arcpress("diff '" + (d / "a.nc").string() + "' '" + (d / "b.nc").string() + "'");
  CHECK(c.exit_code == 1);
  CHECK(c.out.find("DIFFERENT: ") != std::string::npos);
  CHECK(c.out.find(std::string("(NOTE \0 ONE)", 12)) != std::string::npos);
}

TEST_CASE("a pipe streamed with --stream, fed half a program and held open, already gives the output of what came",
          "[cli][output][stream]") {
  auto d = arcpress::test::temp_dir("stream");
  // A long program: the first half is some pieces' worth of input.
  std::string program = "G21 G90\n";
  for (int pass = 0; pass < 400; ++pass) {
    program += fmt::format("G0 X0 Y{} Z1\nG1 Z0 F600\n", pass);
    for (int k = 1; k <= 200; ++k)
      program += fmt::format("G1 X{:.4f} Y{:.4f}\n", 0.25 * k, pass + 0.5 * std::sin(0.05 * k));
  }
  REQUIRE(program.size() > 4 * (size_t(1) << 17));
  arcpress::test::write_file(d / "half.nc", program.substr(0, program.size() / 2 - 17));
  // The input stays open for 20 s after the half; output must appear well before that.
  auto c = run_shell(fmt::format(
      "cd '{}'\n(cat half.nc; sleep 20) | \"$ARCPRESS\" --stream > out.nc & pid=$!\n"
      "for i in $(seq 100); do [ -s out.nc ] && break; sleep 0.1; done\n"
      "size=$(stat -c %s out.nc)\nkill $pid 2>/dev/null; pkill -P $$ sleep 2>/dev/null\necho $size",
      d.string()));
  REQUIRE(c.exit_code == 0);
  const long written = std::stol(c.out);
  CHECK(written > 0);
  CHECK(size_t(written) < program.size() / 2);
}

TEST_CASE("a program refused half way leaves a shell's output file as empty as it found it", "[cli][output][stream]") {
  auto d = arcpress::test::temp_dir("refused");
  std::string program = "G21 G90\n";
  for (int pass = 0; pass < 300; ++pass) {
    program += fmt::format("G0 X0 Y{} Z1\nG1 Z0 F600\n", pass);
    for (int k = 1; k <= 200; ++k) program += fmt::format("G1 X{:.4f} Y{:.4f}\n", 0.25 * k, pass + 0.5 * std::sin(0.05 * k));
  }
  program += "G1 X1.2.3\n";  // unreadable, long after the first pieces went out
  arcpress::test::write_file(d / "in.nc", program);
  auto c = run_shell(fmt::format("cd '{}'\n\"$ARCPRESS\" --strict in.nc > out.nc; echo $?; stat -c %s out.nc",
                                 d.string()));
  CHECK(c.out == "2\n0\n");
  CHECK(c.err.find("nothing written") != std::string::npos);
}

TEST_CASE("progress is shown on standard error only where asked or on a terminal, and erased at the end",
          "[cli][output][stream]") {
  auto d = arcpress::test::temp_dir("progress");
  std::string program = "G21 G90\n";
  for (int pass = 0; program.size() < (size_t(6) << 20); ++pass) {
    program += fmt::format("G0 X0 Y{} Z1\nG1 Z0 F600\n", pass);
    for (int k = 1; k <= 200; ++k) program += fmt::format("G1 X{:.4f} Y{:.4f}\n", 0.25 * k, pass + 0.5 * std::sin(0.05 * k));
  }
  arcpress::test::write_file(d / "big.nc", program);
  const std::string in = "'" + (d / "big.nc").string() + "' -o /dev/null";
  auto shown = run_arcpress(in + " --progress");
  REQUIRE(shown.exit_code == 0);
  CHECK(shown.err.find("MB/s") != std::string::npos);
  CHECK(shown.err.find(" of ") != std::string::npos);          // the file's size is known: a share of it
  CHECK(shown.err.size() >= 4);
  CHECK(shown.err.substr(shown.err.size() - 4) == "\r\033[K");  // erased at the end
  auto piped = run_arcpress(in);                                  // standard error is no terminal here
  CHECK(piped.exit_code == 0);
  CHECK(piped.err.empty());
  auto quiet = run_arcpress(in + " --progress -q");
  CHECK(quiet.err.find("MB/s") != std::string::npos);             // --progress wins: asked for by name
}
