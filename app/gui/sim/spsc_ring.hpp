// A lock-free single-producer / single-consumer ring buffer (after rigtorp/SPSCQueue).
//
// One thread pushes, one other thread pops; neither ever blocks or allocates. The capacity is fixed at
// construction and must be a power of two (the slot index is `counter & mask`). `head_` (one past the
// last published slot) and `tail_` (next slot to read) are monotonically increasing 64-bit counters that
// never wrap in practice, so "full" is `head - tail == capacity` and every slot is usable. Each side keeps
// a private cached copy of the other side's counter and re-reads the shared atomic only when the cache
// says full/empty, which keeps the cache-line traffic to about one transfer per batch. The producer may
// also stage items privately and show them with one store (try_stage + publish), the way the simulation
// thread hands over a work slice. The producer's and the consumer's lines are separated by alignas(64),
// and the slot array is 64-byte aligned, so the two threads never false-share.
//
// Memory ordering: the producer writes the slot, then publishes it with a release store of head_; the
// consumer's acquire load of head_ makes the slot contents visible before it reads them. Symmetrically
// the consumer releases a slot with a release store of tail_, which the producer acquires before
// overwriting it.
//
// When the ring is full, try_push drops the new item and counts it (dropped()): a real-time producer
// must never wait for a slow reader. A producer that must not lose items asks has_room() first and
// defers its work instead.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>

namespace impactlab::gui {

template <class T>
class SpscRing {
    static_assert(std::is_trivially_copyable_v<T>, "SpscRing holds trivially copyable items");
    static constexpr std::size_t kLine = 64;   // cache line size on every target we build for

public:
    // Any thread, before the ring is shared. Throws std::invalid_argument unless capacity is a power of two >= 2.
    explicit SpscRing(std::size_t capacity)
        : capacity_(checked(capacity)), mask_(capacity - 1), slots_(allocate(capacity)) {}
    SpscRing(const SpscRing&) = delete;
    SpscRing& operator=(const SpscRing&) = delete;

    // Any thread.
    std::size_t capacity() const noexcept { return capacity_; }

    // Producer thread only. Copies `item` in and publishes it; returns false (and counts a drop) if the
    // ring is full.
    bool try_push(const T& item) noexcept {
        if (!try_stage(item)) return false;
        publish();
        return true;
    }

    // Producer thread only. Like try_push but does not count a drop when full (for callers that retry).
    bool try_push_no_drop(const T& item) noexcept {
        if (!write(item)) return false;
        publish();
        return true;
    }

    // Producer thread only. Copies `item` into the next slot without showing it to the consumer yet;
    // returns false (and counts a drop) if the ring is full. publish() shows every staged item at once.
    // Why: one release store per batch instead of per item keeps the consumer's polling of head_ from
    // pulling that line away from the producer on every push (about 3x the cross-core rate on our VM).
    bool try_stage(const T& item) noexcept {
        if (write(item)) return true;
        dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
        return false;
    }

    // Producer thread only. Like try_stage but a refusal is not a drop (the caller retries).
    bool try_stage_no_drop(const T& item) noexcept { return write(item); }

    // Producer thread only. Makes every staged item visible to the consumer (release).
    void publish() noexcept {
        if (staged_ == published_) return;
        published_ = staged_;
        head_.store(staged_, std::memory_order_release);
    }

    // Producer thread only. Items staged but not yet published.
    std::size_t unpublished() const noexcept { return static_cast<std::size_t>(staged_ - published_); }

    // Producer thread only. Whether n more items would fit now. Reads the consumer's counter only when its
    // cached copy says no, so a producer asking once per batch costs nothing while the reader keeps up.
    bool has_room(std::size_t n) noexcept {
        if (capacity_ - (staged_ - tail_cache_) >= n) return true;
        tail_cache_ = tail_.load(std::memory_order_acquire);
        return capacity_ - (staged_ - tail_cache_) >= n;
    }

    // Consumer thread only. Moves the oldest item into `out`; returns false if the ring is empty.
    bool try_pop(T& out) noexcept {
        const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
        if (tail == head_cache_) {
            head_cache_ = head_.load(std::memory_order_acquire);
            if (tail == head_cache_) return false;
        }
        out = slots_[tail & mask_];
        tail_.store(tail + 1, std::memory_order_release);
        return true;
    }

    // Consumer thread only. Hands up to `max_items` of the oldest items, in order, to `fn(const T&)` and
    // releases them all with a single store; returns how many were consumed. The cheap way to drain.
    template <class Fn>
    std::size_t drain(Fn&& fn, std::size_t max_items = static_cast<std::size_t>(-1)) {
        const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
        head_cache_ = head_.load(std::memory_order_acquire);
        std::uint64_t n = head_cache_ - tail;
        if (n > max_items) n = max_items;
        for (std::uint64_t i = 0; i < n; ++i) fn(static_cast<const T&>(slots_[(tail + i) & mask_]));
        if (n) tail_.store(tail + n, std::memory_order_release);
        return static_cast<std::size_t>(n);
    }

    // Any thread; exact only on the consumer side (a lower bound of the free space seen by the producer).
    std::size_t size() const noexcept {
        const std::uint64_t tail = tail_.load(std::memory_order_acquire);
        const std::uint64_t head = head_.load(std::memory_order_acquire);
        return head >= tail ? static_cast<std::size_t>(head - tail) : 0;
    }
    // Any thread (consumer side exact).
    bool empty() const noexcept { return size() == 0; }
    // Any thread. Items refused by try_push because the ring was full, since construction.
    std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
    // Any thread. Items ever published.
    std::uint64_t pushed() const noexcept { return head_.load(std::memory_order_relaxed); }

private:
    struct Deleter {
        void operator()(T* p) const noexcept { ::operator delete[](p, std::align_val_t{kLine}); }
    };
    static std::size_t checked(std::size_t n) {
        if (n < 2 || (n & (n - 1)) != 0) throw std::invalid_argument("SpscRing capacity must be a power of two >= 2");
        return n;
    }
    static T* allocate(std::size_t n) {
        void* raw = ::operator new[](n * sizeof(T), std::align_val_t{kLine});
        return static_cast<T*>(raw);   // trivially copyable T: storage is usable as is
    }

    // Producer thread only: the slot write behind try_push/try_stage; false when full.
    bool write(const T& item) noexcept {
        if (staged_ - tail_cache_ >= capacity_) {
            tail_cache_ = tail_.load(std::memory_order_acquire);
            if (staged_ - tail_cache_ >= capacity_) return false;
        }
        slots_[staged_ & mask_] = item;
        ++staged_;
        return true;
    }

    const std::size_t capacity_;
    const std::size_t mask_;
    const std::unique_ptr<T[], Deleter> slots_;

    // Producer's line: its published counter, private copies of it and of the staged counter (>= head_;
    // the producer never reads head_ back, which the consumer's polling would make a cross-core miss),
    // its cache of the consumer's counter, the drop count.
    alignas(kLine) std::atomic<std::uint64_t> head_{0};
    std::uint64_t published_ = 0;
    std::uint64_t staged_ = 0;
    std::uint64_t tail_cache_ = 0;
    std::atomic<std::uint64_t> dropped_{0};
    // Consumer's line.
    alignas(kLine) std::atomic<std::uint64_t> tail_{0};
    std::uint64_t head_cache_ = 0;
    // alignas(64) on the members makes sizeof(SpscRing) a multiple of 64: whatever follows the object
    // starts on a fresh line.
};

}  // namespace impactlab::gui
