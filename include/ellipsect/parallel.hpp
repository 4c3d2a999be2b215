// The library's worker pool: the batch queries (batch.hpp), the Python package and the
// ellipsect program all run their parallel work on it.
//
// The workers, one per hardware thread beyond the caller's, start on first use and are kept
// (starting threads on each call cost about a fifth of a 16,384-pair overlap batch on 2
// cores, bench/RESULTS.md). One call holds the pool at a time: a call that finds it held
// (from another thread, or from inside a body) runs on its caller alone, as does every call
// in a forked child, where the workers do not exist. The caller takes part, and when the
// work runs out, workers that have not woken up yet are no longer waited for: a call never
// waits for a wake-up.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>

namespace ellipsect {

namespace detail {
void run_on_pool(std::size_t count, int threads, const std::function<void(std::size_t)>& body);
}  // namespace detail

// body(k) once for every k in [0, count), on up to `threads` threads (0: every hardware
// thread; 1: the caller alone), which take the k in turn: body must write only its own
// outputs, and results then do not depend on the thread count. An exception thrown by a
// body stops the handing out of further k; the first one is rethrown on the caller once
// every running body has returned.
template <class Body>
void parallel_for(std::size_t count, int threads, Body&& body) {
  if (threads == 1 || count <= 1) {
    for (std::size_t k = 0; k < count; ++k) body(k);
    return;
  }
  detail::run_on_pool(count, threads, std::function<void(std::size_t)>(std::ref(body)));
}

}  // namespace ellipsect
