// dec/detail/threads.h — how the library runs work on threads: a requested thread count resolved
// (0: all hardware threads), and a job run on threads 0..T-1 (0 on the calling thread), all
// joined before returning. Every threaded routine gives results independent of T.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <utility>
#include <vector>

namespace polydec {

// `requested` threads, or the hardware's count for 0; at least 1.
inline int resolve_threads(int requested) {
  return std::max(1, requested > 0 ? requested : int(std::thread::hardware_concurrency()));
}

// Calls job(t) for t = 0..T-1, job(0) on the calling thread, and waits for all.
template <class Job>
void run_on_threads(int T, Job&& job) {
  std::vector<std::jthread> workers;
  for (int t = 1; t < T; ++t) workers.emplace_back(job, t);
  job(0);
}

// Part k of n items cut into `parts` contiguous ranges: [n k / parts, n (k + 1) / parts).
inline std::pair<long, long> part_of(long n, int k, int parts) {
  return {n * k / parts, n * (k + 1) / parts};
}

// Calls item(i) for the items of [0, n) in chunks of `chunk` taken from `next` by whichever thread
// is free, ascending within a chunk: a thread slowed by other processes or by memory takes fewer
// chunks (fixed halves would make the other thread wait for it). Each item's result must not depend
// on which thread runs it.
template <class Item>
void take_chunks(std::atomic<long>& next, long n, long chunk, Item&& item) {
  for (long lo = next.fetch_add(chunk); lo < n; lo = next.fetch_add(chunk))
    for (long i = lo; i < std::min(n, lo + chunk); ++i) item(i);
}

}  // namespace polydec
