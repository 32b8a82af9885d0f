#include "support.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>

namespace fs = std::filesystem;

namespace arcpress::test {

std::vector<fs::path> corpus_files() {
  std::vector<fs::path> files;
  fs::path dir(ARCPRESS_CORPUS_DIR);
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    auto ext = e.path().extension().string();
    if (ext == ".nc" || ext == ".ngc" || ext == ".gcode") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& p, const std::string& data) {
  std::ofstream f(p, std::ios::binary);
  f << data;
}

fs::path temp_dir(const std::string& tag) {
  std::random_device rd;
  fs::path d = fs::temp_directory_path() / ("arcpress-test-" + tag + "-" + std::to_string(rd()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

Command run_arcpress(const std::string& args, const std::string& stdin_text) {
  fs::path d = temp_dir("cmd");
  write_file(d / "stdin", stdin_text);
  std::string cmd = std::string("'") + ARCPRESS_EXE + "' " + args + " < '" + (d / "stdin").string() + "' > '" +
                    (d / "stdout").string() + "' 2> '" + (d / "stderr").string() + "'";
  int status = std::system(cmd.c_str());
  Command c;
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.out = read_file(d / "stdout");
  c.err = read_file(d / "stderr");
  fs::remove_all(d);
  return c;
}

}  // namespace arcpress::test
