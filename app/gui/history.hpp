// The UI thread's own copies of what the simulation published: a trajectory ring (overwrites the oldest)
// and the Poincare points of the current epoch, with CSV export. UI thread only; GL-free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sim_messages.hpp"

namespace impactlab::gui {

// A fixed-capacity ring that overwrites its oldest element; [0] is the oldest, [size()-1] the newest.
template <class T>
class History {
public:
    explicit History(std::size_t capacity) : buf_(capacity) {}
    void push(const T& v) {
        buf_[(start_ + size_) % buf_.size()] = v;
        if (size_ < buf_.size()) ++size_;
        else start_ = (start_ + 1) % buf_.size();
    }
    void clear() { start_ = size_ = 0; }
    std::size_t size() const { return size_; }
    std::size_t capacity() const { return buf_.size(); }
    bool empty() const { return size_ == 0; }
    const T& operator[](std::size_t i) const { return buf_[(start_ + i) % buf_.size()]; }
    const T& back() const { return (*this)[size_ - 1]; }
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
    std::vector<T> buf_;
    std::size_t start_ = 0, size_ = 0;
};

// Writes t,x,v,phi,omega,regime,bumper_force,energy,epoch; returns false if the file cannot be written.
bool write_trajectory_csv(const std::string& path, const History<SimMsg>& h, const std::string& model);
// Writes n,t,x,v,omega,regime.
bool write_sections_csv(const std::string& path, const History<SimMsg>& s, const std::string& model);

}  // namespace impactlab::gui
