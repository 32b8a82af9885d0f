// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/api/compressor.hpp"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "arcpress/api/piece.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/core/workers.hpp"
#include "arcpress_commit.hpp"
#include "arcpress/extract/run.hpp"
#include "arcpress/lex/foreign_content.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/lex/refusal_scan.hpp"
#include "arcpress/model/called_programs.hpp"
#include "arcpress/model/jump_entries.hpp"
#include "arcpress/model/interpreter.hpp"

namespace arcpress {

void reserve_piece(Program& program, Interpretation& in) {
  program.text.reserve(kPieceBytes + (size_t(1) << 12));
  program.blocks.reserve(kPieceBytes / 20);
  program.words.reserve(kPieceBytes / 6);
  in.moves.reserve(kPieceBytes / 24);
  in.move_of_block.reserve(kPieceBytes / 20);
}

namespace {

/// Whether no chain of runs goes on across the end of move `m`: it is no move a fit may
/// rewrite and no input arc a chain keeps tangent to (chain_runs() closes its chain there).
bool ends_chains(const Move& m) { return !m.in_chain(); }

/// The header comment (CompressOptions::header) without its end of line, in the form of the
/// comment `like` (';' or '('): "; arcpress 0.1.0 commit 1b62caa0e2f3 --tolerance 0.01
/// --dialect marlin ...", naming the version and the commit as `arcpress --version` does.
std::string header_comment(const CompressOptions& o, char like) {
  const std::string text = fmt::format(
      "arcpress {} commit {} --tolerance {} --dialect {} --band {} --g1-angle {} --corner-angle {} --method {}",
      kVersion, ARCPRESS_COMMIT,
      o.fit.tolerance_mm, o.dialect.name,
      kBandNames[size_t(o.executed_rule().moves_on_chords() ? CompressOptions::Band::Executed : CompressOptions::Band::Program)],
      o.fit.g1_angle_deg, o.fit.corner_angle_deg, method_name(o.fit.method));
  const std::string sided = o.fit.band_side == BandSide::Both ? text
                           : text + (o.fit.band_side == BandSide::Left ? " --band-side left" : " --band-side right");
  const std::string units = o.dialect.start_units == StartUnits::Inch ? sided + " --units inch" : sided;
  return like == ';' ? "; " + units : "(" + units + ")";
}

}  // namespace

struct Compressor::Impl {
  struct Slot {
    std::unique_ptr<Piece> piece;
    bool done = false;
  };

  Impl(std::string n, const CompressOptions& o, DiagnosticSink& s)
      : name(std::move(n)), opt(o), sink(s), reader(opt.dialect, s, initial_state(opt.dialect)),
        rules(lex_rules(opt.dialect)) {
    const size_t threads = worker_count(opt.threads, size_t(-1));
    limit = kPiecesInFlight * threads;
    total.ok = true;
    total.verified = opt.verify && !opt.passthrough;
    total.unplaced_kept = true;
    total.band_mm = opt.fit.tolerance_mm;
    total.side_allowance_mm = opt.fit.band_side == BandSide::Both ? 0 : kBandSideRoundingShare * opt.fit.tolerance_mm;
    pool_size = threads > 1 ? threads : 0;
    if (opt.block_rate) {
      meter_in.emplace(opt.dialect.max_blocks_per_s, opt.dialect.link_bytes_per_s);
      meter_out.emplace(opt.dialect.max_blocks_per_s, opt.dialect.link_bytes_per_s);
    }
  }

  ~Impl() {
    {
      std::lock_guard lk(mu);
      stopping = true;
    }
    cv_work.notify_all();
    for (auto& t : workers) t.join();
  }

  void push(std::string_view bytes) {
    rethrow();
    if (finished) throw std::logic_error("Compressor::push() after finish()");
    if (failed) return;
    if (after_end_found) called_ahead();
    bytes_read += bytes.size();
    // Whole lines go from `bytes` to their piece; only a line cut by the push waits in
    // `pending` for its end.
    size_t at = 0;
    if (!pending.empty()) {
      const size_t nl = bytes.find('\n');
      pending.append(bytes.substr(0, nl == std::string_view::npos ? bytes.size() : nl + 1));
      if (nl == std::string_view::npos) return release(false);
      at = nl + 1;
    }
    // The jumps in these lines first: a jump back to a block among them is then in time.
    if (const size_t last = bytes.rfind('\n'); !jumps_ahead && last != std::string_view::npos && last + 1 > at)
      read_jumps(bytes.substr(at, last + 1 - at), line + 1 + (pending.empty() ? 0 : 1), false);
    if (!pending.empty()) {
      if (!jumps_ahead) read_jumps(pending, line + 1, false);
      if (!failed) add_line(pending);
      pending.clear();
    }
    for (size_t nl; !failed && (nl = bytes.find('\n', at)) != std::string_view::npos; at = nl + 1)
      add_line(bytes.substr(at, nl + 1 - at));
    if (!failed) pending.assign(bytes.substr(at));
    release(false);
  }

