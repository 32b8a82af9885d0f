// SPDX-License-Identifier: GPL-3.0-or-later
// The program's allocation function, replaced (as C++ allows an executable to) so that its
// memory lies on huge pages.
//
// A whole program read at once (`arcpress diff` reads two) fills hundreds of MB of fresh
// memory that the kernel maps a 4 KiB page at a time, and the diff's spatial searches then
// walk it beyond the TLB's reach. Where the system leaves huge pages to the program's asking
// (transparent huge pages in `madvise` mode, Debian's default), asking for them maps memory
// 2 MiB at a time: the heap as it grows (malloc's main arena, where main() keeps allocations
// of up to 64 MiB), and any allocation large enough to hold a whole huge page of its own.
// `arcpress diff` of the bunny and its compressed output runs in less than half the time
// (docs/benchmarks.md). Where the system decides otherwise the requests change nothing.
#include <sys/mman.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::uintptr_t kHugePageBytes = std::uintptr_t(2) << 20;
/// Allocations from this size on look whether the heap grew (it grows by such steps).
constexpr std::size_t kLookAtHeapBytes = std::size_t(64) << 10;

std::uintptr_t huge_page_below(std::uintptr_t a) { return a & ~(kHugePageBytes - 1); }

/// Asks for huge pages over the whole huge pages inside [begin, end): a hint, whose refusal
/// changes nothing.
void advise(std::uintptr_t begin, std::uintptr_t end) {
  begin = huge_page_below(begin + kHugePageBytes - 1);
  end = huge_page_below(end);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

/// The heap's end up to which huge pages were asked for (0: not yet looked at).
std::atomic<std::uintptr_t> heap_advised{0};

/// Asks for huge pages over what the heap grew by since the last look. (The break is asked
/// of the kernel: sbrk(0) reads malloc's copy, which another thread may be writing.)
void advise_heap_growth() {
  const std::uintptr_t end = static_cast<std::uintptr_t>(::syscall(SYS_brk, 0));
  std::uintptr_t from = heap_advised.load(std::memory_order_relaxed);
  if (from == 0) {  // the heap so far holds the small start-up allocations: left as it is
    heap_advised.compare_exchange_strong(from, huge_page_below(end));
    return;
  }
  const std::uintptr_t to = huge_page_below(end);
  if (to > from && heap_advised.compare_exchange_strong(from, to)) advise(from, to);
}

}  // namespace

// The other forms (arrays, nothrow, sized delete) call these in libstdc++; the aligned
// forms keep the library's own pair.
void* operator new(std::size_t bytes) {
  void* p = std::malloc(bytes > 0 ? bytes : 1);
  if (p == nullptr) throw std::bad_alloc();
  if (bytes >= kLookAtHeapBytes) {
    advise_heap_growth();
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    if (bytes >= kHugePageBytes) advise(at, at + bytes);  // (one malloc mapped on its own)
  }
  return p;
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
