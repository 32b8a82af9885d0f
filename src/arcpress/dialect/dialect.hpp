// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a target controller reads and refuses. A Dialect is data: it is loaded from a TOML
// file under dialects/ (see dialect_loader.hpp and dialects/README.md for every field), and
// the stages that read programs (model) and write them (emit) consult it instead of
// branching on a controller's name. A default-constructed Dialect is generic RS274/NGC and
// equals dialects/rs274.toml.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "arcpress/core/geometry.hpp"
#include "arcpress/dialect/arc_segmentation.hpp"

namespace arcpress {

/// How the controller reads I/J/K.
enum class CentreReading : uint8_t {
  Incremental,  ///< offset from the arc's start (RS274 G91.1); G90.1 switches to absolute where allowed
  Absolute,     ///< the centre itself in program coordinates (Heidenhain ISO); offset from the start under G91
};

/// The form in which arcpress writes an arc's centre.
enum class ArcFormat : uint8_t {
  Centre,  ///< I/J/K, read as CentreReading says
  Radius,  ///< R, negative for sweeps over 180 degrees
};

/// How a printer firmware reads E words after G90/G91 and M82/M83 ([printer] extrusion_distance).
enum class ExtrusionDistance : uint8_t {
  WithAxes,    ///< G90/G91 set E's mode with the axes', M82/M83 then E's alone (Marlin 2, Smoothieware)
  G91OrM83,    ///< E is relative under G91 or after M83, each kept apart (Klipper, Marlin 1)
  M82M83Only,  ///< only M82/M83 set it; G90/G91 are the axes' alone (RepRapFirmware 3)
};

/// E's relative mode after G90 or G91 (`distance`) or after M82 or M83 (not `distance`), which
/// sets relative mode or not (`relative`): `m83` (E's own flag) is updated, and the result says
/// whether E words are relative, the axes being absolute or not (`axes_absolute`).
inline bool extrusion_after(ExtrusionDistance rule, bool distance, bool relative, bool axes_absolute, bool& m83) {
  if (!distance || rule == ExtrusionDistance::WithAxes) m83 = relative;
  return m83 || (rule == ExtrusionDistance::G91OrM83 && !axes_absolute);
}

/// The units a program is read in until its first G20 or G21.
enum class StartUnits : uint8_t {
  Mm,       ///< the controller always starts in millimetres (printer firmwares)
  Inch,     ///< it starts in inches
  Machine,  ///< a setting of the machine's decides (a parameter, a startup block, an INI file):
            ///< read in millimetres, and a program that gives lengths before G20 or G21 is warned of
};

/// How I/J/K are read before the program says G90.1 or G91.1 (RS274 dialects).
enum class StartCentres : uint8_t {
  Incremental,  ///< offsets from the arc's start (G91.1), as RS274 starts
  Absolute,     ///< the absolute centre (G90.1)
  Machine,      ///< a setting of the controller's own (Mach3's IJ mode): read as offsets until an
                ///< arc is whole only as the absolute centre, which then holds; the output states
                ///< the mode (G90.1/G91.1) wherever its arcs, or the program's own after them, need it
};

/// What a code means on a controller that reads it otherwise than RS274 does ([codes]):
/// Heidenhain ISO's G70/G71 are inches and millimetres (RS274's lathe cycles), its G30/G31
/// the blank's corners (a reference return and a skip move), its G54 a datum shift whose
/// axis words are the shift, its T word a tool call that may move the tool.
enum class CodeMeaning : uint8_t {
  Inch,        ///< lengths in inches from here (RS274's G20)
  Mm,          ///< lengths in millimetres from here (RS274's G21)
  Diameter,    ///< X words are diameters from here (RS274's lathe G7; Sinumerik's DIAMON)
  Radius,      ///< X words are radii from here (RS274's lathe G8; Sinumerik's DIAMOF)
  Settings,    ///< sets something the path does not depend on; its axis words and F are values, not a
               ///< place and a feed, and a T word in its block names a tool without calling it
  Mode,        ///< switches a mode the path does not depend on (exact stop, look-ahead, smoothing); the
               ///< rest of its block is read as RS274 reads it: `G09 G01 X10.` moves
  Frame,       ///< changes the coordinates (a datum shift, mirroring, rotation, scaling): its axis
               ///< words are the change's, and the position is known again only once every axis is given
  Machine,     ///< the block's axis words are machine coordinates (RS274's G53)
  Moves,       ///< may move the tool where the program does not say (a tool call, a retraction):
               ///< the position is known again only once every axis is given
  Pole,        ///< the present position becomes the centre arcs turn about (centre_modal; Heidenhain's G29)
  Polar,       ///< a move about that centre arcpress does not read (Heidenhain's polar moves): as
               ///< Unmodelled, and the centre is stated again before it where arcpress's own arcs moved it
  CycleCalls,  ///< from this block on, every move calls the cycle last defined at its end (Heidenhain's M89)
  CycleCall,   ///< calls that cycle at the end of this block's move, or where the tool is, and ends CycleCalls
  MacroCalls,  ///< as CycleCalls from the next move on; its own block's axis words are the call's
               ///< arguments, not a place (Fanuc's G66)
  Unmodelled,  ///< not read: the block is kept, not fitted, and the position is known again as after Frame
  ArcRadius,   ///< a keyword whose value is the arc's radius, as RS274's R word (Sinumerik's CR=5)
  Loop,        ///< with an L word, the blocks after it may be entered again from a later block (a repeat
               ///< marker: Marlin's M808 L3); without one, the loop's end, from which the program goes on
};

/// One code the dialect reads its own way: a G- or M-code, every word of a letter (T, D, L),
/// or a keyword (Sinumerik's `SOFT`, `TRANS`, `MCALL`).
struct CodeReading {
  char letter = 'G';  ///< 'G', 'M', 'T', 'D', 'L', or '&' for a keyword
  int code10 = 0;     ///< the code times ten (G70: 700, G54.1: 541); 0 for a letter or keyword
  CodeMeaning meaning = CodeMeaning::Unmodelled;
  std::string keyword;  ///< a keyword's name in upper case
};

/// A G-code that turns the way the last arc programmed before it turned (Heidenhain's G05 and
/// G15, which take the direction of the last G02/G03 or G12/G13), and the codes that turn each
/// way in its stead ([arcs.last_turn]). Those codes set the way; so do G02 and G03.
struct TurnReading {
  int code10 = 0;             ///< the code times ten (G05: 50)
  int cw10 = 20, ccw10 = 30;  ///< the codes for clockwise and counter-clockwise, times ten
};

/// Digits for numbers arcpress computes itself (centres, relative moves). Numbers copied
/// from the input keep the input's own text.
struct NumberDigits {
  int axis = 4;        ///< decimals for X..W when arcpress computes the value
  int centre = 4;      ///< decimals for I/J/K/R normally printed
  int max = 6;         ///< most decimals the controller reads; centres may use up to this
  int feed = 1;        ///< decimals for F
  int e = 5;           ///< decimals for E
};

struct Dialect {
  std::string name = "rs274";
  std::string description = "Generic RS274/NGC: I/J/K incremental centres, all planes, helices";
  std::string source;  ///< the file it was loaded from, empty for the built-in default