  void finish() {
    rethrow();
    if (finished) return;
    if (after_end_found) called_ahead();
    finished = true;
    if (!failed && !pending.empty() && !jumps_ahead) read_jumps(pending, line + 1, false);
    if (!failed && !pending.empty()) add_line(pending);
    pending.clear();
    if (!failed && cur) {
      // The last piece is often the only one (a program under kPieceBytes): every thread
      // works on it.
      cur->last = true;
      cur->threads = opt.threads;
      close_piece(true);
    }
    release(true);
    if (!failed && meter_in && meter_out) {
      total.rate_in = meter_in->finish();
      total.rate_out = meter_out->finish();
    }
    // A program with G1 moves of which none could be fitted is told why, where something
    // kept them from it (not where each is alone already, as in a program fitted before).
    const auto& nf = total.not_fitted;
    const auto most = std::max_element(nf.begin(), nf.end(), [](const NotFitted& x, const NotFitted& y) {
      return (x.why == Unfit::None ? 0 : x.moves) < (y.why == Unfit::None ? 0 : y.moves);
    });
    if (!failed && !opt.passthrough && total.g1_moves > 0 && total.runs_fitted == 0 && most != nf.end() &&
        most->why != Unfit::None)
      sink.warning({most->first_line, 1}, "W-FIT-NONE",
                   fmt::format("none of the {} G1 moves could be fitted; {} of them: {}{} (see --stats)",
                               total.g1_moves, most->moves, describe(most->why),
                               most->cause_line ? fmt::format(" at line {}", most->cause_line) : std::string()));
    std::sort(total.forced_kink_lines.begin(), total.forced_kink_lines.end());
    total.forced_kink_lines.erase(std::unique(total.forced_kink_lines.begin(), total.forced_kink_lines.end()),
                                  total.forced_kink_lines.end());
    total.forced_kinks = total.forced_kink_lines.size();
    std::sort(total.comparison.kink_lines.begin(), total.comparison.kink_lines.end());
  }

  size_t take(std::string& out) {
    rethrow();
    release(false);
    const size_t n = ready.size();
    if (out.empty()) out.swap(ready);
    else out += ready;
    ready.clear();
    return n;
  }

  /// Where a piece stood before a line was read into it: what reading it added, to be
  /// taken out again when the piece ends before that line.
  struct Mark {
    size_t text = 0, blocks = 0, words = 0, moves = 0, frames = 0, unplaced = 0, reported = 0;
    ModalState state;
  };

  /// Reads the jumps in `lines` (whole lines from line `first_line`): the blocks they name
  /// are read as places the program may be entered at. One that names a block already read
  /// as no such place comes too late, and fails the program, but where `ahead` (the program's
  /// text read before it is pushed: a file read twice) the lines were not pushed yet.
  void read_jumps(std::string_view lines, uint32_t first_line, bool ahead) {
    jumps_ahead = jumps_ahead || ahead;
    JumpTargets found;
    const size_t ended = found.read(lines, first_line, ahead ? nullptr : &passed);
    if (ahead) {
      // The text after the program's first end, where the subprograms its calls run are
      // written: read before the blocks (called_ahead()).
      if (after_end.size() > kAfterEndBytes) after_end_whole = false;
      else if (after_end_found) after_end += lines;
      else if (ended != std::string_view::npos) after_end_found = true, after_end = lines.substr(ended);
    }
    if (!found.any()) return;
    auto next = jumps ? std::make_shared<JumpTargets>(*jumps) : std::make_shared<JumpTargets>();
    next->merge(found);
    jumps = std::move(next);
    if (cur) cur->program.jumps = jumps;
    if (const auto& late = found.late()) {
      sink.error({late->line, 1}, "E-FLOW-JUMP-BACK",
                 late->computed ? std::string("a jump to a block number the program computes, read after numbered "
                                              "blocks that were read as no jump's target: their moves may have been "
                                              "joined with others; give arcpress the program as a file, whose jumps "
                                              "it reads before its blocks")
                                : fmt::format("a jump back to {}, a block read before as no jump's target: its "
                                              "moves may have been joined with others; give arcpress the program "
                                              "as a file, whose jumps it reads before its blocks",
                                              late->number & kLabelKey ? std::string("a label") : fmt::format("N{}", late->number)));
      failed = true;
      total.ok = false;
      ready.clear();
    }
  }

