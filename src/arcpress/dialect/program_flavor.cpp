// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/dialect/program_flavor.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace arcpress {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// Slicers' flavor names that say which firmware, and the shipped dialect of each.
constexpr std::pair<const char*, const char*> kFlavors[] = {
    {"marlin", "marlin"},     {"marlin2", "marlin"},  {"marlinlegacy", "marlin"},
    {"marlinfirmware", "marlin"}, {"marlin(volumetric)", "marlin"},  // Cura's "RepRap (Volumetric)"
    {"klipper", "klipper"},   {"reprapfirmware", "reprapfirmware"},
    {"smoothie", "smoothieware"}, {"smoothieware", "smoothieware"},
};

/// The shipped dialect a slicer's flavor name maps to without doubt, or empty.
/// The dialect of the firmware a Prusa printer model runs (`model` lower case): Buddy on the
/// MK3.5, MK3.9, MK4, MINI, XL and CORE One; Prusa-Firmware on the MK3, MK3S and MK2.5 (and
/// their MMU variants, "MK3SMMU2S"); empty for any other.
std::string dialect_of_model(std::string_view model) {
  auto starts = [&](std::string_view prefix) { return model.substr(0, prefix.size()) == prefix; };
  for (std::string_view buddy : {"mk3.5", "mk3.9", "mk4", "mini", "xl", "coreone"})
    if (starts(buddy)) return "prusa";
  return starts("mk3") || starts("mk2.5") ? "prusa-mk3" : "";
}

/// The printer model `l` (a line in lower case) names: PrusaSlicer's `; printer_model = MK3S`
/// in its config block, or the model check its Prusa profiles' start G-code makes,
/// `M862.3 P "MK3S"`; empty where it names none.
std::string_view model_named(std::string_view l) {
  if (l.substr(0, 6) == "m862.3") {
    const size_t open = l.find('"'), close = open == std::string_view::npos ? open : l.find('"', open + 1);
    return close == std::string_view::npos ? std::string_view() : l.substr(open + 1, close - open - 1);
  }
  if (l.empty() || l.front() != ';') return {};
  std::string_view rest = trimmed(l.substr(1));
  if (rest.substr(0, 13) != "printer_model") return {};
  rest = trimmed(rest.substr(13));
  return rest.empty() || rest.front() != '=' ? std::string_view() : trimmed(rest.substr(1));
}

std::string dialect_of_flavor(const std::string& flavor) {
  for (const auto& [name, dialect] : kFlavors)
    if (flavor == name) return dialect;
  return {};
}

/// Whether `text` is a Heidenhain ISO program's begin block: `%`, the program's name, its
/// units (G70 or G71) and the block end, `%PART G71 *`.
bool tnc_begin_block(std::string_view text) {
  if (text.size() < 2 || text.front() != '%') return false;
  size_t i = 1;
  auto name_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; };
  while (i < text.size() && name_char(text[i])) ++i;
  if (i == 1) return false;
  std::string_view rest = trimmed(text.substr(i));
  if (rest.size() < 4 || (rest[0] != 'G' && rest[0] != 'g') || rest[1] != '7' || (rest[2] != '0' && rest[2] != '1'))
    return false;
  rest = trimmed(rest.substr(3));
  return !rest.empty() && rest.front() == '*';
}

/// Whether `text` is the first line a Sinumerik control writes in a program file it passes
/// on, `%_N_PART1_MPF` (a main program; `_SPF` a subprogram).
bool sinumerik_file_header(std::string_view text) {
  if (text.size() < 9 || text.substr(0, 4) != "%_N_") return false;
  const std::string_view tail = text.substr(text.size() - 4);
  return tail == "_MPF" || tail == "_SPF";
}

}  // namespace

std::optional<ProgramFlavor> program_flavor(std::string_view program) {
  uint32_t line = 0;
  size_t at = 0;
  bool first = true;  // (no line with text read yet)
  std::optional<ProgramFlavor> flavor_line, model;  // the first of each read
  while (at < program.size()) {
    const size_t end = std::min(program.find('\n', at), program.size());
    std::string_view text = trimmed(program.substr(at, end - at));
    ++line;
    at = end + 1;
    if (first && line == 1 && text.substr(0, 3) == "\xEF\xBB\xBF") text = trimmed(text.substr(3));  // UTF-8 BOM
    if (first && !text.empty()) {
      first = false;
      if (tnc_begin_block(text)) return ProgramFlavor{"heidenhain-iso", std::string(text), line, false};
      if (sinumerik_file_header(text)) return ProgramFlavor{"sinumerik", std::string(text), line, false};
    }
    if (text.empty() || (text.front() != ';' && ((text.front() != 'M' && text.front() != 'm') || lower(text.substr(0, 6)) != "m862.3")))
      continue;
    const std::string l = lower(text);
    // A Prusa printer's model says which of Prusa's firmwares runs it, where the flavor says
    // only Marlin (or nothing): the first line that names one is kept.
    if (!model)
      if (const std::string d = dialect_of_model(model_named(l)); !d.empty()) {
        model = ProgramFlavor{d, std::string(text), line};
        if (flavor_line) return model;
        model->model_only = true;
      }
    if (text.front() != ';') continue;
    if (l.rfind(";$path=/_n_", 0) == 0) return ProgramFlavor{"sinumerik", std::string(text), line, false};
    std::string flavor;
    if (l.rfind(";flavor:", 0) == 0) {  // Cura
      flavor = lower(trimmed(std::string_view(l).substr(8)));
    } else {
      std::string_view rest = trimmed(std::string_view(l).substr(1));
      if (rest.rfind("gcode_flavor", 0) != 0) continue;  // PrusaSlicer, SuperSlicer, OrcaSlicer, Slic3r
      rest = trimmed(rest.substr(12));
      if (rest.empty() || rest.front() != '=') continue;
      flavor = std::string(trimmed(rest.substr(1)));
    }
    // (An empty dialect: a flavor, but not one that says which firmware.)
    if (flavor_line) continue;  // (the first one counts)
    flavor_line = ProgramFlavor{dialect_of_flavor(flavor), std::string(text), line};
    if (flavor_line->dialect != "marlin") return flavor_line;
    if (model) return model->model_only = false, model;
  }
  return model ? model : flavor_line;
}

std::string dialect_of_extension(std::string_view path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string_view::npos || path.find_first_of("/\\", dot) != std::string_view::npos) return {};
  const std::string ext = lower(path.substr(dot + 1));
  return ext == "mpf" || ext == "spf" ? "sinumerik" : std::string();
}

std::vector<std::string> flavor_dialects() {
  std::vector<std::string> out;
  for (const auto& [name, dialect] : kFlavors)
    if (std::find(out.begin(), out.end(), dialect) == out.end()) out.push_back(dialect);
  return out;
}

}  // namespace arcpress
