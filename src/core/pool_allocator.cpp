#include "core/pool_allocator.h"

#include <array>
#include <bit>
#include <cstdlib>
#include <mutex>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace plantarch::core {

namespace {

// Freed blocks by size class (class k holds blocks of kRecycledBlock << k bytes), kept up to
// kKeptBytes in all: enough for the pools of a large plant or a small canopy, little beside
// the memory a canopy's pools take.
class Recycler {
public:
    static constexpr std::size_t kKeptBytes = std::size_t(256) << 20;
    static constexpr int kClasses = 40;

    void* take(int sizeClass) {
        std::lock_guard<std::mutex> lock(mutex_);
        std::vector<void*>& list = free_[std::size_t(sizeClass)];
        if (list.empty()) return nullptr;
        void* p = list.back();
        list.pop_back();
        kept_ -= blockBytes(sizeClass);
        return p;
    }
    bool keep(void* p, int sizeClass) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (kept_ + blockBytes(sizeClass) > kKeptBytes) return false;
        free_[std::size_t(sizeClass)].push_back(p);
        kept_ += blockBytes(sizeClass);
        return true;
    }
    void release() {
        std::lock_guard<std::mutex> lock(mutex_);
        for (std::vector<void*>& list : free_) {
            for (void* p : list) std::free(p);
            list.clear();
        }
        kept_ = 0;
    }
    std::size_t kept() {
        std::lock_guard<std::mutex> lock(mutex_);
        return kept_;
    }
    static std::size_t blockBytes(int sizeClass) { return kRecycledBlock << sizeClass; }

private:
    std::mutex mutex_;
    std::array<std::vector<void*>, kClasses> free_;
    std::size_t kept_ = 0;
};

Recycler& recycler() {
    // Never destroyed: containers freed during static destruction may still return blocks.
    static Recycler* r = new Recycler;
    return *r;
}

// The size class of a request of `bytes` >= kRecycledBlock.
int sizeClass(std::size_t bytes) {
    return std::bit_width((bytes - 1) / kRecycledBlock);
}

void* fresh(std::size_t bytes) {
    if (bytes < kHugeBlock) return std::malloc(bytes);
    void* p = std::aligned_alloc(kHugePage, bytes);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (p) madvise(p, bytes, MADV_HUGEPAGE);  // advice only: no huge pages is no error
#endif
    return p;
}

}  // namespace

void* allocatePool(std::size_t bytes) {
    if (bytes < kRecycledBlock) {
        if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return p;
        throw std::bad_alloc();
    }
    const int k = sizeClass(bytes);
    if (k >= Recycler::kClasses) throw std::bad_alloc();
    if (void* p = recycler().take(k)) return p;
    if (void* p = fresh(Recycler::blockBytes(k))) return p;
    throw std::bad_alloc();
}

void freePool(void* p, std::size_t bytes) noexcept {
    if (!p) return;
    if (bytes >= kRecycledBlock && recycler().keep(p, sizeClass(bytes))) return;
    std::free(p);
}

void releaseRecycledPools() noexcept {
    recycler().release();
}

std::size_t recycledPoolBytes() noexcept {
    return recycler().kept();
}

}  // namespace plantarch::core
