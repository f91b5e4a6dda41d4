#pragma once
/// @file
/// Test support: counts the heap allocations of a test executable. Include it in exactly one
/// translation unit of the executable (it defines malloc and friends, and operator new/delete).
/// Eigen's dynamic storage comes from std::malloc, not operator new, so the count is taken at malloc
/// itself: glibc lets the executable interpose malloc and friends and forwards to its __libc_*
/// entry points. AddressSanitizer replaces malloc too: build such tests only without the
/// sanitizers (tests/element/CMakeLists.txt).

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> gAllocations{0};     // calls of malloc, calloc, realloc, aligned_alloc, posix_memalign
std::atomic<long> gAllocatedBytes{0};  // the bytes they asked for
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t size) {
    ++gAllocations;
    gAllocatedBytes += static_cast<long>(size);
    return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
    ++gAllocations;
    gAllocatedBytes += static_cast<long>(n * size);
    return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
    ++gAllocations;
    gAllocatedBytes += static_cast<long>(size);
    return __libc_realloc(p, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
    ++gAllocations;
    gAllocatedBytes += static_cast<long>(size);
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
    ++gAllocations;
    gAllocatedBytes += static_cast<long>(size);
    *out = __libc_memalign(alignment, size);
    return *out ? 0 : 12;  // ENOMEM
}
void free(void* p) { __libc_free(p); }
}

void* operator new(std::size_t size) {
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
