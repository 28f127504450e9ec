#pragma once
// The allocator of the Context's geometry pools.
//
// A canopy's pools run to hundreds of megabytes, written once and read many times. Blocks of
// 4 MiB and more are aligned to 2 MiB and offered to the kernel for transparent huge pages
// (where the system has them, in "madvise" mode or "always"), which makes first touching
// them several times cheaper than in 4 KiB pages. Freed blocks are kept, up to a bound, for
// the next Context: first touching a fresh page is the largest single cost of building a
// small plant. With `Uninitialised`, growing a vector leaves new elements unset (the pools'
// writers fill every element they add), so a pool is written once instead of zeroed first.

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace plantarch::core {

inline constexpr std::size_t kHugePage = std::size_t(2) << 20;
inline constexpr std::size_t kHugeBlock = std::size_t(4) << 20;

/// Pool blocks of at least this many bytes are rounded up to a power of two and kept for
/// reuse when freed (pool_allocator.cpp): building one plant after another, each into a new
/// Context, then finds its pools' pages already mapped instead of faulting in fresh ones.
inline constexpr std::size_t kRecycledBlock = std::size_t(64) << 10;

/// A block of at least `bytes` (a power of two from kRecycledBlock up; 4 MiB and more aligned
/// to 2 MiB and offered for huge pages). Throws std::bad_alloc.
void* allocatePool(std::size_t bytes);
/// Returns a block from allocatePool(bytes), which may keep it for the next request of its
/// size.
void freePool(void* p, std::size_t bytes) noexcept;
/// Frees every kept block (a test's or a memory-tight caller's way to give pages back).
void releaseRecycledPools() noexcept;
/// Bytes in blocks kept for reuse.
std::size_t recycledPoolBytes() noexcept;

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
    void deallocate(T* p, std::size_t n) noexcept { freePool(p, n * sizeof(T)); }

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
