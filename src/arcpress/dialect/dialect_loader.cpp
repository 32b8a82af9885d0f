// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/dialect/dialect_loader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <utility>
#include <toml++/toml.h>

#include "arcpress/core/error.hpp"
#include "arcpress/core/utf8_path.hpp"
#include "arcpress/platform/platform.hpp"

#ifndef ARCPRESS_SOURCE_DIALECT_DIR
#define ARCPRESS_SOURCE_DIALECT_DIR ""
#endif

namespace arcpress {

double Dialect::radius_allowance_mm(double radius_mm) const {
  if (radius_abs_mm <= 0) return kRadiusAimMm;
  double controller = radius_rel > 0 ? std::max(radius_abs_mm, radius_rel * radius_mm) : radius_abs_mm;
  return std::min(kRadiusAimMm, controller);
}

bool Dialect::refuses(std::string_view code) const {
  return std::find(refused.begin(), refused.end(), code) != refused.end();
}

namespace {

namespace fs = std::filesystem;

/// "a", "b", "c"
std::string quoted(std::initializer_list<std::string_view> choices) {
  std::string list;
  for (auto c : choices) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", c);
  return list;
}

/// Walks one TOML table, reading known keys into a Dialect and rejecting everything else,
/// with the place of the offending key in every message.
class TableReader {
 public:
  TableReader(const toml::table& t, std::string path, std::string prefix)
      : t_(t), path_(std::move(path)), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const toml::source_region& at, std::string_view key, const std::string& what) const {
    throw Error(kExitInput, fmt::format("{}:{}:{}: {}{}: {}", path_, at.begin.line, at.begin.column, prefix_, key, what));
  }

  const toml::node* node(std::string_view key) {
    seen_.insert(std::string(key));
    return t_.get(key);
  }

