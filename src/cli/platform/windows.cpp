// SPDX-License-Identifier: GPL-3.0-or-later
// The command line's platform layer on Windows: files (file_io.hpp) through the wide API, so
// that paths are UTF-8 throughout, with binary handles and 64-bit sizes; the atomic replace
// by ReplaceFileW, which keeps the replaced file's attributes and security; interrupts by
// SetConsoleCtrlHandler; and the process's arguments, streams and console (console.hpp).
// Windows has no owner and group for a program to keep, nor modes: a replaced file keeps its
// attributes (read-only, hidden, ...) and its access control list instead.
#include <windows.h>
#include <fcntl.h>
#include <io.h>
#include <shellapi.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "arcpress/core/error.hpp"
#include "console.hpp"
#include "file_io.hpp"

namespace arcpress::cli {
namespace {

std::wstring wide(const std::string& utf8) {
  if (utf8.empty()) return {};
  const int n = ::MultiByteToWideChar(CP_UTF8, 0, utf8.data(), int(utf8.size()), nullptr, 0);
  std::wstring out(size_t(n), L'\0');
  ::MultiByteToWideChar(CP_UTF8, 0, utf8.data(), int(utf8.size()), out.data(), n);
  return out;
}

std::string utf8(const wchar_t* w, size_t len) {
  if (len == 0) return {};
  const int n = ::WideCharToMultiByte(CP_UTF8, 0, w, int(len), nullptr, 0, nullptr, nullptr);
  std::string out(size_t(n), '\0');
  ::WideCharToMultiByte(CP_UTF8, 0, w, int(len), out.data(), n, nullptr, nullptr);
  return out;
}

std::string utf8(const std::wstring& w) { return utf8(w.data(), w.size()); }

/// The system's words for error `err` (GetLastError()), without the line end.
std::string error_text(DWORD err) {
  wchar_t* buf = nullptr;
  const DWORD n = ::FormatMessageW(FORMAT_MESSAGE_ALLOCATE_BUFFER | FORMAT_MESSAGE_FROM_SYSTEM |
                                       FORMAT_MESSAGE_IGNORE_INSERTS,
                                   nullptr, err, 0, reinterpret_cast<wchar_t*>(&buf), 0, nullptr);
  std::string text = n > 0 && buf ? utf8(buf, n) : fmt::format("error {}", err);
  if (buf) ::LocalFree(buf);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ' || text.back() == '.'))
    text.pop_back();
  return text;
}

HANDLE as_handle(std::intptr_t h) { return reinterpret_cast<HANDLE>(h); }
std::intptr_t from_handle(HANDLE h) { return reinterpret_cast<std::intptr_t>(h); }
constexpr std::intptr_t kNoHandle = -1;  // INVALID_HANDLE_VALUE

/// The temporary files being written (one per program a batch writes at once), for the
/// console handler, which runs on a thread of its own: it takes the lock, removes them and
/// marks the process interrupted; commit() renames under the same lock and never after an
/// interrupt.
std::mutex g_temporary_lock;
std::set<std::wstring> g_temporaries;
bool g_interrupted = false;
/// Whether standard output has failed: nothing more is written there.
bool g_stdout_failed = false;

/// STATUS_CONTROL_C_EXIT: the exit status of a program Ctrl-C ended.
constexpr UINT kInterruptedExit = 0xC000013A;

BOOL WINAPI on_console_event(DWORD event) {
  if (event != CTRL_C_EVENT && event != CTRL_BREAK_EVENT && event != CTRL_CLOSE_EVENT &&
      event != CTRL_LOGOFF_EVENT && event != CTRL_SHUTDOWN_EVENT)
    return FALSE;
  {
    std::lock_guard<std::mutex> hold(g_temporary_lock);
    g_interrupted = true;
    // Opened with FILE_SHARE_DELETE: the name goes now, the file with the process's handle.
    for (const std::wstring& t : g_temporaries) ::DeleteFileW(t.c_str());
    g_temporaries.clear();
  }
  // Ended as Windows ends a program on Ctrl-C, with STATUS_CONTROL_C_EXIT, whatever the event.
  ::ExitProcess(kInterruptedExit);
}

/// Writes all of `data` to `h`; returns 0 or the error of the failure, and adds the bytes
/// that were written to `done`.
DWORD write_all(HANDLE h, std::string_view data, size_t& done) {
  constexpr size_t kMaxWrite = size_t(1) << 30;
  for (size_t at = 0; at < data.size();) {
    DWORD n = 0;
    if (!::WriteFile(h, data.data() + at, DWORD(std::min(kMaxWrite, data.size() - at)), &n, nullptr))
      return ::GetLastError();
    at += n;
    done += n;
  }
  return 0;
}

/// The device names Windows reserves in every folder (NUL, CON, ...), and \\.\ paths: written
/// as they are, never replaced.
bool is_device(const std::string& path) {
  if (path.rfind("\\\\.\\", 0) == 0) return true;
  const size_t slash = path.find_last_of("\\/:");
  std::string base = path.substr(slash == std::string::npos ? 0 : slash + 1);
  base = base.substr(0, base.find('.'));
  std::transform(base.begin(), base.end(), base.begin(), [](char c) { return char(c >= 'a' && c <= 'z' ? c - 32 : c); });
  for (const char* d : {"NUL", "CON", "PRN", "AUX", "COM1", "COM2", "COM3", "COM4", "LPT1", "LPT2", "LPT3"})
    if (base == d) return true;
  return false;
}

/// The path a handle's file has, symbolic links resolved; empty where that fails.
std::wstring final_path(HANDLE h) {
  std::wstring buf(512, L'\0');
  for (;;) {
    const DWORD n = ::GetFinalPathNameByHandleW(h, buf.data(), DWORD(buf.size()), FILE_NAME_NORMALIZED);
    if (n == 0) return {};
    if (n < buf.size()) {
      buf.resize(n);
      return buf;
    }
    buf.resize(n + 1);
  }
}

/// `path` made absolute (ReplaceFileW wants a folder in both names, as wine does).
std::wstring full_path(const std::wstring& path) {
  const DWORD n = ::GetFullPathNameW(path.c_str(), 0, nullptr, nullptr);
  if (n == 0) return path;
  std::wstring out(n, L'\0');
  const DWORD got = ::GetFullPathNameW(path.c_str(), n, out.data(), nullptr);
  if (got == 0 || got >= n) return path;
  out.resize(got);
  return out;
}

long long file_pointer(HANDLE h) {
  LARGE_INTEGER zero{}, at{};
  return ::SetFilePointerEx(h, zero, &at, FILE_CURRENT) ? at.QuadPart : -1;
}

bool seek(HANDLE h, long long to) {
  LARGE_INTEGER at{};
  at.QuadPart = to;
  return ::SetFilePointerEx(h, at, nullptr, FILE_BEGIN) != 0;
}

}  // namespace

/// OutputFile's steps that need the system's types.
struct OutputFileSystem {
  static void note_start(OutputFile& f);
  static void open_temporary(OutputFile& f, const std::string& target);
};

InputFile::InputFile(const std::string& path) : name_(path == "-" ? "standard input" : "'" + path + "'") {
  if (path == "-") {
    handle_ = from_handle(::GetStdHandle(STD_INPUT_HANDLE));
  } else {
    const std::wstring w = wide(path);
    const DWORD attributes = ::GetFileAttributesW(w.c_str());
    if (attributes != INVALID_FILE_ATTRIBUTES && (attributes & FILE_ATTRIBUTE_DIRECTORY))
      throw Error(kExitIo, fmt::format("cannot read {}: it is a folder", name_));
    HANDLE h = ::CreateFileW(w.c_str(), GENERIC_READ, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                             OPEN_EXISTING, FILE_FLAG_SEQUENTIAL_SCAN, nullptr);
    if (h == INVALID_HANDLE_VALUE)
      throw Error(kExitIo, fmt::format("cannot open {}: {}", name_, error_text(::GetLastError())));
    handle_ = from_handle(h);
    owned_ = true;
  }
  HANDLE h = as_handle(handle_);
  LARGE_INTEGER size{};
  if (h && h != INVALID_HANDLE_VALUE && ::GetFileType(h) == FILE_TYPE_DISK && ::GetFileSizeEx(h, &size)) {
    const long long at = std::max(0LL, file_pointer(h));
    size_ = size_t(size.QuadPart - std::min<long long>(at, size.QuadPart));
    start_ = at;
  }
}

InputFile::~InputFile() {
  if (owned_) ::CloseHandle(as_handle(handle_));
}

size_t InputFile::read(std::string& into, size_t max) {
  max = asked(max);
  const size_t had = into.size();
  into.resize(had + max);
  DWORD n = 0;
  HANDLE h = as_handle(handle_);
  if (!h || h == INVALID_HANDLE_VALUE) {  // no standard input at all: empty
    into.resize(had);
    return 0;
  }
  if (!::ReadFile(h, into.data() + had, DWORD(std::min<size_t>(max, size_t(1) << 30)), &n, nullptr)) {
    const DWORD err = ::GetLastError();
    into.resize(had);
    if (err == ERROR_BROKEN_PIPE || err == ERROR_HANDLE_EOF) return 0;  // the writer is done
    throw Error(kExitIo, fmt::format("cannot read {}: {}", name_, error_text(err)));
  }
  into.resize(had + n);
  taken_ += n;
  return n;
}

std::string InputFile::read_at(size_t offset, size_t n) const {
  if (!size_ || offset >= *size_) return {};
  HANDLE h = as_handle(handle_);
  const size_t len = std::min(n, *size_ - offset);
  std::string out(len, '\0');
  const long long was = file_pointer(h);
  size_t got = 0;
  if (was >= 0 && seek(h, start_ + static_cast<long long>(offset)))
    while (got < len) {
      DWORD k = 0;
      if (!::ReadFile(h, out.data() + got, DWORD(len - got), &k, nullptr) || k == 0) break;
      got += k;
    }
  if (was >= 0) seek(h, was);
  out.resize(got);
  return out;
}

void InputFile::spool() {
  if (size_) return;
  wchar_t folder[MAX_PATH + 1] = {}, path[MAX_PATH + 1] = {};
  const DWORD folder_length = ::GetTempPathW(MAX_PATH + 1, folder);
  HANDLE h = INVALID_HANDLE_VALUE;
  auto fail = [&](DWORD err) {
    if (h != INVALID_HANDLE_VALUE) ::CloseHandle(h);
    return Error(kExitIo, fmt::format("cannot keep {} in a temporary file in '{}' to read it whole: {} (set TMP to "
                                      "another folder, or give --stream)",
                                      name_, utf8(folder, folder_length), error_text(err)));
  };
  if (folder_length == 0 || folder_length > MAX_PATH || !::GetTempFileNameW(folder, L"arc", 0, path))
    throw fail(::GetLastError());
  // (Deleted when closed: nothing is left behind, whatever happens.)
  h = ::CreateFileW(path, GENERIC_READ | GENERIC_WRITE, 0, nullptr, CREATE_ALWAYS,
                    FILE_ATTRIBUTE_TEMPORARY | FILE_FLAG_DELETE_ON_CLOSE, nullptr);
  if (h == INVALID_HANDLE_VALUE) {
    const DWORD err = ::GetLastError();
    ::DeleteFileW(path);
    throw fail(err);
  }
  const size_t total = copy_rest([&](std::string_view data) {
    for (size_t put = 0; put < data.size();) {
      DWORD k = 0;
      if (!::WriteFile(h, data.data() + put, DWORD(data.size() - put), &k, nullptr)) throw fail(::GetLastError());
      put += k;
    }
  });
  if (!seek(h, 0)) throw fail(::GetLastError());
  if (owned_) ::CloseHandle(as_handle(handle_));
  handle_ = from_handle(h);
  owned_ = true;
  size_ = total;
  start_ = 0;
  taken_ = 0;
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path == "-") {
    if (g_stdout_failed) throw Error(kExitIo, "cannot write standard output");
    std::fflush(stdout);  // whatever stdio holds goes first
    handle_ = from_handle(::GetStdHandle(STD_OUTPUT_HANDLE));
    is_stdout_ = true;
    OutputFileSystem::note_start(*this);
    return;
  }
  const std::wstring w = wide(path);
  if (is_device(path)) {
    HANDLE h = ::CreateFileW(w.c_str(), GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_WRITE, nullptr, OPEN_EXISTING,
                             FILE_ATTRIBUTE_NORMAL, nullptr);
    if (h == INVALID_HANDLE_VALUE)
      throw Error(kExitIo, fmt::format("cannot open '{}' for writing: {}", path, error_text(::GetLastError())));
    handle_ = from_handle(h);
    owned_ = true;
    return;
  }
  WIN32_FILE_ATTRIBUTE_DATA info{};
  if (!::GetFileAttributesExW(w.c_str(), GetFileExInfoStandard, &info)) {
    const DWORD err = ::GetLastError();
    if (err != ERROR_FILE_NOT_FOUND) throw Error(kExitIo, fmt::format("cannot write '{}': {}", path, error_text(err)));
    if (!path.empty() && (path.back() == '/' || path.back() == '\\'))
      throw Error(kExitIo, fmt::format("cannot write '{}': no such folder", path));
    OutputFileSystem::open_temporary(*this, path);
    return;
  }
  if (info.dwFileAttributes & FILE_ATTRIBUTE_DIRECTORY)
    throw Error(kExitIo, fmt::format("cannot write '{}': it is a folder", path));
  std::string target = path;
  if (info.dwFileAttributes & FILE_ATTRIBUTE_REPARSE_POINT) {
    // A link is followed to what it names: that is rewritten, and the link stays.
    HANDLE h = ::CreateFileW(w.c_str(), 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                             OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
    if (h == INVALID_HANDLE_VALUE)
      throw Error(kExitIo, fmt::format("cannot write '{}': {} (a link to nothing)", path, error_text(::GetLastError())));
    std::wstring resolved = final_path(h);
    ::CloseHandle(h);
    if (resolved.rfind(L"\\\\?\\", 0) == 0 && resolved.rfind(L"\\\\?\\UNC\\", 0) != 0) resolved.erase(0, 4);
    if (resolved.empty()) throw Error(kExitIo, fmt::format("cannot follow the link '{}'", path));
    target = utf8(resolved);
  }
  OutputFileSystem::open_temporary(*this, target);
}

OutputFile::~OutputFile() {
  if (!done_) discard();
}

/// A disk file behind standard output (`> out.nc`): where it began, so that discard() can
/// cut it back there.
void OutputFileSystem::note_start(OutputFile& f) {
  HANDLE h = as_handle(f.handle_);
  if (!h || h == INVALID_HANDLE_VALUE || ::GetFileType(h) != FILE_TYPE_DISK) return;
  f.start_ = file_pointer(h);
}

/// The temporary file beside `target`, put in its place by commit().
void OutputFileSystem::open_temporary(OutputFile& f, const std::string& target) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0;; ++attempt) {
    const std::string name = fmt::format("{}.arcpress-{:x}{:x}{:x}", target, ::GetCurrentProcessId(),
                                         ::GetTickCount() & 0xffff, counter++);
    const std::wstring w = wide(name);
    std::lock_guard<std::mutex> hold(g_temporary_lock);
    if (g_interrupted) throw Error(kExitIo, "interrupted");
    // Shared for deletion, so that an interrupt can remove it while it is open.
    HANDLE h = ::CreateFileW(w.c_str(), GENERIC_WRITE | DELETE, FILE_SHARE_READ | FILE_SHARE_DELETE, nullptr,
                             CREATE_NEW, FILE_ATTRIBUTE_NORMAL, nullptr);
    if (h == INVALID_HANDLE_VALUE) {
      const DWORD err = ::GetLastError();
      if ((err == ERROR_FILE_EXISTS || err == ERROR_ALREADY_EXISTS) && attempt < 100) continue;
      throw Error(kExitIo, fmt::format("cannot create a temporary file beside '{}': {}", target, error_text(err)));
    }
    g_temporaries.insert(w);
    f.handle_ = from_handle(h);
    f.owned_ = true;
    f.temporary_ = name;
    f.target_ = target;
    return;
  }
}

