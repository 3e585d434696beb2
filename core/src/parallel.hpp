// Independent evaluations (the fit's held-out windows, the continuation's maps at a few points, a tangent's
// pieces) spread over the machine's cores.
// Each index is computed by exactly one thread into its own slot, so results never depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace impactlab::detail {

// A fixed set of worker threads (one fewer than the cores) that help whoever calls run(): starting threads
// for every batch cost more than a short batch (a period's tangent) gains. A batch started from inside
// another's index (nested) is helped by the idle workers the same way.
class WorkPool {
public:
    static WorkPool& instance() {
        static WorkPool pool;
        return pool;
    }
    WorkPool(const WorkPool&) = delete;
    WorkPool& operator=(const WorkPool&) = delete;
    ~WorkPool() {
        {
            const std::lock_guard<std::mutex> lock(m_);
            stop_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : threads_) t.join();
    }

    // Calls fn(i) for i in [0, n) on the calling thread and any idle workers; returns when all are done. The
    // first exception thrown (a cancel, say) stops the handing out of indices and is rethrown here.
    // Calling thread: any, workers included.
    void run(std::size_t n, const std::function<void(std::size_t)>& fn) {
        if (threads_.empty() || n <= 1) {
            for (std::size_t i = 0; i < n; ++i) fn(i);
            return;
        }
        Batch b(n, fn);
        {
            const std::lock_guard<std::mutex> lock(m_);
            open_.push_back(&b);
        }
        wake_.notify_all();
        drain(b);
        {
            std::unique_lock<std::mutex> lock(m_);
            close(&b);
            left_.wait(lock, [&] { return b.users == 0; });
        }
        if (b.error) std::rethrow_exception(b.error);
    }

private:
    struct Batch {
        Batch(std::size_t count, const std::function<void(std::size_t)>& f) : n(count), fn(&f) {}
        std::size_t n;
        const std::function<void(std::size_t)>* fn;
        std::atomic<std::size_t> next{0};
        std::atomic<bool> failed{false};
        int users = 0;   // workers inside drain (guarded by the pool's mutex)
        std::exception_ptr error;
        std::mutex error_mutex;
    };

    WorkPool() {
        const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
        for (unsigned i = 1; i < cores; ++i) threads_.emplace_back([this] { work(); });
    }

    static void drain(Batch& b) {
        for (std::size_t i; !b.failed.load(std::memory_order_relaxed) && (i = b.next.fetch_add(1)) < b.n;) {
            try {
                (*b.fn)(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(b.error_mutex);
                if (!b.error) b.error = std::current_exception();
                b.failed = true;
            }
        }
    }
    // Takes b off the open list (the pool's mutex held): no worker joins it after this.
    void close(Batch* b) {
        const auto it = std::find(open_.begin(), open_.end(), b);
        if (it != open_.end()) open_.erase(it);
    }

    void work() {
        std::unique_lock<std::mutex> lock(m_);
        while (true) {
            wake_.wait(lock, [&] { return stop_ || !open_.empty(); });
            if (stop_) return;
            Batch* b = open_.front();
            ++b->users;
            lock.unlock();
            drain(*b);
            lock.lock();
            close(b);   // handed out in full (or failed)
            if (--b->users == 0) left_.notify_all();
        }
    }

    std::mutex m_;
    std::condition_variable wake_, left_;
    std::deque<Batch*> open_;
    bool stop_ = false;
    std::vector<std::thread> threads_;
};

// Calls fn(i) for i in [0, n) on up to hardware_concurrency threads (the caller's among them). The first
// exception thrown (a cancel, say) stops the handing out of indices and is rethrown on the caller's thread.
template <class Fn>
void for_each_index(std::size_t n, Fn&& fn) {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
    for (std::size_t i = 0; i < n; ++i) fn(i);   // the browser page is built without threads
#else
    WorkPool::instance().run(n, std::function<void(std::size_t)>(std::ref(fn)));
#endif
}

}  // namespace impactlab::detail