  /// The loops of `program` (the whole text) whose jump back would run their first moves
  /// in other modes: their starts are read with those not known (Compressor::read_loops()).
  void read_loops(std::string_view program) {
    if (!jumps || failed || program.size() > kLoopsAheadBytes) return;
    if (after_end_found) called_ahead();
    DiagnosticSink quiet(name);
    Program p = lex(name, std::string(program), quiet, rules);
    p.jumps = jumps;
    ModalState s = reader.state();
    const LoopsFound loops = loops_in_other_modes(p, opt.dialect, s);
    if (loops.starts.empty()) return;
    seed_loops(s, loops.starts);
    reader.reset(s);
    for (const Diagnostic& d : loops.told) sink.warning(d.at, d.code, d.message);
  }

  /// What the subprograms in the text after the program's end leave (CalledPrograms), read
  /// before its first block: the reader goes on with it. (Over kAfterEndBytes, none is read:
  /// after a call, the modes a body may change are then not known.)
  void called_ahead() {
    after_end_found = false;
    ModalState s = reader.state();
    DiagnosticSink quiet(name);  // (the blocks are read again in their turn, and told then)
    if (after_end_whole) s.called = read_called_programs(lex(name, std::move(after_end), quiet, rules), 0, opt.dialect);
    after_end = std::string();
    reader.reset(s);
  }

  /// One whole line (with its end of line, or the program's last without).
  void add_line(std::string_view text) {
    if (!cur) open_piece();
    Program& p = cur->program;
    Interpretation& in = cur->in;
    // Past piece_bytes() the piece ends after the first move that ends chains; past
    // kCornerPieceBytes also before a move that starts at a corner (where a chain ends too,
    // though the corner rule then judges the vertices beside it without their neighbours
    // across the cut).
    const bool ending = p.text.size() >= gather_bytes;
    Mark mark;
    if (ending)
      mark = {p.text.size(), p.blocks.size(), p.words.size(), in.moves.size(), in.frames.size(), in.unplaced.size(),
              sink.reported(), reader.state()};
    const size_t begin = p.text.size();
    p.text.append(text);
    lex_line(p, begin, p.text.size(), ++line, sink);
    const uint32_t bi = uint32_t(p.blocks.size() - 1);
    // (Where the jumps were read ahead, none can come late: nothing to note.)
    if (const Block& b = p.blocks[bi]; !jumps_ahead)
      for (const Word* w = p.words_begin(b); w != p.words_end(b) && (w->letter == 'N' || w->letter == kLabelLetter); ++w)
        if (const auto key = w->target_key(); key && (!jumps || !jumps->enters(*key))) passed.pass(*key);
    reader.step(bi);
    if (sink.error_count() > 0) {  // strict mode: nothing more is written
      failed = true;
      total.ok = false;
      ready.clear();
      return;
    }
    if (!ending) return;
    const int32_t m = in.move_of_block[bi];
    // A line taken out again, to be read again as the next piece's first line (it said
    // nothing the first time, so reading it again repeats no diagnostic): the piece ends
    // before it.
    const bool silent = sink.reported() == mark.reported;
    auto end_before_line = [&] {
      p.text.resize(mark.text);
      p.blocks.resize(mark.blocks);
      p.words.resize(mark.words);
      in.moves.resize(mark.moves);
      in.move_of_block.resize(mark.blocks);
      in.frames.resize(mark.frames);
      in.unplaced.resize(mark.unplaced);
      reader.reset(mark.state);
      --line;
      close_piece(false);
      add_line(text);
    };
    if (m >= 0 && ends_chains(in.moves[size_t(m)])) {
      close_piece(true);
    } else if (p.text.size() >= kCornerPieceBytes && m >= 1 && silent && starts_at_corner(size_t(m))) {
      end_before_line();
    } else if (p.text.size() >= kMaxPieceBytes) {
      // A forced cut ends the piece before a move a fit may rewrite, or after a line that is
      // no such move where the last move is not one either: never between such a move and
      // the lines after it, where a code arcpress does not model keeps it as written (it
      // may go on from it, a rounding say), which it could no longer do from the next
      // piece. Past twice kMaxPieceBytes the piece is cut after any line.
      const bool fittable_line = m >= 0 && in.moves[size_t(m)].fittable();
      const bool last_fittable = !in.moves.empty() && in.moves.back().fittable();
      if (fittable_line && silent && m >= 1) {
        ++forced;
        end_before_line();
      } else if (!last_fittable || m >= 0 || p.text.size() >= 2 * kMaxPieceBytes) {
        ++forced;
        close_piece(false);
      }
    }
  }