void OutputFile::fail(const std::string& what, int err) {
  discard();
  if (is_stdout_) g_stdout_failed = true;
  throw Error(kExitIo, fmt::format("{} {}: {}", what, is_stdout_ ? std::string("standard output") : "'" + path_ + "'",
                                   error_text(DWORD(err))));
}

void OutputFile::write(std::string_view data) {
  if (done_) throw Error(kExitIo, fmt::format("cannot write '{}': already closed", path_));
  const DWORD err = write_all(as_handle(handle_), data, written_);
  if (err == ERROR_BROKEN_PIPE || err == ERROR_NO_DATA || err == ERROR_PIPE_NOT_CONNECTED) {
    // The reader went away: said as such, with how much it took.
    const size_t taken = written_;
    discard();
    if (is_stdout_) g_stdout_failed = true;
    throw Error(kExitIo, fmt::format("{} closed after {} bytes",
                                     is_stdout_ ? std::string("standard output") : "'" + path_ + "'", taken));
  }
  if (err != 0) fail("cannot write", int(err));
}

void OutputFile::commit() {
  if (done_) return;
  if (!temporary_.empty()) {
    HANDLE h = as_handle(handle_);
    if (!::FlushFileBuffers(h)) fail("cannot finish writing", int(::GetLastError()));
    handle_ = kNoHandle;
    const bool closed = ::CloseHandle(h) != 0;
    const DWORD close_err = ::GetLastError();
    std::lock_guard<std::mutex> hold(g_temporary_lock);
    const std::wstring temporary = full_path(wide(temporary_)), target = full_path(wide(target_));
    done_ = true;
    g_temporaries.erase(wide(temporary_));
    if (!closed || g_interrupted) {
      ::DeleteFileW(temporary.c_str());
      throw Error(kExitIo, g_interrupted ? std::string("interrupted")
                                         : fmt::format("cannot finish writing '{}': {}", path_, error_text(close_err)));
    }
    // An existing file is replaced keeping its attributes and security; a new one is moved
    // into place. Either is one step on the same volume.
    const bool exists = ::GetFileAttributesW(target.c_str()) != INVALID_FILE_ATTRIBUTES;
    const bool moved = exists ? ::ReplaceFileW(target.c_str(), temporary.c_str(), nullptr,
                                               REPLACEFILE_IGNORE_MERGE_ERRORS | REPLACEFILE_IGNORE_ACL_ERRORS, nullptr,
                                               nullptr) != 0
                              : ::MoveFileExW(temporary.c_str(), target.c_str(), MOVEFILE_WRITE_THROUGH) != 0;
    if (!moved) {
      const DWORD err = ::GetLastError();
      ::DeleteFileW(temporary.c_str());
      // Windows replaces no read-only file (POSIX systems do, keeping its mode): said so.
      const DWORD attributes = ::GetFileAttributesW(target.c_str());
      if (attributes != INVALID_FILE_ATTRIBUTES && (attributes & FILE_ATTRIBUTE_READONLY))
        throw Error(kExitIo, fmt::format("cannot replace '{}': it is read-only", path_));
      throw Error(kExitIo, fmt::format("cannot rename the output into '{}': {}", path_, error_text(err)));
    }
  } else if (owned_) {
    HANDLE h = as_handle(handle_);
    handle_ = kNoHandle;
    done_ = true;
    if (!::CloseHandle(h))
      throw Error(kExitIo, fmt::format("cannot finish writing '{}': {}", path_, error_text(::GetLastError())));
  }
  done_ = true;
}

