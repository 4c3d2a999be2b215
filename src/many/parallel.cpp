// The worker pool (include/ellipsect/parallel.hpp).
#include <ellipsect/parallel.hpp>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>

#include <unistd.h>

namespace ellipsect {
namespace {

// The pool (parallel.hpp): the work is shared through an atomic counter, so when the caller
// is done there is nothing left for workers that have not woken up yet.
class Workers {
public:
  static Workers& get() {
    static Workers* const pool = new Workers();  // never destroyed: workers wait in it until exit
    return *pool;
  }

  // work() on the caller and on up to `extra` workers; returns once every one that began has returned.
  template <class Work>
  void run(std::size_t extra, const Work& work) {
    if (extra == 0 || getpid() != owner_) return work();
    std::unique_lock busy(busy_, std::try_to_lock);
    if (!busy) return work();
    const std::function<void()> job = [&work] { work(); };
    {
      std::lock_guard lock(mutex_);
      job_ = &job;
      wanted_ = std::min(extra, threads_);
      taken_ = 0;
      ++generation_;
    }
    wake_.notify_all();
    struct Join {  // also where work() throws: the workers hold references to it
      Workers& pool;
      ~Join() {
        std::unique_lock lock(pool.mutex_);
        pool.wanted_ = pool.taken_;  // those not yet awake stay out
        pool.done_.wait(lock, [&] { return pool.running_ == 0; });
      }
    } join{*this};
    work();
  }

private:
  Workers() : owner_(getpid()), threads_(std::max(1u, std::thread::hardware_concurrency()) - 1) {
    for (std::size_t i = 0; i < threads_; ++i) std::thread([this] { loop(); }).detach();
  }

  void loop() {
    std::uint64_t seen = 0;
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (taken_ >= wanted_) continue;
      ++taken_;
      ++running_;
      const std::function<void()>* job = job_;
      lock.unlock();
      (*job)();
      lock.lock();
      if (--running_ == 0) done_.notify_all();
    }
  }

  const pid_t owner_;  // the process whose threads these are
  const std::size_t threads_;
  std::mutex busy_;   // held by the call using the pool
  std::mutex mutex_;  // guards the fields below
  std::condition_variable wake_, done_;
  std::uint64_t generation_ = 0;
  std::size_t wanted_ = 0, taken_ = 0, running_ = 0;
  const std::function<void()>* job_ = nullptr;
};

// Set on the threads running a call's work: a call from there runs alone (the pool is held).
thread_local bool in_pool = false;

}  // namespace

namespace detail {

void run_on_pool(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    const bool nested = in_pool;
    in_pool = true;
    for (std::size_t k; (k = next.fetch_add(1)) < count;) {
      try {
        body(k);
      } catch (...) {
        const std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(count);
      }
    }
    in_pool = nested;
  };
  const std::size_t wanted = std::min(threads > 0 ? std::size_t(threads) : count, count);
  if (wanted <= 1 || in_pool) {
    work();
  } else {
    Workers::get().run(wanted - 1, work);
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace detail
}  // namespace ellipsect