  /// Whether move m of the piece, a G1 a fit may rewrite after another, starts at a corner
  /// of the path: its chain of runs ends there (chain_runs()).
  bool starts_at_corner(size_t m) const {
    const Interpretation& in = cur->in;
    return in.moves[m].fittable() && in.moves[m - 1].fittable() && in.moves[m].frame == in.moves[m - 1].frame &&
           corner_at(in, m, opt.fit.tolerance_mm, opt.fit.corner_angle_deg);
  }

  void open_piece() {
    cur = std::make_unique<Piece>();
    if (spare) {
      // A released piece's buffers, emptied: reading into memory already touched, not new.
      auto take = [](auto& to, auto& from) {
        to = std::move(from);
        to.clear();
      };
      take(cur->program.text, spare->program.text);
      take(cur->program.blocks, spare->program.blocks);
      take(cur->program.words, spare->program.words);
      take(cur->in.moves, spare->in.moves);
      take(cur->in.move_of_block, spare->in.move_of_block);
      spare.reset();
    }
    cur->index = pieces++;
    gather_bytes = piece_bytes(cur->index);
    cur->program.name = name;
    cur->program.rules = rules;
    cur->program.jumps = jumps;
    reserve_piece(cur->program, cur->in);
    cur->start = reader.state();
    cur->emit = next_emit;
    reader.begin(cur->program, cur->in);
  }

  void close_piece(bool clean) {
    Piece& p = *cur;
    // What is not G-code at all is refused before a byte of it is written.
    if (p.index == 0)
      if (const std::optional<ForeignContent> foreign = foreign_content(p.program, p.last)) {
        sink.error(foreign->at, "E-INPUT-NOT-GCODE", fmt::format("does not look like G-code ({})", foreign->why));
        failed = true;
        total.ok = false;
        ready.clear();
        cur.reset();
        return;
      }
    p.end = reader.state();
    p.clean_end = clean;
    if (!habits) habits = output_habits(p.program);
    p.emit.habits = habits;
    scan_refusals(p.program, opt.dialect, sink);
    for (const Word& w : p.program.words) centre_mode_set = centre_mode_set || sets_centre_mode(w);
    next_emit.in_motion = p.end.motion;
    next_emit.out_motion = clean ? p.end.motion : -1;
    next_emit.header_done = centre_mode_set;
    next_emit.centres_maybe_said = !opt.passthrough && opt.fit.method != FitOptions::Method::Keep && opt.dialect.arcs;
    next_emit.pole_maybe_moved = next_emit.centres_maybe_said && opt.dialect.centre_modal;
    next_emit.turn_maybe_moved = next_emit.centres_maybe_said && !opt.dialect.last_turn.empty();
    dispatch(std::move(cur));
  }

  void dispatch(std::unique_ptr<Piece> piece) {
    // One thread, or a program that is one piece (its threads then work inside it): here.
    // Otherwise the workers, started with the first piece that goes to them.
    if (pool_size == 0 || (piece->last && workers.empty())) {
      compress_piece(*piece, opt);
      flight.push_back({std::move(piece), true});
      release(false);
      return;
    }
    if (workers.empty())
      for (size_t w = 0; w < pool_size; ++w) workers.emplace_back([this] { work(); });
    {
      std::lock_guard lk(mu);
      flight.push_back({std::move(piece), false});
      todo.push_back(&flight.back());
    }
    cv_work.notify_one();
    while (true) {
      release(false);
      std::unique_lock lk(mu);
      if (flight.size() < limit || failure) break;
      cv_done.wait(lk, [&] { return flight.front().done || failure; });
    }
    rethrow();
  }

