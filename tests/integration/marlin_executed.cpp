// SPDX-License-Identifier: GPL-3.0-or-later
// Marlin's own arc code as a judge of the path a program makes on a Marlin printer: reads a
// program and writes it again with each G2/G3 block replaced by the G1 moves that Marlin's
// plan_arc() (Marlin/src/gcode/motion/G2_G3.cpp, built beside this file with
// marlin_shim.hpp) hands its planner, in the order and at the positions it computes them:
// the path the printer moves along, which `arcpress diff` then measures
// (marlin_executed.sh). Positions and modes follow the firmware: G90/G91 set E's mode with
// the axes' (built with E_BY_M82_M83, as the MK3's firmware, they leave it), M82/M83 E's
// alone, G92 sets positions. (Built with prusa_mk3_arc.cpp in place of G2_G3.cpp, the arcs
// are the MK3's.) E is kept in double precision here and
// each arc is handed to plan_arc() from E 0: the firmware's single-precision E counter, which
// rounds the input's moves as much as the output's (at E 2 000 mm a float's step is 0.000122
// mm), is not what is compared; the division of the arc's E into its segments is. Exit 1 where Marlin reports an arc's
// parameters bad; exit 3 for a program Marlin does not run as written: a block whose first
// word is no command (modal motion: Marlin drops it) or a program in inches (G20: no
// INCH_MODE_SUPPORT by default).
//
//     marlin_executed PROGRAM > EXECUTED
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

xyze_pos_t current_position, destination;
feedRate_t feedrate_mm_s = 25;
uint8_t active_extruder = 0;
Planner planner;
GcodeSuite gcode;
Temperature thermalManager;
GCodeParser parser;