  // --- arcs -------------------------------------------------------------------------
  bool arcs = true;                             ///< false: never write G2/G3 (lines only)
  CentreReading centre = CentreReading::Incremental;
  bool centre_mode_words = true;                ///< G90.1/G91.1 are understood
  /// I/J/K set a centre that holds until the next (Heidenhain's pole): a block with centre
  /// words and no axis words sets it and moves nothing, and an arc without them turns about it.
  bool centre_modal = false;
  /// Codes that turn the way the last programmed arc turned ([arcs.last_turn]): where arcs
  /// arcpress wrote came between, such a block gets the program's way as its own code.
  std::vector<TurnReading> last_turn;
  bool radius_word = true;                      ///< R form accepted
  ArcFormat format = ArcFormat::Centre;         ///< what arcpress writes unless told otherwise
  std::string arc_header;                       ///< a block written before the first arc (of each piece of a stream), e.g. "G91.1"
  uint8_t planes = 0b111;                       ///< bit 0 XY (G17), bit 1 ZX (G18), bit 2 YZ (G19)
  bool helical = true;                          ///< linear motion along the plane's normal inside an arc
  bool extra_axes = false;                      ///< A/B/C, U/V/W words inside an arc, moved linearly
  bool relative_arcs = true;                    ///< arcs allowed under G91
  bool zx_reversed = false;                     ///< G2/G3 turn the other way in G18 (Klipper)
  double max_sweep_deg = 180.0;                 ///< per block
  double min_sweep_deg = 0.01;                  ///< below: read as no motion or a full circle
  double min_radius_mm = 0.0;
  double max_radius_mm = 1000.0;                ///< above: lines (huge I/J amplify rounding)
  double min_arc_length_mm = 0.0;               ///< shorter arcs: lines (firmware re-segmentation)
  int min_arc_moves = 0;                        ///< an arc must replace at least this many G1 moves
  double min_chord_mm = 0.001;                  ///< closer printed end points read as a full circle
  /// The controller refuses an arc whose start and end radius differ by more than
  /// radius_abs_mm and (when radius_rel > 0) by more than radius_rel times the radius.
  /// 0 for radius_abs_mm: the controller does not check (printers jump at the end).
  double radius_abs_mm = 0.0283;
  double radius_rel = 0.001;
  /// How the firmware cuts arcs into the chords it moves along ([arcs.executed]); where it
  /// has a rule, the band is held on those chords by default (--band executed).
  ArcSegmentation executed;