  /// Puts the header comment (CompressOptions::header) into the first piece's `text` after
  /// its first line, where that is a comment the dialect reads and not followed by one
  /// already, in the same form; the lines added.
  size_t insert_header(std::string& text) const {
    if (!opt.header || opt.passthrough) return 0;
    const size_t eol = text.find('\n');
    if (eol == std::string::npos) return 0;
    const std::string_view first(text.data(), eol);
    const size_t c = first.find_first_not_of(" \t");
    const bool comment = c != std::string_view::npos &&
                         ((first[c] == ';' && opt.dialect.semicolon_comments) || (first[c] == '(' && opt.dialect.paren_comments));
    const size_t next_eol = text.find('\n', eol + 1);
    const std::string_view second(text.data() + eol + 1, (next_eol == std::string::npos ? text.size() : next_eol) - eol - 1);
    if (!comment || is_arcpress_header(first) || is_arcpress_header(second)) return 0;
    const bool crlf = eol > 0 && text[eol - 1] == '\r';
    text.insert(eol + 1, header_comment(opt, first[c]) + (crlf ? "\r\n" : "\n"));
    return 1;
  }

  /// Moves the finished pieces at the front, in order, into `ready` and the result; with
  /// `all`, waits for every piece.
  void release(bool all) {
    while (true) {
      Slot slot;
      {
        std::unique_lock lk(mu);
        if (all) cv_done.wait(lk, [&] { return flight.empty() || flight.front().done || failure; });
        if (failure || flight.empty() || !flight.front().done) break;
        slot = std::move(flight.front());
        flight.pop_front();
      }
      if (failed) continue;
      // The header goes after the first line of the first piece, so its other lines move down one.
      const size_t header_lines = slot.piece->index == 0 ? insert_header(slot.piece->result.output) : 0;
      add_piece(total, *slot.piece, lines_out + header_lines);
      lines_out += header_lines;
      // The block rate runs on across pieces: their timed blocks in program order.
      if (meter_in && meter_out) {
        Piece& p = *slot.piece;
        for (const TimedBlock& b : p.timed_in) meter_in->add(b);
        for (const TimedBlock& b : p.timed_out) meter_out->add(b);
        meter_in->add_untimed(p.untimed_in);
        meter_out->add_untimed(p.untimed_out);
        std::vector<TimedBlock>().swap(p.timed_in);
        std::vector<TimedBlock>().swap(p.timed_out);
      }
      // The joint across the cut, which neither piece's check saw whole.
      if (slot.piece->index > 0 && total.verified) {
        if (const auto turn = joint_turn_deg(prev_tail, slot.piece->head, opt.fit.tolerance_mm, opt.fit.corner_angle_deg)) {
          PathComparison& c = total.comparison;
          ++c.smooth_joints;
          c.max_smooth_kink_deg = std::max(c.max_smooth_kink_deg, *turn);
          if (*turn > opt.fit.g1_angle_deg) {
            ++c.smooth_joints_over_g1;
            c.kink_lines.push_back(slot.piece->head.input_line);
            total.forced_kink_lines.push_back(slot.piece->head.input_line);  // forced by the cut
          }
        }
      }
      prev_tail = slot.piece->tail;
      lines_out += slot.piece->output_lines;
      ready += slot.piece->result.output;
      spare = std::move(slot.piece);
    }
    rethrow();
  }

  void work() {
    while (true) {
      Slot* slot = nullptr;
      {
        std::unique_lock lk(mu);
        cv_work.wait(lk, [&] { return stopping || !todo.empty(); });
        if (stopping || todo.empty()) return;  // stopping: the compressor is destroyed unfinished
        slot = todo.front();
        todo.pop_front();
      }
      std::exception_ptr err;
      try {
        compress_piece(*slot->piece, opt);
      } catch (...) {  // the pipeline does not throw for input; an allocation can
        err = std::current_exception();
      }
      {
        std::lock_guard lk(mu);
        slot->done = true;
        if (err && !failure) failure = err;
      }
      cv_done.notify_all();
    }
  }

  void rethrow() {
    std::lock_guard lk(mu);
    if (failure) std::rethrow_exception(failure);
  }

