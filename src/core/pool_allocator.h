#pragma once
// The allocator of the Context's geometry pools.
//
// A canopy's pools run to hundreds of megabytes, written once and read many times. Blocks of
// 4 MiB and more are aligned to 2 MiB and offered to the kernel for transparent huge pages
// (where the system has them, in "madvise" mode or "always"), which makes first touching
// them several times cheaper than in 4 KiB pages. With `Uninitialised`, growing a vector
// leaves new elements unset (the pools' writers fill every element they add), so a pool is
// written once instead of zeroed first.

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace plantarch::core {

inline constexpr std::size_t kHugePage = std::size_t(2) << 20;
inline constexpr std::size_t kHugeBlock = std::size_t(4) << 20;

inline void* allocatePool(std::size_t bytes) {
    if (bytes < kHugeBlock) {
        if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return p;
        throw std::bad_alloc();
    }
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: no huge pages is no error
#endif
    return p;
}

template <class T, bool Uninitialised = false>
struct PoolAllocator {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = PoolAllocator<U, Uninitialised>;
    };

    PoolAllocator() noexcept = default;
    template <class U>
    PoolAllocator(const PoolAllocator<U, Uninitialised>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        return static_cast<T*>(allocatePool(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t) noexcept { std::free(p); }

    // Value-initialisation (vector::resize(n)) left undone for trivial types when asked.
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        if constexpr (Uninitialised && std::is_trivially_default_constructible_v<U>)
            ::new (static_cast<void*>(p)) U;
        else
            ::new (static_cast<void*>(p)) U();
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <class U>
    bool operator==(const PoolAllocator<U, Uninitialised>&) const noexcept {
        return true;
    }
};

}  // namespace plantarch::core