namespace {

bool relative_axes = false, relative_e = false;
double e_position = 0;       // E, as the program counts it, in double precision
bool known[4] = {};          // axes the program has set: the printer's own start is not the program's
std::vector<xyze_pos_t> planned;
bool refused = false;

const char kAxes[] = "XYZE";
#ifdef E_BY_M82_M83
constexpr bool kEWithAxes = false;
#else
constexpr bool kEWithAxes = true;
#endif

std::string number(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", v);
  std::string s = text;
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

/// The words of `code` (a line without its comment), as Marlin's parser reads them.
/// (E's value also in double precision, in e_word.)
double e_word = 0;
bool read_words(const std::string& code, GCodeParser& p, char& command, double& command_number) {
  p = GCodeParser{};
  command = 0;
  size_t i = 0;
  bool first = true;
  while (i < code.size()) {
    const char c = char(std::toupper(static_cast<unsigned char>(code[i])));
    if (!std::isalpha(static_cast<unsigned char>(c))) { ++i; continue; }
    char* end = nullptr;
    const double v = std::strtod(code.c_str() + i + 1, &end);
    const size_t next = size_t(end - code.c_str());
    const bool has_value = next > i + 1;
    if (!has_value) {  // (a letter without a number is no word: the text of a comment in parentheses)
      ++i;
      continue;
    }
    if (first && c != 'N') {
      if (c != 'G' && c != 'M' && c != 'T') return false;  // no command: not a block Marlin runs
      command = c, command_number = v, first = false;
    } else if (c != 'N') {
      p.seen[c - 'A'] = true;
      p.value[c - 'A'] = float(v);
      if (c == 'E') e_word = v;
    }
    i = next;
  }
  return true;
}

}  // namespace

void marlin_error(const char* message) {
  std::fprintf(stderr, "marlin_executed: %s\n", message);
  refused = true;
}
millis_t millis() { return 0; }
void idle(bool) {}
/// GcodeSuite::G0_G1() as plan_arc() calls it (Buddy): a straight move to the destination.
void GcodeSuite::G0_G1() {
  planned_line(destination);
  current_position = destination;
}
void planned_line(const xyze_pos_t& p) { planned.push_back(p); }

/// GcodeSuite::get_destination_from_command(): each axis given goes to its value, or by it
/// where its mode is relative; the others stay; F sets the feed.
void get_destination_from_command() {
  for (int a = 0; a < 4; ++a) {
    const char L = kAxes[a];
    if (parser.seen[L - 'A']) {
      const float v = parser.value[L - 'A'];
      const bool relative = a == E_AXIS ? relative_e : relative_axes;
      destination[a] = relative ? current_position[a] + v : v;
    } else {
      destination[a] = current_position[a];
    }
  }
  if (parser.seen['F' - 'A'] && parser.value['F' - 'A'] > 0) feedrate_mm_s = parser.value['F' - 'A'] / 60.0f;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: marlin_executed PROGRAM > EXECUTED\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "marlin_executed: cannot read %s\n", argv[1]);
    return 2;
  }
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string code = line.substr(0, line.find(';'));
    // A line that starts with no letter (a comment in parentheses, a host's `$` command) is
    // an unknown command to Marlin, which goes on with the next.
    const size_t start = code.find_first_not_of(" \t");
    if (start == std::string::npos || !std::isalpha(static_cast<unsigned char>(code[start]))) {
      std::printf("%s\n", line.c_str());
      continue;
    }
    char command = 0;
    double n = 0;
    if (!read_words(code, parser, command, n)) {
      std::fprintf(stderr, "marlin_executed: a block without a command: %s\n", line.c_str());
      return 3;
    }
    const int g = command == 'G' ? int(n * 10 + 0.5) : -1, m = command == 'M' ? int(n * 10 + 0.5) : -1;
    if (g == 200) {
      std::fprintf(stderr, "marlin_executed: G20 (no INCH_MODE_SUPPORT)\n");
      return 3;
    }
    if (g == 20 || g == 30) {
      planned.clear();
      // The arc from E 0, its E given as the way from there.
      const bool has_e = parser.seen['E' - 'A'], was_relative_e = relative_e;
      const double e_way = !has_e ? 0 : relative_e ? e_word : e_word - e_position;
      current_position.e = 0;
      if (has_e) parser.value['E' - 'A'] = float(e_way), relative_e = true;
      GcodeSuite::G2_G3(g == 20);
      relative_e = was_relative_e;
      if (refused) return 1;
      for (int a = 0; a < 4; ++a) known[a] |= parser.seen[kAxes[a] - 'A'];
      float e_last = 0;
      double e_printed = 0;  // (relative E: each segment's as the difference of the sums printed, which add up)
      bool first = true;
      for (const xyze_pos_t& p : planned) {
        std::string out = "G1";
        for (int a = 0; a < 3; ++a)
          if (known[a]) out += std::string(" ") + kAxes[a] + number(p[a]);
        if (p.e != e_last || has_e) {
          const double e_sum = std::round(double(p.e) * 1e6) / 1e6;
          out += " E" + number(relative_e ? e_sum - e_printed : e_position + double(p.e));
          e_printed = e_sum;
        }
        if (first && parser.seen['F' - 'A']) out += " F" + number(parser.value['F' - 'A']);
        e_last = p.e;
        first = false;
        std::printf("%s\n", out.c_str());
      }
      e_position += e_way;
      continue;
    }
    // Any other block: its modes and where it leaves the position.
    if (g == 900) relative_axes = false, relative_e = kEWithAxes ? false : relative_e;
    if (g == 910) relative_axes = true, relative_e = kEWithAxes ? true : relative_e;
    if (m == 820) relative_e = false;
    if (m == 830) relative_e = true;
    if (g == 920) {
      for (int a = 0; a < 4; ++a)
        if (parser.seen[kAxes[a] - 'A']) current_position[a] = parser.value[kAxes[a] - 'A'], known[a] = true;
      if (parser.seen['E' - 'A']) e_position = e_word;
    }
    if (g == 0 || g == 10) {
      if (parser.seen['E' - 'A']) e_position = relative_e ? e_position + e_word : e_word;
      get_destination_from_command();
      for (int a = 0; a < 4; ++a) known[a] |= parser.seen[kAxes[a] - 'A'];
      current_position = destination;
    }
    if (g == 280) current_position = xyze_pos_t{}, known[0] = known[1] = known[2] = false;  // homing
    std::printf("%s\n", line.c_str());
  }
  return 0;
}