  void boolean(std::string_view key, bool& out) {
    if (auto* n = node(key)) {
      auto v = n->value<bool>();
      if (!n->is_boolean() || !v) fail(n->source(), key, "expected true or false");
      out = *v;
    }
  }
  void number(std::string_view key, double& out, double lo, double hi) {
    if (auto* n = node(key)) {
      if (!n->is_number()) fail(n->source(), key, "expected a number");
      double v = *n->value<double>();
      if (!(v >= lo && v <= hi)) fail(n->source(), key, fmt::format("{} is outside {} .. {}", v, lo, hi));
      out = v;
    }
  }
  template <class Int>
  void integer(std::string_view key, Int& out, int64_t lo, int64_t hi) {
    if (auto* n = node(key)) {
      if (!n->is_integer()) fail(n->source(), key, "expected a whole number");
      int64_t v = *n->value<int64_t>();
      if (v < lo || v > hi) fail(n->source(), key, fmt::format("{} is outside {} .. {}", v, lo, hi));
      out = Int(v);
    }
  }
  void text(std::string_view key, std::string& out) {
    if (auto* n = node(key)) {
      if (!n->is_string()) fail(n->source(), key, "expected a string");
      out = *n->value<std::string>();
    }
  }
  /// A string that must be one of `choices`; returns its index, or -1 when absent.
  int choice(std::string_view key, std::initializer_list<std::string_view> choices) {
    auto* n = node(key);
    if (!n) return -1;
    if (n->is_string()) {
      std::string v = *n->value<std::string>();
      int i = 0;
      for (auto c : choices) {
        if (v == c) return i;
        ++i;
      }
    }
    fail(n->source(), key, "expected one of " + quoted(choices));
  }
  /// An array of strings, each one of `choices` when given, and each passing `valid` (which
  /// says what it expected otherwise) when given.
  bool strings(std::string_view key, std::vector<std::string>& out, std::initializer_list<std::string_view> choices = {},
               const char* (*valid)(std::string_view) = nullptr) {
    auto* n = node(key);
    if (!n) return false;
    auto* arr = n->as_array();
    if (!arr) fail(n->source(), key, "expected an array of strings");
    out.clear();
    for (auto& e : *arr) {
      if (!e.is_string()) fail(e.source(), key, "expected an array of strings");
      std::string v = *e.value<std::string>();
      if (choices.size() && std::find(choices.begin(), choices.end(), v) == choices.end()) {
        fail(e.source(), key, fmt::format("\"{}\" is not one of {}", v, quoted(choices)));
      }
      if (const char* expected = valid ? valid(v) : nullptr) fail(e.source(), key, fmt::format("\"{}\": {}", v, expected));
      out.push_back(v);
    }
    return true;
  }
  const toml::table* table(std::string_view key) {
    auto* n = node(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(n->source(), key, "expected a table");
    return n->as_table();
  }
  /// Every key not read is a mistake in the file.
  void finish() const {
    for (auto&& [k, v] : t_)
      if (!seen_.count(std::string(k.str()))) fail(k.source(), k.str(), "unknown key");
  }

 private:
  const toml::table& t_;
  std::string path_;
  std::string prefix_;
  std::set<std::string> seen_;
};

/// A G- or M-code as programs write it ("G70", "G54.1", "M91"): its letter, upper case, and
/// the code times ten; none where `k` is no such code.
std::optional<std::pair<char, int>> code_named(std::string_view k) {
  const char letter = char(std::toupper(static_cast<unsigned char>(k.empty() ? ' ' : k[0])));
  double v = 0;
  const char* end = k.data() + k.size();
  if ((letter == 'G' || letter == 'M') && k.size() >= 2 && std::isdigit(static_cast<unsigned char>(k[1])) &&
      std::from_chars(k.data() + 1, end, v).ptr == end && v < 10000)
    return std::pair{letter, int(std::lround(v * 10))};
  return std::nullopt;
}

void read_digits(TableReader& parent, const toml::table* t, const std::string& path, const std::string& prefix,
                 NumberDigits& d) {
  if (!t) return;
  TableReader r(*t, path, prefix);
  r.integer("axis", d.axis, 0, 9);
  r.integer("centre", d.centre, 0, 9);
  r.integer("max", d.max, 0, 9);
  r.integer("feed", d.feed, 0, 9);
  r.integer("e", d.e, 0, 9);
  r.finish();
  if (d.max < d.centre) parent.fail(t->source(), prefix + "max", "must be at least 'centre'");
}

}  // namespace

Dialect parse_dialect(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw Error(kExitInput, fmt::format("{}:{}:{}: {}", path, e.source().begin.line, e.source().begin.column,
                                        e.description()));
  }
  Dialect d;
  d.source = path;
  TableReader top(root, path, "");
  if (!root.contains("name")) top.fail(root.source(), "name", "missing: a dialect file names its dialect");
  top.text("name", d.name);
  top.text("description", d.description);
  if (d.name.empty() || d.name.find_first_of(" /\t") != std::string::npos)
    top.fail(root.source(), "name", "must be a non-empty word");

