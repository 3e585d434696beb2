// The UI thread's own copies of what the simulation published: a trajectory ring (overwrites the oldest)
// and the Poincare points of the current epoch, with CSV export. UI thread only; GL-free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/sim_messages.hpp"

namespace impactlab::gui {

// A fixed-capacity ring that overwrites its oldest element; [0] is the oldest, [size()-1] the newest.
// The capacity is a power of two (indexing is a mask, not a division: the plots walk 100k points a frame).
// Every element also has a sequence number that never repeats (seq_of(i)), so a consumer that draws
// incrementally can tell what is new since its last look; clear() starts a new generation.
template <class T>
class History {
public:
    // Throws std::invalid_argument unless capacity is a power of two >= 1.
    explicit History(std::size_t capacity) : buf_(checked(capacity)), mask_(capacity - 1) {}
    void push(const T& v) {
        buf_[(start_ + size_) & mask_] = v;
        if (size_ < buf_.size()) ++size_;
        else start_ = (start_ + 1) & mask_;
        ++pushed_;
    }
    void clear() {
        start_ = size_ = 0;
        ++generation_;
    }
    // Forgets the `count` oldest elements (all if count >= size()); sequence numbers stay as they were.
    void drop_oldest(std::size_t count) {
        if (count > size_) count = size_;
        start_ = (start_ + count) & mask_;
        size_ -= count;
    }
    // Forgets the `count` newest elements (all if count >= size()): a run continued from a replayed instant
    // drops its old future. A new generation, so that what draws incrementally starts over.
    void drop_newest(std::size_t count) {
        if (count > size_) count = size_;
        size_ -= count;
        pushed_ -= count;
        ++generation_;
    }
    // Replay: the history reads as it was when element end - 1 was the newest (size() == end, the same
    // indices and sequence numbers) until reveal(). Nothing may be pushed or cleared in between.
    void rewind_to(std::size_t end) {
        reveal();
        hidden_ = end < size_ ? size_ - end : 0;
        size_ -= hidden_;
        pushed_ -= hidden_;
    }
    void reveal() {
        size_ += hidden_;
        pushed_ += hidden_;
        hidden_ = 0;
    }
    std::size_t size() const { return size_; }
    std::size_t capacity() const { return buf_.size(); }
    bool empty() const { return size_ == 0; }
    const T& operator[](std::size_t i) const { return buf_[(start_ + i) & mask_]; }
    const T& back() const { return (*this)[size_ - 1]; }
    // Sequence number of element i (pushes since construction, counting cleared ones).
    std::uint64_t seq_of(std::size_t i) const { return pushed_ - size_ + i; }
    // Bumped by clear().
    std::uint64_t generation() const { return generation_; }
    // Index of the first element with key(e) >= value, for a key nondecreasing along the ring.
    template <class Key>
    std::size_t lower_bound(double value, Key&& key) const {
        std::size_t lo = 0, hi = size_;
        while (lo < hi) {
            const std::size_t mid = (lo + hi) / 2;
            if (key((*this)[mid]) < value) lo = mid + 1;
            else hi = mid;
        }
        return lo;
    }

private:
    static std::size_t checked(std::size_t n) {
        if (n == 0 || (n & (n - 1)) != 0) throw std::invalid_argument("History capacity must be a power of two");
        return n;
    }
    std::vector<T> buf_;
    std::size_t mask_;
    std::size_t start_ = 0, size_ = 0;
    std::size_t hidden_ = 0;   // rewind_to(): newest elements not shown until reveal()
    std::uint64_t pushed_ = 0, generation_ = 0;
};

// The minimum and maximum of key(element) over a window [first, size()) of a History that slides forward,
// kept with two monotonic deques: amortized O(1) per new element instead of a pass over the whole window
// every frame (100k records of 64 bytes are 6.4 MB of memory traffic). Rebuilt when the history is
// cleared or the window grows backwards. UI thread only.
class WindowExtent {
public:
    struct Result {
        double lo, hi;
        bool empty;
    };
    template <class T, class Key>
    Result update(const History<T>& h, std::size_t first, Key&& key) {
        const std::uint64_t end_seq = h.seq_of(h.size());   // one past the newest
        const std::uint64_t first_seq = h.seq_of(first);
        if (h.generation() != generation_ || first_seq < first_seq_ || next_seq_ > end_seq ||
            next_seq_ < first_seq) {
            lo_.clear();
            hi_.clear();
            generation_ = h.generation();
            next_seq_ = first_seq;
        }
        first_seq_ = first_seq;
        const std::uint64_t seq0 = h.seq_of(0);
        for (std::uint64_t q = next_seq_; q < end_seq; ++q) {
            const double v = key(h[static_cast<std::size_t>(q - seq0)]);
            while (!lo_.empty() && lo_.back().second >= v) lo_.pop_back();
            lo_.emplace_back(q, v);
            while (!hi_.empty() && hi_.back().second <= v) hi_.pop_back();
            hi_.emplace_back(q, v);
        }
        next_seq_ = end_seq;
        while (!lo_.empty() && lo_.front().first < first_seq) lo_.pop_front();
        while (!hi_.empty() && hi_.front().first < first_seq) hi_.pop_front();
        if (lo_.empty()) return {0, 0, true};
        return {lo_.front().second, hi_.front().second, false};
    }

private:
    std::deque<std::pair<std::uint64_t, double>> lo_, hi_;
    std::uint64_t generation_ = ~std::uint64_t{0};
    std::uint64_t first_seq_ = 0, next_seq_ = 0;
};

// Writes t,x,v,phi,omega,regime,bumper_force,energy,epoch; returns false if the file cannot be written.
bool write_trajectory_csv(const std::string& path, const History<SimMsg>& h, const std::string& model);
// Writes n,t,x,v,omega,regime.
bool write_sections_csv(const std::string& path, const History<SimMsg>& s, const std::string& model);

}  // namespace impactlab::gui