size_t OutputFile::discard() {
  if (done_) return 0;
  done_ = true;
  size_t left = 0;
  HANDLE h = as_handle(handle_);
  if (!temporary_.empty()) {
    std::lock_guard<std::mutex> hold(g_temporary_lock);
    ::CloseHandle(h);
    ::DeleteFileW(wide(temporary_).c_str());
    g_temporaries.erase(wide(temporary_));
  } else {
    // A file the shell opened is cut back to where it began; a pipe or console keeps what
    // it has been given.
    if (start_ < 0 || !seek(h, start_) || !::SetEndOfFile(h)) left = written_;
    if (owned_) ::CloseHandle(h);
  }
  handle_ = kNoHandle;
  return left;
}

void remove_temporary_files_on_signals() { ::SetConsoleCtrlHandler(on_console_event, TRUE); }

std::vector<std::string> start_process(int, char**) {
  // The command line as typed, in UTF-8: the narrow argv holds it in the code page, where
  // a name such as Ø-pièce 部品.nc cannot be said.
  int count = 0;
  wchar_t** wargv = ::CommandLineToArgvW(::GetCommandLineW(), &count);
  std::vector<std::string> args;
  for (int k = 0; k < count && wargv; ++k) args.push_back(utf8(wargv[k], std::wcslen(wargv[k])));
  if (wargv) ::LocalFree(wargv);
  // Programs in and out byte for byte: no CR added before LF, none dropped, no Ctrl-Z end.
  ::_setmode(::_fileno(stdin), _O_BINARY);
  ::_setmode(::_fileno(stdout), _O_BINARY);
  // Messages name files in UTF-8.
  ::SetConsoleOutputCP(CP_UTF8);
  return args;
}

bool is_terminal(int stream) { return ::_isatty(stream) != 0; }

}  // namespace arcpress::cli