  std::string name;
  CompressOptions opt;
  DiagnosticSink& sink;
  ModalInterpreter reader;
  const LexRules rules;  // how the dialect's lines are lexed, each piece's program's
  std::shared_ptr<const JumpTargets> jumps;      // the blocks the program's jumps read so far enter
  PassedNumbers passed;                          // block numbers read as no jump's target
  bool jumps_ahead = false;                      // the jumps were read before the program was pushed
  static constexpr size_t kAfterEndBytes = size_t(8) << 20;
  std::string after_end;                         // the text after the program's first end, read ahead
  bool after_end_found = false, after_end_whole = true;
  std::string pending;          // bytes after the last whole line
  std::unique_ptr<Piece> cur;   // the piece being read
  std::unique_ptr<Piece> spare; // the last piece released, whose buffers the next one reads into
  uint32_t line = 0;
  size_t pieces = 0, bytes_read = 0, forced = 0, lines_out = 0, limit = 1, pool_size = 0;
  size_t gather_bytes = kPieceBytes;  ///< piece_bytes() of the piece being read
  bool centre_mode_set = false;
  bool failed = false;
  bool finished = false;
  std::optional<OutputHabits> habits;
  EmitStart next_emit;
  PieceEnd prev_tail;           // the path's end in the last piece released
  CompressResult total;
  std::string ready;            // output released and not yet taken

  std::mutex mu;
  std::condition_variable cv_work, cv_done;
  std::deque<Slot> flight;      // pieces in program order, from the oldest not released
  std::deque<Slot*> todo;       // ... not yet taken by a worker
  std::exception_ptr failure;
  bool stopping = false;
  std::vector<PooledThread> workers;
  std::optional<BlockRateMeter> meter_in, meter_out;  ///< with opt.block_rate
};

Compressor::Compressor(std::string name, const CompressOptions& opt, DiagnosticSink& sink) {
  check_options(opt.fit);
  if (opt.threads > kMaxThreads)
    throw Error(kExitInput, fmt::format("the thread count must be from 0 to {}, got {}", kMaxThreads, opt.threads));
  if (opt.arc_format == ArcFormat::Radius && !opt.dialect.radius_word)
    throw Error(kExitInput, opt.dialect.name + " does not read R-form arcs; use I/J/K");
  if (opt.band == CompressOptions::Band::Executed && !opt.dialect.executed.moves_on_chords())
    throw Error(kExitInput, fmt::format("the executed band: dialect {} names no arc segmentation ([arcs.executed] "
                                        "rule); its controller moves on the programmed circles",
                                        opt.dialect.name));
  if (opt.fit.band_side != BandSide::Both && opt.executed_rule().moves_on_chords())
    throw Error(kExitInput, fmt::format("--band-side holds the band on the programmed path, and {}'s firmware moves "
                                        "along chords of each arc, which cut inside it: add --band program to hold "
                                        "the side on the programmed arcs",
                                        opt.dialect.name));
  sink.set_strict(opt.strict);
  impl_ = std::make_unique<Impl>(std::move(name), opt, sink);
}
Compressor::~Compressor() = default;

/// Runs `f` on the engine; once one call has failed, that failure is every later call's:
/// what was pushed before it may be lost, so nothing after it may pass for whole.
template <class F>
auto Compressor::guarded(F&& f) -> decltype(f()) {
  if (broken_) std::rethrow_exception(broken_);
  try {
    return f();
  } catch (...) {
    broken_ = std::current_exception();
    throw;
  }
}

void Compressor::push(std::string_view bytes) { guarded([&] { impl_->push(bytes); }); }
void Compressor::read_jumps(std::string_view lines, uint32_t first_line) {
  guarded([&] { impl_->read_jumps(lines, first_line, true); });
}
bool Compressor::has_jumps() const { return impl_->jumps && impl_->jumps->any(); }
void Compressor::read_loops(std::string_view program) { guarded([&] { impl_->read_loops(program); }); }
size_t Compressor::take(std::string& out) { return guarded([&] { return impl_->take(out); }); }
void Compressor::finish() { guarded([&] { impl_->finish(); }); }
const CompressResult& Compressor::result() const { return impl_->total; }
size_t Compressor::bytes_read() const { return impl_->bytes_read; }
size_t Compressor::forced_cuts() const { return impl_->forced; }
size_t Compressor::pieces() const { return impl_->pieces; }

}  // namespace arcpress
