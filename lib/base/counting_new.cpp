// The counting allocator: every replaceable operator new and delete of the process, through malloc, with
// each block counted at the size malloc gave it (malloc_usable_size, glibc's; AddressSanitizer's in the
// sanitizer builds), so that a block is counted out exactly as it was counted in. Under a MemoryCeiling
// (dqskin/memory_ceiling.hpp) an allocation that would pass it throws std::bad_alloc, or returns null for
// the nothrow forms, before malloc is called; except while an exception unwinds the stack (below).
//
// Linked into the dqskin command line and its tests, not into the library: replacing operator new is the
// program's choice (C++20 [replacement.functions]), and an application linking dqskin keeps its own.
#include "dqskin/memory_ceiling.hpp"

#include <malloc.h>

#include <cstdlib>
#include <exception>
#include <new>

namespace {

using dqskin::memory_detail::release;
using dqskin::memory_detail::reserve;

// Counts and allocates `size` bytes aligned to `alignment` (0: malloc's own); null when the ceiling
// (unless `past_ceiling`) or malloc refuses. The reservation is made first, so that two threads cannot
// both pass the ceiling.
void* counted_alloc(std::size_t size, std::size_t alignment, bool past_ceiling = false) noexcept {
  if (size == 0) size = 1;  // operator new(0) returns a distinct pointer
  if (!reserve(size, past_ceiling)) return nullptr;
  void* p = nullptr;
  if (alignment == 0) {
    p = std::malloc(size);
  } else if (::posix_memalign(&p, alignment, size) != 0) {
    p = nullptr;
  }
  if (!p) {
    release(int64_t(size));
    return nullptr;
  }
  release(int64_t(size) - int64_t(::malloc_usable_size(p)));  // count what malloc rounded it to
  return p;
}

void counted_free(void* p) noexcept {
  if (!p) return;
  release(int64_t(::malloc_usable_size(p)));
  std::free(p);
}

// operator new's contract: retry through the new-handler while there is one, else throw.
//
// While an exception unwinds the stack, the ceiling is not applied: what runs then is destructors and
// cleanup, which free the failed work's memory, and a throw from a destructor ends the process
// (std::terminate). Some allocate as they free: nlohmann::json's destructor reserves a stack as large as
// the array it destroys, to free deep documents without recursion; a report's document destroyed after
// a refusal at the ceiling aborted the process where it should have printed one line.
void* counted_new(std::size_t size, std::size_t alignment) {
  for (;;) {
    if (void* p = counted_alloc(size, alignment)) return p;
    if (std::uncaught_exceptions() > 0)
      if (void* p = counted_alloc(size, alignment, /*past_ceiling=*/true)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

[[maybe_unused]] const bool g_marked = (dqskin::memory_detail::set_counted(), true);

}  // namespace

void* operator new(std::size_t size) { return counted_new(size, 0); }
void* operator new[](std::size_t size) { return counted_new(size, 0); }
void* operator new(std::size_t size, std::align_val_t a) { return counted_new(size, std::size_t(a)); }
void* operator new[](std::size_t size, std::align_val_t a) { return counted_new(size, std::size_t(a)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted_alloc(size, 0); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted_alloc(size, 0); }
void* operator new(std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_alloc(size, std::size_t(a));
}
void* operator new[](std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_alloc(size, std::size_t(a));
}

void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { counted_free(p); }