  if (const toml::table* t = top.table("arcs")) {
    TableReader r(*t, path, "arcs.");
    r.boolean("enabled", d.arcs);
    if (int c = r.choice("centre", {"incremental", "absolute"}); c >= 0) d.centre = CentreReading(c);
    r.boolean("centre_mode_words", d.centre_mode_words);
    r.boolean("centre_modal", d.centre_modal);
    r.boolean("radius_word", d.radius_word);
    if (int c = r.choice("format", {"centre", "radius"}); c >= 0) d.format = ArcFormat(c);
    r.text("header", d.arc_header);
    std::vector<std::string> planes;
    if (r.strings("planes", planes, {"G17", "G18", "G19"})) {
      d.planes = 0;
      for (auto& p : planes) d.planes |= uint8_t(1u << (p[2] - '7'));
    }
    r.boolean("helical", d.helical);
    r.boolean("extra_axes", d.extra_axes);
    r.boolean("relative", d.relative_arcs);
    r.boolean("zx_reversed", d.zx_reversed);
    r.number("max_sweep_deg", d.max_sweep_deg, 1, 359);
    r.number("min_sweep_deg", d.min_sweep_deg, 0, 90);
    r.number("min_radius_mm", d.min_radius_mm, 0, 1e6);
    r.number("max_radius_mm", d.max_radius_mm, 1e-3, 1e9);
    r.number("min_length_mm", d.min_arc_length_mm, 0, 1e6);
    r.integer("min_moves", d.min_arc_moves, 0, 1000);
    r.number("min_chord_mm", d.min_chord_mm, 0, 10);
    r.number("radius_check_mm", d.radius_abs_mm, 0, 100);
    r.number("radius_check_relative", d.radius_rel, 0, 1);
    if (const toml::table* e = r.table("executed")) {
      TableReader x(*e, path, "arcs.executed.");
      if (const toml::node* at = x.node("rule")) {
        std::string rule;
        x.text("rule", rule);
        const auto named = rule_named(rule);
        if (!named) x.fail(at->source(), "rule", fmt::format("expected one of \"{}\"", fmt::join(kRuleNames, "\", \"")));
        d.executed.rule = *named;
      }
      x.number("max_segment_mm", d.executed.max_segment_mm, 0, 1000);
      x.number("min_segment_mm", d.executed.min_segment_mm, 0, 1000);
      x.integer("min_circle_segments", d.executed.min_circle_segments, 0, 100000);
      x.number("max_deviation_mm", d.executed.max_deviation_mm, 0, 10);
      x.integer("correction_period", d.executed.correction_period, 0, 1000);
      x.finish();
      if (d.executed.rule == ArcSegmentation::Rule::Klipper && d.executed.max_segment_mm <= 0)
        x.fail(e->source(), "max_segment_mm", "klipper's resolution must be above 0");
    }
    if (const toml::table* l = r.table("last_turn")) {
      // CODE = ["CW", "CCW"]: a G-code that turns as the last programmed arc did, and the
      // G-codes that turn each way in its stead.
      TableReader x(*l, path, "arcs.last_turn.");
      for (auto&& [key, value] : *l) {
        const std::string k(key.str());
        auto g_code = [](std::string_view v) -> std::optional<int> {
          const auto c = code_named(v);
          return c && c->first == 'G' ? std::optional<int>(c->second) : std::nullopt;
        };
        const auto code = g_code(k);
        if (!code) x.fail(key.source(), k, "expected a G-code as the key (\"G05\"; quoted where it has a point)");
        std::vector<std::string> ways;
        x.strings(k, ways, {}, [](std::string_view v) -> const char* {
          const auto c = code_named(v);
          return c && c->first == 'G' ? nullptr : "expected a G-code";
        });
        if (ways.size() != 2) x.fail(value.source(), k, "expected two G-codes: the clockwise one, then the counter-clockwise one");
        d.last_turn.push_back({*code, *g_code(ways[0]), *g_code(ways[1])});
      }
      x.finish();
    }
    r.finish();
    if (d.format == ArcFormat::Radius && !d.radius_word)
      top.fail(t->source(), "arcs.format", "\"radius\" needs radius_word = true");
  }
  if (const toml::table* t = top.table("startup")) {
    TableReader r(*t, path, "startup.");
    if (int c = r.choice("units", {"mm", "inch", "machine"}); c >= 0) d.start_units = StartUnits(c);
    if (int c = r.choice("arc_centres", {"incremental", "absolute", "machine"}); c >= 0)
      d.start_centres = StartCentres(c);
    r.finish();
  }
  if (const toml::table* t = top.table("lathe")) {
    TableReader r(*t, path, "lathe.");
    r.boolean("diameter", d.diameter_x);
    r.finish();
  }
  if (const toml::table* t = top.table("printer")) {
    TableReader r(*t, path, "printer.");
    r.boolean("firmware_retraction", d.firmware_retraction);
    if (int c = r.choice("extrusion_distance", {"g90-g91", "g91-or-m83", "m82-m83"}); c >= 0)
      d.extrusion_distance = ExtrusionDistance(c);
    // A name as the lexer reads an extended command's.
    auto command_name = [](std::string_view v) -> const char* {
      auto alpha = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
      const bool ok = v.size() >= 2 && alpha(v[0]) && (alpha(v[1]) || v[1] == '_') &&
                      std::all_of(v.begin(), v.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
      return ok ? nullptr : "expected a command's name: two letters (or a letter and '_'), then letters, digits or '_'";
    };
    if (r.strings("position_keeping_commands", d.position_keeping_commands, {}, command_name))
      for (std::string& c : d.position_keeping_commands)
        for (char& ch : c) ch = char(std::toupper(static_cast<unsigned char>(ch)));
    r.finish();
  }
  if (const toml::table* t = top.table("codes")) {
    // CODE = "meaning": each key a G- or M-code as programs write it ("G70", "G54.1", "M91"),
    // "T", "D" or "L" for every word of that letter, or a keyword ("SOFT", "TRANS").
    TableReader r(*t, path, "codes.");
    for (auto&& [key, value] : *t) {
      const std::string k(key.str());
      if (value.is_table())
        r.fail(key.source(), k, "a code with a point is quoted (\"G54.1\" = ...): bare, TOML reads it as a table");
      std::string upper = k;
      for (char& ch : upper) ch = char(std::toupper(static_cast<unsigned char>(ch)));
      const auto code = code_named(k);
      const bool letter = upper == "T" || upper == "D" || upper == "L";
      auto alpha = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
      const bool keyword = upper.size() >= 2 && alpha(upper[0]) && alpha(upper[1]) &&
                           std::all_of(upper.begin(), upper.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
      if (!code && !letter && !keyword)
        r.fail(key.source(), k,
               "expected a G- or M-code as the key (\"G70\", \"G54.1\", \"M91\"), \"T\", \"D\" or \"L\", or a keyword (\"SOFT\")");
      const int meaning = r.choice(k, {"inch", "mm", "diameter", "radius", "settings", "mode", "frame", "machine", "moves", "pole", "polar", "cycle-calls", "cycle-call",
                                      "macro-calls", "unmodelled", "arc-radius", "loop"});
      if (CodeMeaning(meaning) == CodeMeaning::ArcRadius && (code || letter))
        r.fail(key.source(), k, "\"arc-radius\" is a keyword's meaning (CR = \"arc-radius\"): its value is the radius");
      if (code) d.codes.push_back({code->first, code->second, CodeMeaning(meaning), {}});
      else if (letter) d.codes.push_back({upper[0], 0, CodeMeaning(meaning), {}});
      else d.codes.push_back({'&', 0, CodeMeaning(meaning), upper});
    }
    r.finish();
  }
  if (const toml::table* t = top.table("numbers")) {
    TableReader r(*t, path, "numbers.");
    r.boolean("decimal_point", d.decimal_point);
    r.number("integer_increment_mm", d.integer_increment_mm, 0, 1);
    r.number("integer_increment_inch", d.integer_increment_inch, 0, 1);
    r.integer("max_significant_digits", d.max_significant_digits, 0, 17);
    read_digits(r, r.table("mm"), path, "numbers.mm.", d.mm);
    read_digits(r, r.table("inch"), path, "numbers.inch.", d.inch);
    r.finish();
  }
  if (const toml::table* t = top.table("lines")) {
    TableReader r(*t, path, "lines.");
    r.integer("max_length", d.max_line_length, 20, 100000);
    std::vector<std::string> comments;
    if (r.strings("comments", comments, {"paren", "semicolon"})) {
      d.paren_comments = std::count(comments.begin(), comments.end(), "paren") > 0;
      d.semicolon_comments = std::count(comments.begin(), comments.end(), "semicolon") > 0;
    }
    r.strings("refused", d.refused);
    r.boolean("indented_blocks", d.indented_blocks);
    r.boolean("assignments", d.assignments);
    r.boolean("labels", d.labels);
    r.boolean("numbered_labels", d.numbered_labels);
    r.finish();
  }
  if (const toml::table* t = top.table("throughput")) {
    TableReader r(*t, path, "throughput.");
    r.number("max_blocks_per_s", d.max_blocks_per_s, 0, 1e9);
    r.number("link_bytes_per_s", d.link_bytes_per_s, 0, 1e12);
    r.finish();
  }
  top.finish();
  return d;
}

Dialect load_dialect_file(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(utf8_path(path), ec)) throw Error(kExitIo, fmt::format("cannot read dialect file '{}': it is a folder", path));
  errno = 0;
  std::ifstream f(utf8_path(path), std::ios::binary);
  if (!f)
    throw Error(kExitIo, fmt::format("cannot read dialect file '{}': {}", path,
                                     errno ? std::strerror(errno) : ec ? ec.message() : "cannot open it"));
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_dialect(ss.str(), path);
}

std::vector<std::string> dialect_search_path(const std::string& exe_dir) {
  std::vector<std::string> dirs;
  if (const std::optional<std::string> env = platform::environment("ARCPRESS_DIALECT_PATH")) {
    const std::string& s = *env;
    size_t a = 0;
    while (a <= s.size()) {
      size_t b = s.find(platform::path_list_separator(), a);
      if (b == std::string::npos) b = s.size();
      if (b > a) dirs.push_back(s.substr(a, b - a));
      a = b + 1;
    }
  }
  if (!exe_dir.empty()) {
    dirs.push_back(utf8_string((utf8_path(exe_dir) / ".." / "share" / "arcpress" / "dialects").lexically_normal()));
    dirs.push_back(utf8_string((utf8_path(exe_dir) / ".." / "dialects").lexically_normal()));
    dirs.push_back(utf8_string(utf8_path(exe_dir) / "dialects"));  // beside the program (as unpacked from a zip)
  }
  if (*ARCPRESS_SOURCE_DIALECT_DIR) dirs.push_back(ARCPRESS_SOURCE_DIALECT_DIR);
  return dirs;
}

std::vector<Dialect> list_dialects(const std::vector<std::string>& search_path) {
  std::vector<Dialect> out;
  std::set<std::string> names;
  for (const auto& dir : search_path) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(utf8_path(dir), ec))
      if (e.path().extension() == ".toml") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& p : files) {
      if (names.count(utf8_string(p.stem()))) continue;
      names.insert(utf8_string(p.stem()));
      out.push_back(load_dialect_file(utf8_string(p)));
    }
  }
  std::sort(out.begin(), out.end(), [](const Dialect& a, const Dialect& b) { return a.name < b.name; });
  return out;
}

Dialect find_dialect(const std::string& name, const std::vector<std::string>& search_path) {
  for (const auto& dir : search_path) {
    fs::path p = utf8_path(dir) / utf8_path(name + ".toml");
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) {
      Dialect d = load_dialect_file(utf8_string(p));
      if (d.name != name)
        throw Error(kExitInput, fmt::format("{}: declares name = \"{}\", expected \"{}\"", utf8_string(p), d.name, name));
      return d;
    }
  }
  std::string known;
  for (const auto& d : list_dialects(search_path)) known += (known.empty() ? "" : ", ") + d.name;
  throw Error(kExitInput, fmt::format("unknown dialect '{}' (known: {}; searched: {})", name,
                                      known.empty() ? "none" : known, fmt::join(search_path, ", ")));
}

}  // namespace arcpress