  // --- machine ----------------------------------------------------------------------
  /// What a length means before the program's first G20 or G21 ([startup] units).
  StartUnits start_units = StartUnits::Machine;
  /// How I/J/K are read before G90.1 or G91.1 ([startup] arc_centres).
  StartCentres start_centres = StartCentres::Incremental;
  /// X words are diameters from the start, as on lathes that power up in diameter mode
  /// (Haas, Fanuc); G7/G8 still switch where the program writes them.
  bool diameter_x = false;
  /// A printer firmware's own retraction ([printer] firmware_retraction): G10 without L and
  /// without axis words retracts the filament (or, with P, sets a tool's temperatures), G11
  /// recovers it; neither moves the programmed position (a Z hop is undone on recovery).
  /// Elsewhere G10 sets offsets or tables and G11 is not read.
  bool firmware_retraction = false;
  /// How E words read after G90/G91 and M82/M83 ([printer] extrusion_distance).
  ExtrusionDistance extrusion_distance = ExtrusionDistance::WithAxes;
  /// A line's leading blanks open and close blocks ([lines] indented_blocks): RepRapFirmware
  /// 3 runs the lines indented below an `if`, `else` or `while` as its block (BlockNesting).
  bool indented_blocks = false;
  /// Lines assign to parameters and addresses with `=` ([lines] assignments): Sinumerik's
  /// `R1=5`, `X=R1*2`, `X=IC(5)` (LexRules::assignments).
  bool assignments = false;
  /// Blocks begin with labels, the targets of jumps by name ([lines] labels): Sinumerik's
  /// `LOOP1:`, named by `GOTOB LOOP1` (LexRules::labels).
  bool labels = false;
  /// Numbered labels and their repeats and calls ([lines] numbered_labels): Heidenhain ISO's
  /// `G98 L1`, `L1,2`, `L1,0` (LexRules::numbered_labels).
  bool numbered_labels = false;
  /// Extended commands (Klipper's `NAME ARG=...` lines, by their name in capitals) that move
  /// nothing ([printer] position_keeping_commands): the position stays known across them.
  /// Any other such command, a user's macro among them, may move anything.
  std::vector<std::string> position_keeping_commands;
  /// Codes read otherwise than RS274 reads them ([codes]); the rest as RS274.
  std::vector<CodeReading> codes;
  /// The entry of last_turn for G-code `code10`, or null.
  const TurnReading* turn_reading(int code10) const {
    for (const TurnReading& t : last_turn)
      if (t.code10 == code10) return &t;
    return nullptr;
  }
  /// The way G-code `code10` sets for the codes of last_turn: 2 clockwise, 3 counter-clockwise
  /// (G02 and G03, and the codes last_turn names), 0 none.
  int turn_set_by(int code10) const {
    if (code10 == 20 || code10 == 30) return code10 / 10;
    for (const TurnReading& t : last_turn)
      if (t.cw10 == code10 || t.ccw10 == code10) return t.cw10 == code10 ? 2 : 3;
    return 0;
  }
  /// Whether the extended command on `line` is one of position_keeping_commands (any case).
  bool keeps_position(std::string_view line) const {
    if (position_keeping_commands.empty()) return false;
    size_t i = 0;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '/')) ++i;
    size_t e = i;
    while (e < line.size() && (std::isalnum(static_cast<unsigned char>(line[e])) || line[e] == '_')) ++e;
    const std::string_view command = line.substr(i, e - i);
    return std::any_of(position_keeping_commands.begin(), position_keeping_commands.end(), [&](const std::string& n) {
      return n.size() == command.size() && std::equal(n.begin(), n.end(), command.begin(), [](char x, char y) {
               return x == std::toupper(static_cast<unsigned char>(y));
             });
    });
  }
  /// The G-code (times ten) [codes] gives `meaning`, else `rs274` (the units' codes, named in
  /// W-MODEL-UNITS).
  int code_for(CodeMeaning meaning, int rs274) const {
    for (const CodeReading& c : codes)
      if (c.meaning == meaning) return c.code10;
    return rs274;
  }
  /// The meaning the dialect gives code `letter` `code10` (times ten; 0 for every word of a
  /// letter), or null where it reads it as RS274.
  const CodeMeaning* meaning_of(char letter, int code10) const {
    for (const CodeReading& c : codes)
      if (c.letter == letter && c.code10 == code10) return &c.meaning;
    return nullptr;
  }
  /// The meaning of keyword `word` (any case), or null where the dialect reads no such keyword.
  const CodeMeaning* keyword_meaning(std::string_view word) const {
    for (const CodeReading& c : codes)
      if (c.letter == '&' && c.keyword.size() == word.size() &&
          std::equal(word.begin(), word.end(), c.keyword.begin(),
                     [](char x, char y) { return std::toupper(static_cast<unsigned char>(x)) == y; }))
        return &c.meaning;
    return nullptr;
  }

  // --- numbers ----------------------------------------------------------------------
  NumberDigits mm{4, 4, 6, 1, 5};
  NumberDigits inch{5, 5, 7, 2, 5};
  bool decimal_point = false;        ///< every number needs a point ("X1." ; "X1" is 1 increment)
  /// With decimal_point: what a number without a point means, in units of the least
  /// increment (Fanuc IS-B: 0.001 mm, 0.0001 in). 0: a number without a point is whole units.
  double integer_increment_mm = 0.0;
  double integer_increment_inch = 0.0;
  int max_significant_digits = 0;    ///< 0: no limit (Grbl parses 8)

  // --- lines ------------------------------------------------------------------------
  size_t max_line_length = 255;       ///< characters, end of line excluded

  // --- throughput ([throughput]) ---------------------------------------------------
  /// Blocks per second the controller takes at most (its planner and parser); 0: not set.
  double max_blocks_per_s = 0;
  /// Bytes per second the link to the controller carries (a serial line at B baud with 8N1
  /// framing: B / 10); 0: not set (a host-resident or USB controller).
  double link_bytes_per_s = 0;
  bool paren_comments = true;         ///< "( ... )" is a comment
  bool semicolon_comments = true;     ///< ";" starts a comment to the end of the line
  /// Words the controller refuses in a program: a letter ("O"), a code ("G90.1") or "%".
  /// arcpress never writes them and warns where the input has them.
  std::vector<std::string> refused;

  bool plane_allowed(Plane p) const { return (planes >> int(p)) & 1u; }
  const NumberDigits& digits(bool inch_units) const { return inch_units ? inch : mm; }
  /// Largest end-radius difference arcpress lets through: the controller's rule, and never
  /// more than kRadiusAimMm so every controller runs the arc as a true circle.
  double radius_allowance_mm(double radius_mm) const;
  /// True when the controller refuses `code` ("O", "G90.1", "%").
  bool refuses(std::string_view code) const;
};

/// arcpress's own target for the end-radius error after rounding, for every controller.
inline constexpr double kRadiusAimMm = 0.002;

}  // namespace arcpress
